//! What the stage 4–6 benches share: the size of their meshes and paths, and scenes of one
//! shape with its clear zones computed, as a servo application prepares them.

// Each bench uses a part of this module.
#![allow(dead_code)]

use std::sync::Arc;

use haphe::map::MapOptions;
use haphe::mesh::shapes::Catalog;
use haphe::mesh::{Surface, SurfaceOptions};
use haphe::scene::{Material, ObjectId, Pose, Scene, SceneObject, Shape};

/// Triangles of each benchmark mesh.
pub const TRIANGLES: usize = 10_000;
/// Device points of each path's cycle (ten seconds at 1 kHz).
pub const TICKS: usize = 10_000;
/// The servo rate, Hz.
pub const RATE_HZ: f64 = 1000.0;

/// A scene of one shape at the origin, its clear zones computed as a servo application
/// does when it loads a shape.
pub fn scene_of(surface: Surface) -> Scene {
    let shape = Shape::build(surface, &MapOptions::default()).expect("the map builds");
    shape.prepare_clear_zones();
    scene_with(Arc::new(shape))
}

/// A scene of the shared `shape` at the origin.
pub fn scene_with(shape: Arc<Shape>) -> Scene {
    let mut scene = Scene::local(4);
    let object = SceneObject::new(ObjectId(0), shape, Pose::IDENTITY, Material::default());
    scene
        .insert(object)
        .map_err(|(e, _)| e)
        .expect("room for it");
    scene
}

/// A scene of a procedural shape of [`TRIANGLES`] triangles at the origin.
pub fn procedural(which: Catalog) -> Scene {
    let surface = Surface::new(which.with_triangles(TRIANGLES), &SurfaceOptions::default())
        .expect("a valid surface");
    scene_of(surface)
}
