//! Deep penetration: beyond the saturation depth the proxy holds where it was, so the
//! force never pulls the hand on through a thick object.

use haphe::DVec3;
use haphe::mesh::shapes::Catalog;
use haphe::proxy::{Proxy, ProxyOptions};
use haphe::scene::Material;
use haphe::verify::{
    STRIKE_FORCE_TOLERANCE_N, StrikeCheck, check_proxy, check_strikes, strike_path,
};

use super::{fit_to_hand_size, scene_of, shape, support};

/// The strike of the deep-penetration report: the hand held 3 cm above a 0.2 m sphere
/// (20 000 triangles) for 0.1 s, then driven at 1.5 m/s, 35° from the vertical, straight
/// through it for 0.3 s. The god-object slid a quarter of the way around the sphere and
/// on 30 ticks pulled the hand on (up to 0.9 N); now it holds near the entry.
#[test]
fn the_sphere_strike_never_pulls_the_hand_on() {
    let scene = scene_of(
        shape(Catalog::Sphere.with_triangles(20_000)),
        Material::default(),
    );
    let dir = DVec3::new(35f64.to_radians().sin(), 0.0, -35f64.to_radians().cos());
    let start = DVec3::new(0.0, 0.0, 0.13);
    let mut path = vec![start; 100];
    path.extend((1..=300).map(|k| start + dir * (1.5 * k as f64 * 1e-3)));
    let mut proxy = Proxy::new(start, ProxyOptions::default());
    let (mut pushes, mut held, mut contact, mut worst) = (0, 0, 0, 0.0f64);
    let mut previous = start;
    for &hip in &path {
        let out = proxy.tick(&scene, hip, (hip - previous) * 1e3);
        previous = hip;
        contact += usize::from(out.contact.is_some());
        held += usize::from(out.status.deep_hold);
        worst = worst.max(out.force.dot(dir));
        pushes += usize::from(out.force.dot(dir) > STRIKE_FORCE_TOLERANCE_N);
        if let Some(c) = out.contact {
            assert!(c.normal.dot(dir) < 0.0, "far side: {c:?}");
        }
    }
    println!("contact {contact}, held {held}, pushes on {pushes}, largest {worst:.3e} N");
    assert!(contact > 250 && held > 200, "{contact} {held}");
    assert_eq!(pushes, 0, "largest push {worst} N");
    // The brute-force proxy holds the same way.
    let check = check_proxy(&scene, &path, ProxyOptions::default());
    assert_eq!(check.mismatches, 0, "{check:?}");
}

fn assert_holds(name: &str, check: &StrikeCheck) {
    println!("{name}: {check:?}");
    assert!(check.strikes >= 20, "{name}: {check:?}");
    assert!(check.deep_strikes >= 10, "{name}: {check:?}");
    assert_eq!(
        check.pushes_on - check.pushes_on_shallow,
        0,
        "{name}: {check:?}"
    );
    assert_eq!(
        check.far_side - check.far_side_shallow,
        0,
        "{name}: {check:?}"
    );
}

/// Deep strikes, straight and oblique (0–70°), 0.5–10 m/s at 1 kHz, to depths up to
/// passing out of the far side, on the convex and concave procedural shapes, with the
/// default material and a stiff one.
#[test]
fn deep_strikes_never_pull_the_hand_on_procedural_shapes() {
    let stiff = Material {
        stiffness: 2_000.0,
        damping: 2.0,
        ..Material::default()
    };
    for which in [
        Catalog::Sphere,
        Catalog::Blob,
        Catalog::Torus,
        Catalog::ConcaveCorner,
    ] {
        for (m, material) in [Material::default(), stiff].into_iter().enumerate() {
            let scene = scene_of(shape(which.with_triangles(2_000)), material);
            let check = check_strikes(&scene, ProxyOptions::default(), 30, 0.25, 1e3, 7 + m as u64);
            assert_holds(&format!("{which} material {m}"), &check);
        }
    }
}

/// The fast proxy equals the brute-force one along deep strikes (the proxy holds, lets go
/// and holds again).
#[test]
fn fast_proxy_equals_brute_force_along_deep_strikes() {
    for which in [Catalog::Sphere, Catalog::ConcaveCorner, Catalog::Torus] {
        let scene = scene_of(shape(which.with_triangles(2_000)), Material::default());
        let mut path = Vec::new();
        for (k, angle) in [0.0f64, 30.0, 60.0].into_iter().enumerate() {
            let dir = DVec3::new(
                angle.to_radians().sin(),
                0.1 * k as f64,
                -angle.to_radians().cos(),
            )
            .normalize();
            let start = DVec3::new(0.07, 0.01, 0.14) - 0.05 * dir;
            let (out, _) = strike_path(start, dir, 1.0 + k as f64, 0.3, 1e3);
            // Back out along the same line, so the proxy lets go.
            path.extend(out.iter().chain(out.iter().rev()));
        }
        let check = check_proxy(&scene, &path, ProxyOptions::default());
        println!("{which}: {check:?}");
        assert!(check.contact_ticks > 100, "{which}: {check:?}");
        assert_eq!(check.mismatches, 0, "{which}: {check:?}");
        assert_eq!(check.inside, 0, "{which}: {check:?}");
    }
}

/// The whole family: 20 000-triangle shapes and every closed shared model, 200 strikes
/// each (run with `--ignored`; a few minutes in the test profile).
#[test]
#[ignore]
fn deep_strikes_on_every_closed_model() {
    let mut scenes = Vec::new();
    for which in [
        Catalog::Sphere,
        Catalog::Blob,
        Catalog::Torus,
        Catalog::ConcaveCorner,
    ] {
        scenes.push((which.to_string(), which.with_triangles(20_000)));
    }
    {
        let dir = support::meshes();
        let mut names: Vec<_> = std::fs::read_dir(dir.join("models"))
            .expect("listable")
            .map(|e| e.expect("entry").path())
            .collect();
        names.sort();
        for path in names {
            let bytes = std::fs::read(&path).expect("readable");
            let Ok(mut mesh) =
                haphe::mesh::read_mesh(&path.to_string_lossy(), &bytes, &Default::default())
            else {
                continue;
            };
            fit_to_hand_size(&mut mesh);
            scenes.push((
                path.file_name().unwrap().to_string_lossy().into_owned(),
                mesh,
            ));
        }
    }
    for (name, mesh) in scenes {
        let shape = shape(mesh);
        if !shape.is_solid() {
            println!("{name}: not closed, skipped");
            continue;
        }
        let scene = scene_of(shape, Material::default());
        let started = std::time::Instant::now();
        let check = check_strikes(&scene, ProxyOptions::default(), 200, 0.25, 1e3, 3);
        let seconds = started.elapsed().as_secs_f64();
        println!(
            "{name}: {:.2} µs/tick over {} ticks",
            seconds * 1e6 / check.ticks as f64,
            check.ticks
        );
        println!("{name}: {check:?}");
    }
}
