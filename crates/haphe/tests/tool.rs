//! The sphere proxy — a tool of radius r — against the brute-force tool proxy, and the
//! geometry a tool with a size must get right: gaps narrower than it, channels wider than
//! it, resting in concave corners, smooth sliding over convex edges, deep strikes.

mod support;

use std::sync::Arc;

use haphe::DVec3;
use haphe::map::MapOptions;
use haphe::mesh::shapes::{self, Catalog};
use haphe::mesh::{Mesh, Surface, SurfaceOptions};
use haphe::proxy::{Proxy, ProxyOptions};
use haphe::scene::{Material, ObjectId, Pose, Scene, SceneObject, Shape};
use haphe::verify::{
    check_proxy, check_strikes, distance_to_surface, haptic_path, haptic_path_in_contact,
    one_object_scene,
};

fn shape(mesh: Mesh) -> Arc<Shape> {
    let surface = Surface::new(mesh, &SurfaceOptions::default()).expect("a usable surface");
    Arc::new(Shape::build(surface, &MapOptions::default()).expect("a map"))
}

fn friction() -> Material {
    Material::builder()
        .stiffness(800.0)
        .damping(1.0)
        .friction(0.6, 0.4)
        .build()
        .expect("a valid material")
}

fn tool(radius: f64) -> ProxyOptions {
    ProxyOptions::default()
        .with_tool_radius(radius)
        .expect("a radius in its domain")
}

/// The largest side of a scene's first object, metres.
fn size(scene: &Scene) -> f64 {
    let (lo, hi) = scene.objects()[0].shape.surface().bounds();
    (hi - lo).max_element()
}

/// Explore and steady-contact paths over `scene`, the fast tool proxy against the
/// brute-force one at every tick, at r = 0.5 mm, 2 mm and 1 % of the object's size.
fn check_tool(name: &str, scene: &Scene, ticks: usize, seed: u64) {
    for radius in [0.5e-3, 2e-3, 0.01 * size(scene)] {
        let explore = haptic_path(scene, ticks, (0.01, 2.0), 1e3, seed);
        let press = haptic_path_in_contact(scene, ticks, (0.05, 0.5), (0.5e-3, 3e-3), 1e3, seed);
        for (kind, path) in [("explore", explore), ("contact", press)] {
            let check = check_proxy(scene, &path, tool(radius));
            println!("{name} r {radius} {kind}: {check:?}");
            assert!(
                check.contact_ticks > ticks / 10,
                "{name} r {radius} {kind}: too little contact: {check:?}"
            );
            assert_eq!(check.mismatches, 0, "{name} r {radius} {kind}: {check:?}");
            assert_eq!(check.inside, 0, "{name} r {radius} {kind}: {check:?}");
            assert_eq!(check.bad_forces, 0, "{name} r {radius} {kind}: {check:?}");
        }
    }
}

#[test]
fn tool_equals_brute_force_on_procedural_shapes() {
    for (k, which) in Catalog::ALL.into_iter().enumerate() {
        let scene = one_object_scene(shape(which.with_triangles(2_000)), friction(), 4)
            .expect("room");
        check_tool(&which.to_string(), &scene, 2_000, 31 + k as u64);
    }
}
