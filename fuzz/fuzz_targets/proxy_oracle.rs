//! Fuzzes the proxy against the brute-force proxy: a procedural mesh chosen by the input,
//! a material, and a device path from the input (points on a grid that hits vertices and
//! edges of axis-aligned shapes exactly, non-finite and huge values mixed in). At every
//! tick the fast proxy must equal the brute-force one, its force must be finite and within
//! the maximum, and it must never be inside a solid deeper than its skin.
#![no_main]

use std::sync::Arc;

use haphe::DVec3;
use haphe::map::MapOptions;
use haphe::mesh::shapes::Catalog;
use haphe::mesh::{Surface, SurfaceOptions};
use haphe::proxy::{Proxy, ProxyOptions};
use haphe::query::{Side, classify_point};
use haphe::scene::{Material, ObjectId, Pose, Scene, SceneObject, Shape};
use haphe::verify::{BruteProxy, PROXY_TOLERANCE_M, distance_to_surface};
use libfuzzer_sys::fuzz_target;

/// A coordinate in [-0.15, 0.15] m from 2 bytes; the top values stand for bad input.
fn coordinate(bytes: &[u8]) -> f64 {
    match u16::from_le_bytes([bytes[0], bytes[1]]) {
        u16::MAX => f64::NAN,
        0xFFFE => 1e300,
        v => (f64::from(v) / 65533.0 - 0.5) * 0.3,
    }
}

fuzz_target!(|bytes: &[u8]| {
    if bytes.len() < 4 {
        return;
    }
    let which = Catalog::ALL[bytes[0] as usize % Catalog::ALL.len()];
    let triangles = 20 + 40 * usize::from(bytes[1] % 8);
    let Ok(surface) = Surface::new(which.with_triangles(triangles), &SurfaceOptions::default())
    else {
        return;
    };
    let Ok(shape) = Shape::build(surface, &MapOptions::default()) else {
        return;
    };
    let friction = f64::from(bytes[2]) / 255.0;
    let material = Material::builder().stiffness(500.0).damping(1.0).friction(friction, 0.6 * friction).build().expect("a valid material");
    let mut scene = Scene::local(1);
    let object = SceneObject::new(ObjectId(0), Arc::new(shape), Pose::IDENTITY, material);
    if scene.insert(object).is_err() {
        return;
    }
    let options = ProxyOptions::default();
    let start = DVec3::new(0.0, 0.0, 0.3);
    let mut fast = Proxy::new(start, options);
    let mut brute = BruteProxy::new(&scene, start, options);
    let o = &scene.objects()[0];
    for chunk in bytes[3..].chunks_exact(6) {
        let hip = DVec3::new(
            coordinate(&chunk[0..2]),
            coordinate(&chunk[2..4]),
            coordinate(&chunk[4..6]),
        );
        let out = fast.tick(&scene, hip, DVec3::ZERO);
        let (b, b_contact) = brute.tick(hip);
        assert!(
            out.proxy.distance(b) <= PROXY_TOLERANCE_M && out.contact.is_some() == b_contact,
            "{which}: fast {out:?}, brute {b} ({b_contact})"
        );
        assert!(out.force.is_finite() && out.force.length() <= options.max_force() * (1.0 + 1e-12));
        if o.shape.is_solid()
            && classify_point(o.shape.surface(), o.shape.map(), out.proxy).0 == Side::Inside
        {
            assert!(
                distance_to_surface(o.shape.surface(), out.proxy) <= options.skin(),
                "{which}: proxy inside at {}",
                out.proxy
            );
        }
    }
});
