//! The scene the servo, device and view tests and examples share: one sphere of the
//! shape catalog at the origin; a scene of any one shape; a model scaled to a hand's
//! size, as `haphe verify` checks the proxy on it.

use std::sync::Arc;

use crate::map::MapOptions;
use crate::mesh::shapes::Catalog;
use crate::mesh::{Mesh, Surface, SurfaceOptions};
use crate::scene::{EditError, Material, ObjectId, Pose, Scene, SceneObject, Shape};

/// A scene of one object, [`ObjectId`] 0: the catalog's sphere of about `triangles`
/// triangles at the origin with `material`, its map and clear zones built (so that no
/// tick builds them), room for one more object.
///
/// # Errors
/// What building the surface or the map says (not expected of the catalog's sphere).
pub fn sphere_scene(
    triangles: usize,
    material: Material,
) -> Result<Scene, Box<dyn std::error::Error + Send + Sync>> {
    let surface = Surface::new(
        Catalog::Sphere.with_triangles(triangles),
        &SurfaceOptions::default(),
    )?;
    let shape = Arc::new(Shape::build(surface, &MapOptions::default())?);
    shape.prepare_clear_zones();
    Ok(one_object_scene(shape, material, 2)?)
}

/// A scene of one object, [`ObjectId`] 0: `shape` at the origin with `material`, room
/// for `capacity` objects in all.
///
/// # Errors
/// [`EditError::Full`] when `capacity` is 0.
pub fn one_object_scene(
    shape: Arc<Shape>,
    material: Material,
    capacity: usize,
) -> Result<Scene, EditError> {
    let mut scene = Scene::local(capacity);
    scene
        .insert(SceneObject::new(
            ObjectId(0),
            shape,
            Pose::IDENTITY,
            material,
        ))
        .map_err(|(e, _)| e)?;
    Ok(scene)
}

/// Size a model is scaled to for the proxy checks of `haphe verify`, metres: device
/// speeds (m/s) and depths mean something only at the scale of a hand.
pub const HAND_SCALE_M: f64 = 0.2;

/// The mesh of `surface` scaled to a hand's size: its largest side [`HAND_SCALE_M`], its
/// lowest corner at the origin; and the scale.
pub fn hand_sized(surface: &Surface) -> (Mesh, f64) {
    let (lo, hi, _) = super::bounds(surface);
    let scale = HAND_SCALE_M / (hi - lo).max_element();
    let mesh = Mesh {
        vertices: surface
            .vertices()
            .iter()
            .map(|&v| (v - lo) * scale)
            .collect(),
        triangles: surface.triangles().to_vec(),
    };
    (mesh, scale)
}
