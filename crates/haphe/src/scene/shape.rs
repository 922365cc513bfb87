//! Shapes: a surface and its voxel map, built once and shared by every object that uses it.

use glam::DVec3;

use crate::map::{MapError, MapOptions, VoxelMap};
use crate::mesh::Surface;

/// An immutable collision shape: a [`Surface`] with its [`VoxelMap`] and a bounding sphere,
/// in the object frame. Shared between objects (and threads) behind an
/// [`Arc`](std::sync::Arc); nothing in it changes after it is built.
#[derive(Debug)]
pub struct Shape {
    surface: Surface,
    map: VoxelMap,
    bound_centre: DVec3,
    bound_radius: f64,
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
        Shape {
            surface,
            map,
            bound_centre,
            bound_radius,
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
}
