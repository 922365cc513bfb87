//! Shapes: a surface and its voxel map, built once and shared by every object that uses it.

use std::sync::atomic::{AtomicU64, Ordering};

use glam::DVec3;

use crate::map::{MapError, MapOptions, VoxelMap};
use crate::mesh::{
    Mesh, ReadError, ReadOptions, Surface, SurfaceError, SurfaceOptions, TriId,
    read_mesh_with_stats,
};
use crate::query::{ClearZone, zone_from_bits, zone_height};

/// Why a mesh could not become a [`Shape`]: its file is not a mesh, or the mesh has no
/// usable surface, or its map cannot be built. The last two name the mesh.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ShapeError {
    /// The bytes are not a mesh (the error names the file and the place).
    #[error(transparent)]
    Read(#[from] ReadError),
    /// The mesh cannot become a [`Surface`].
    #[error("{name}: {source}")]
    Surface {
        /// The mesh's name (its file, or what the caller calls it).
        name: String,
        /// What is wrong.
        source: SurfaceError,
    },
    /// The map of the surface cannot be built.
    #[error("{name}: {source}")]
    Map {
        /// The mesh's name.
        name: String,
        /// What is wrong.
        source: MapError,
    },
}

/// An immutable collision shape: a [`Surface`] with its [`VoxelMap`] and a bounding sphere,
/// in the object frame. Shared between objects (and threads) behind an
/// [`Arc`](std::sync::Arc); the geometry never changes after it is built. The only thing
/// that does is a cache: each triangle's [`ClearZone`], computed the first time a proxy
/// slides on the triangle (or all at once by [`Shape::prepare_clear_zones`]) and kept in
/// an atomic slot (8 bytes a triangle), so that reading it takes no lock.
#[derive(Debug)]
pub struct Shape {
    surface: Surface,
    map: VoxelMap,
    bound_centre: DVec3,
    bound_radius: f64,
    /// Packed [`ClearZone`] per triangle, 0 until computed.
    zones: Box<[AtomicU64]>,
    zone_height: f32,
}

impl Shape {
    /// A shape from a surface and the map built for it (for example both from
    /// [`decode`](crate::map::decode)).
    pub fn new(surface: Surface, map: VoxelMap) -> Shape {
        let report = surface.report();
        let bound_centre =
            0.5 * (DVec3::from_array(report.bounds_min) + DVec3::from_array(report.bounds_max));
        let bound_radius = surface
            .vertices()
            .iter()
            .map(|v| v.distance(bound_centre))
            .fold(0.0, f64::max);
        let zones = (0..surface.triangle_count())
            .map(|_| AtomicU64::new(0))
            .collect();
        let zone_height = zone_height(&map);
        Shape {
            surface,
            map,
            bound_centre,
            bound_radius,
            zones,
            zone_height,
        }
    }

    /// Builds the voxel map of `surface` and makes the shape.
    ///
    /// # Errors
    /// Those of [`VoxelMap::build`].
    pub fn build(surface: Surface, options: &MapOptions) -> Result<Shape, MapError> {
        let map = VoxelMap::build(&surface, options)?;
        Ok(Shape::new(surface, map))
    }

    /// The shape of `mesh` ready for a servo loop, the recipe every front end follows: its
    /// [`Surface`] (default [`SurfaceOptions`]), its [`VoxelMap`] and every triangle's
    /// clear zone computed now ([`Shape::prepare_clear_zones`]), so that no tick computes
    /// one. `name` (a file, or what the caller calls the mesh) is in the errors.
    ///
    /// # Errors
    /// [`ShapeError::Surface`] (no triangle with area, or an invalid hand-built mesh) or
    /// [`ShapeError::Map`] (map options out of range, a grid too large).
    pub fn from_mesh(name: &str, mesh: Mesh, options: &MapOptions) -> Result<Shape, ShapeError> {
        let surface = Surface::new(mesh, &SurfaceOptions::default()).map_err(|source| {
            ShapeError::Surface {
                name: name.to_owned(),
                source,
            }
        })?;
        let shape = Shape::build(surface, options).map_err(|source| ShapeError::Map {
            name: name.to_owned(),
            source,
        })?;
        Ok(shape.with_clear_zones())
    }

    /// Reads the mesh file `file` whose contents are `bytes` (the format from `read`, or
    /// told apart by content) and makes its shape as [`Shape::from_mesh`] does.
    ///
    /// # Errors
    /// [`ShapeError::Read`] naming the file and the place, or those of
    /// [`Shape::from_mesh`].
    pub fn read(
        file: &str,
        bytes: &[u8],
        read: &ReadOptions,
        options: &MapOptions,
    ) -> Result<Shape, ShapeError> {
        let loaded = read_mesh_with_stats(file, bytes, read)?;
        Shape::from_mesh(file, loaded.mesh, options)
    }

    /// The shape with every triangle's clear zone computed ([`Shape::prepare_clear_zones`]):
    /// for a surface and map loaded from a file, as [`Shape::from_mesh`] does for a mesh.
    pub fn with_clear_zones(self) -> Shape {
        self.prepare_clear_zones();
        self
    }

    /// The surface (object frame, metres).
    pub fn surface(&self) -> &Surface {
        &self.surface
    }

    /// The voxel map of the surface.
    pub fn map(&self) -> &VoxelMap {
        &self.map
    }

    /// Whether the shape is a closed solid (else a two-sided surface).
    pub fn is_solid(&self) -> bool {
        self.surface.is_solid()
    }

    /// Centre of a sphere holding every vertex, metres, object frame.
    pub fn bound_centre(&self) -> DVec3 {
        self.bound_centre
    }

    /// Radius of that sphere, metres.
    pub fn bound_radius(&self) -> f64 {
        self.bound_radius
    }

    /// The clear zone of triangle `t` ([`ClearZone::NONE`] when out of range), computed on
    /// first use and cached.
    ///
    /// # Real-time
    /// No lock, no allocation, no panic. A cached zone costs one atomic load; the first
    /// call for a triangle computes it ([`ClearZone::of`]: at most
    /// [`MAX_ZONE_CELLS`](crate::query::MAX_ZONE_CELLS) cells read). Two threads computing
    /// the same zone at once store the same value.
    #[doc(hidden)]
    #[inline]
    pub fn clear_zone(&self, t: TriId) -> ClearZone {
        let Some(slot) = self.zones.get(t.index()) else {
            return ClearZone::NONE;
        };
        let bits = slot.load(Ordering::Relaxed);
        if bits != 0 {
            return zone_from_bits(bits, self.zone_height);
        }
        let zone = ClearZone::of(&self.surface, &self.map, t);
        slot.store(zone.to_bits(), Ordering::Relaxed);
        zone
    }

    /// Computes every triangle's clear zone now, on every core (rayon, feature `parallel`),
    /// so that no tick computes one: for a servo loop that must keep its worst tick short
    /// from the first contact on. Returns how many zones were computed (those not cached
    /// yet).
    pub fn prepare_clear_zones(&self) -> usize {
        use crate::par::*;
        (0..self.zones.len())
            .into_par_iter()
            .filter(|&t| self.zones[t].load(Ordering::Relaxed) == 0)
            .inspect(|&t| {
                self.clear_zone(TriId(t as u32));
            })
            .count()
    }
}
