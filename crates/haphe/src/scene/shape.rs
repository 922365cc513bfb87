//! Shapes: a surface and its voxel map, built once and shared by every object that uses it.

use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};

use glam::{DVec2, DVec3};

use crate::map::{MapError, MapOptions, VoxelMap};
use crate::mesh::{
    Mesh, ReadError, ReadOptions, Surface, SurfaceError, SurfaceOptions, TriId,
    read_mesh_with_stats,
};
use crate::query::{ClearZone, zone_from_bits, zone_height};

use super::Material;
use super::texture_coords::{self, UvPoint};

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
    /// Texture coordinates given for another number of triangles than the shape has.
    #[error("texture coordinates for {given} triangles, but the shape has {triangles} triangles")]
    TextureCoordsCount {
        /// How many triangles the coordinates were given for.
        given: usize,
        /// How many the shape has.
        triangles: usize,
    },
    /// A texture coordinate is NaN or infinite.
    #[error("triangle {triangle}, corner {corner}: a texture coordinate is not a finite number")]
    TextureCoordNotFinite {
        /// The triangle, as numbered in the mesh the shape was made from.
        triangle: usize,
        /// The corner (0, 1 or 2).
        corner: usize,
    },
}

/// An immutable collision shape: a [`Surface`] with its [`VoxelMap`] and a bounding sphere,
/// in the object frame. Shared between objects (and threads) behind an
/// [`Arc`](std::sync::Arc); the geometry never changes after it is built. The only thing
/// that does is a cache: each triangle's [`ClearZone`], computed the first time a proxy
/// slides on the triangle (or all at once by [`Shape::prepare_clear_zones`]) and kept in
/// an atomic slot (8 bytes a triangle), so that reading it takes no lock.
///
/// A shape may carry texture coordinates at its triangles' corners (read from the mesh
/// file by [`Shape::read`], or given by [`Shape::with_texture_coords`]), which image
/// textures follow: 48 bytes more a triangle.
#[derive(Debug)]
pub struct Shape {
    pub(super) surface: Surface,
    pub(super) map: VoxelMap,
    pub(super) bound_centre: DVec3,
    pub(super) bound_radius: f64,
    /// Packed [`ClearZone`] per triangle, 0 until computed.
    pub(super) zones: Box<[AtomicU64]>,
    pub(super) zone_height: f32,
    /// `[u, v]` at each corner of each surface triangle, in the surface's order.
    pub(super) texture_coords: Option<Arc<[[DVec2; 3]]>>,
    /// The material of each triangle where the shape's own material varies over it (a
    /// cut volume's layers); else the object's material holds everywhere.
    pub(super) materials: Option<Arc<TriangleMaterials>>,
    /// How many deformations or re-meshes made this shape from the one first built.
    pub(super) version: u64,
    /// The first build's surface uid, kept by every later version (see
    /// [`Shape::replacing`]).
    pub(super) lineage: u64,
    /// Made by [`Shape::replacing`]: other triangles than the version before.
    pub(super) remeshed: bool,
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
            map,
            bound_centre,
            bound_radius,
            zones,
            zone_height,
            lineage: surface.uid(),
            surface,
            texture_coords: None,
            materials: None,
            version: 0,
            remeshed: false,
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
    /// told apart by content) and makes its shape as [`Shape::from_mesh`] does, with the
    /// file's texture coordinates when it has them for every corner
    /// ([`ReadMesh::texture_coords`](crate::mesh::ReadMesh::texture_coords)): each surface
    /// corner takes the coordinate of the file's corner at its place.
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
        let texture = loaded.texture_coords.map(|uvs| {
            let corners: Vec<[DVec3; 3]> = (0..loaded.mesh.triangles.len())
                .map(|t| loaded.mesh.corners(t))
                .collect();
            (widen(&uvs), corners)
        });
        let shape = Shape::from_mesh(file, loaded.mesh, options)?;
        match texture {
            Some((uvs, corners)) => shape.attach_texture_coords(&uvs, Some(&corners)),
            None => Ok(shape),
        }
    }

    /// The shape with texture coordinates `[u, v]` at its triangles' corners (`v`
    /// pointing up the image: `v = 0` is its bottom row), for a shape made from a mesh of
    /// one's own: entry `t` is for triangle `t` of the mesh given to [`Surface::new`] (or
    /// [`Shape::from_mesh`]), its corners in that triangle's order. Replaces any the shape
    /// had.
    ///
    /// # Errors
    /// [`ShapeError::TextureCoordsCount`] when the length is not the number of triangles;
    /// [`ShapeError::TextureCoordNotFinite`] naming the first triangle and corner with a
    /// NaN or infinite coordinate.
    ///
    /// # Examples
    /// ```
    /// use haphe::map::MapOptions;
    /// use haphe::mesh::shapes;
    /// use haphe::scene::Shape;
    /// let mesh = shapes::sphere(0.05, 1);
    /// let triangles = mesh.triangles.len();
    /// let shape = Shape::from_mesh("cube", mesh, &MapOptions::default()).unwrap();
    /// assert!(!shape.has_texture_coords());
    /// let shape = shape
    ///     .with_texture_coords(vec![[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]; triangles])
    ///     .unwrap();
    /// assert!(shape.has_texture_coords());
    /// ```
    pub fn with_texture_coords(
        self,
        per_loaded_triangle: Vec<[[f64; 2]; 3]>,
    ) -> Result<Shape, ShapeError> {
        self.attach_texture_coords(&per_loaded_triangle, None)
    }

    /// The shape with `per_loaded` texture coordinates, checked, in the surface's order
    /// (see [`texture_coords::in_surface_order`]).
    fn attach_texture_coords(
        self,
        per_loaded: &[[[f64; 2]; 3]],
        loaded_corners: Option<&[[DVec3; 3]]>,
    ) -> Result<Shape, ShapeError> {
        let triangles = self.surface.triangle_count();
        if per_loaded.len() != triangles || loaded_corners.is_some_and(|c| c.len() != triangles) {
            return Err(ShapeError::TextureCoordsCount {
                given: per_loaded.len(),
                triangles,
            });
        }
        for (triangle, uvs) in per_loaded.iter().enumerate() {
            if let Some(corner) = uvs.iter().position(|uv| !uv.iter().all(|x| x.is_finite())) {
                return Err(ShapeError::TextureCoordNotFinite { triangle, corner });
            }
        }
        let in_order = texture_coords::in_surface_order(&self.surface, per_loaded, loaded_corners);
        Ok(Shape {
            texture_coords: Some(in_order.into()),
            ..self
        })
    }

    /// Whether the shape has texture coordinates (so that an image texture can follow
    /// them).
    pub fn has_texture_coords(&self) -> bool {
        self.texture_coords.is_some()
    }

    /// The texture coordinate at barycentric `weights` of triangle `t`, with the gradients
    /// of `u` and `v` over its plane (object frame). `None` without texture coordinates,
    /// for `t` out of range, and where the triangle's texture map is degenerate (no area
    /// in 3D or in the image).
    ///
    /// # Real-time
    /// No allocation, no lock, no panic; a few dozen flops.
    #[inline]
    pub(crate) fn uv_at(&self, t: TriId, weights: [f64; 3]) -> Option<UvPoint> {
        let uvs = self.texture_coords.as_deref()?.get(t.index())?;
        texture_coords::uv_at(self.surface.frame(t), uvs, weights)
    }

    /// The shape with every triangle's clear zone computed ([`Shape::prepare_clear_zones`]):
    /// for a surface and map loaded from a file, as [`Shape::from_mesh`] does for a mesh.
    pub fn with_clear_zones(self) -> Shape {
        self.prepare_clear_zones();
        self
    }

    /// This shape as the next version of `previous`, with other triangles: the surface of
    /// a volume the tool cut into, extracted again. [`Edit::SetShape`](super::Edit::SetShape)
    /// and [`Scene::replace`](super::Scene::replace) accept it for an object whose shape
    /// is `previous` (or another version of the same first build); a proxy resting on the
    /// object then forgets the triangle it rested on (it does not ride, as it does on a
    /// deformation) and is pushed out if the new surface lies over it.
    pub fn replacing(mut self, previous: &Shape) -> Shape {
        self.lineage = previous.lineage;
        self.version = previous.version + 1;
        self.remeshed = true;
        self
    }

    /// The shape with `palette[of[t]]` the material of the triangle `t` of the mesh it
    /// was made from (in that mesh's order), over the material of any object using it. An
    /// index beyond the palette, or a triangle beyond `of`, keeps the object's.
    pub(crate) fn with_triangle_materials(self, palette: Vec<Material>, of: &[u16]) -> Shape {
        let in_order = self
            .surface
            .source_triangles()
            .iter()
            .map(|&s| of.get(s as usize).copied().unwrap_or(u16::MAX))
            .collect();
        let softest = palette
            .iter()
            .copied()
            .min_by(|a, b| a.stiffness.total_cmp(&b.stiffness))
            .unwrap_or_default();
        Shape {
            materials: Some(Arc::new(TriangleMaterials {
                palette: palette.into(),
                of: in_order,
                softest,
            })),
            ..self
        }
    }

    /// How triangle `t` feels: the shape's own material there
    /// ([`Shape::with_triangle_materials`]), else `object`'s (the material of the object
    /// using the shape).
    ///
    /// # Real-time
    /// Two bounds-checked reads; no allocation, no panic.
    #[inline]
    pub(crate) fn material_on<'a>(&'a self, t: TriId, object: &'a Material) -> &'a Material {
        self.materials
            .as_deref()
            .and_then(|m| m.palette.get(usize::from(*m.of.get(t.index())?)))
            .unwrap_or(object)
    }

    /// The material whose saturation depth starts and keeps a hold: the softest of the
    /// shape's own materials (so that a hold begins only where the force saturates on
    /// every triangle), else `object`'s.
    #[inline]
    pub(crate) fn hold_material<'a>(&'a self, object: &'a Material) -> &'a Material {
        self.materials.as_deref().map_or(object, |m| &m.softest)
    }

    /// Whether this shape was made by [`Shape::replacing`] (other triangles than the
    /// version before it; for the oracles).
    #[cfg(any(test, feature = "testing"))]
    pub(crate) fn is_remesh(&self) -> bool {
        self.remeshed
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

/// A material per triangle: an index into a palette, in the surface's order.
#[derive(Debug)]
pub(crate) struct TriangleMaterials {
    palette: Box<[Material]>,
    of: Box<[u16]>,
    /// The palette's material of least stiffness.
    softest: Material,
}

/// Texture coordinates as read (`f32`) in the shape's precision.
fn widen(uvs: &[[[f32; 2]; 3]]) -> Vec<[[f64; 2]; 3]> {
    uvs.iter().map(|t| t.map(|uv| uv.map(f64::from))).collect()
}
