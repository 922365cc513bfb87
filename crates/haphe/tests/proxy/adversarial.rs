//! Adversarial device paths: strikes at up to 1 cm a tick on a thin plate, a knife edge
//! and a concave corner, and paths that slide exactly on a face or in its plane.

use super::*;

/// A knife: a triangular prism 0.2 m long whose edge along x has an apex angle of 2°.
fn knife() -> Mesh {
    let (h, half) = (0.05, 0.05 * (1f64.to_radians()).tan());
    let vertices = vec![
        DVec3::new(-0.1, -half, 0.0),
        DVec3::new(-0.1, half, 0.0),
        DVec3::new(-0.1, 0.0, h),
        DVec3::new(0.1, -half, 0.0),
        DVec3::new(0.1, half, 0.0),
        DVec3::new(0.1, 0.0, h),
    ];
    let triangles = vec![
        [0, 2, 1],
        [3, 4, 5],
        [0, 3, 5],
        [0, 5, 2],
        [1, 2, 5],
        [1, 5, 4],
        [0, 1, 4],
        [0, 4, 3],
    ];
    Mesh {
        vertices,
        triangles,
    }
}

/// Fast strikes (up to 10 m/s at 1 kHz: 1 cm per tick) on a plate 0.1 mm thick, a 2° knife
/// edge and a concave corner: equal to the oracle, never inside, never through.
#[test]
fn fast_strikes_never_break_through() {
    let shapes = [
        ("thin plate", Catalog::ThinPlate.with_triangles(1_000)),
        ("knife", knife()),
        (
            "concave corner",
            Catalog::ConcaveCorner.with_triangles(1_000),
        ),
    ];
    for (k, (name, mesh)) in shapes.into_iter().enumerate() {
        let scene = scene_of(shape(mesh), friction());
        let path = haptic_path(&scene, 5_000, (2.0, 10.0), 1e3, 100 + k as u64);
        let check = check_proxy(&scene, &path, ProxyOptions::default());
        println!("{name}: {check:?}");
        assert!(check.contact_ticks > 500, "{name}: {check:?}");
        assert_eq!(check.mismatches, 0, "{name}: {check:?}");
        assert_eq!(check.inside, 0, "{name}: {check:?}");
    }
}

/// The device slides exactly on the surface (zero height, where the segment test alone
/// cannot tell the sides apart), then presses: the proxy still stops at the surface.
#[test]
fn sliding_exactly_on_the_surface_then_pressing() {
    let scene = floor(Material::default());
    let box_ = &scene.objects()[0];
    for start in [
        DVec3::new(-0.05, 0.013, 0.0),
        DVec3::new(-0.0375, -0.05, 0.0),
    ] {
        let mut proxy = Proxy::new(start + DVec3::new(0.0, 0.0, 0.01), ProxyOptions::default());
        for k in 0..200 {
            let hip = start + DVec3::new(0.0005 * k as f64, 0.0003 * k as f64, 0.0);
            proxy.tick(&scene, hip, DVec3::ZERO);
        }
        for k in 0..20 {
            let hip = proxy.position() + DVec3::new(0.0001, 0.0, -0.0005 * k as f64);
            let out = proxy.tick(&scene, hip, DVec3::ZERO);
            let q = box_.pose.to_object(out.proxy);
            assert!(out.proxy.z >= 0.0, "tick {k}: {out:?}");
            assert_ne!(
                classify_point(box_.shape.surface(), box_.shape.map(), q).0,
                Side::Inside
            );
        }
    }
}

/// The device arrives on a face moving within its plane (through the face's edge, which
/// the watertight test may hand to the face seen edge-on), then moves on within that
/// plane into the solid, where the plane runs inside a wall. Which side of the plane the
/// test's tie-break leans to depends on the direction of motion, so the proxy could rest
/// on the face and then slip under the wall's edge; it touched the face on arrival, so
/// the wall stops it; so does a proxy placed on the face, which touches it on its first
/// tick. The shape: the concave corner sheared by `z += x / 2` (exact in
/// binary), whose floor `z = x / 2` runs into the solid at `x < 0` and `y < 0`.
#[test]
fn arriving_on_a_face_within_its_plane_then_moving_into_a_wall() {
    let s = 0.25;
    let mut mesh = shapes::concave_corner(s, 1);
    for v in &mut mesh.vertices {
        v.z += 0.5 * v.x;
    }
    let scene = scene_of(shape(mesh), Material::default());
    let o = &scene.objects()[0];
    let on_floor = DVec3::new(0.0625, 0.0625, 0.03125);
    let (along_x, along_y) = (DVec3::new(1.0, 0.0, 0.5), DVec3::Y);
    let mut checked = 0;
    for from in [along_x, along_y] {
        for into in [-along_x, -along_y, -along_x - along_y] {
            // No step: the proxy is placed on the floor (`Proxy::new` there).
            for steps in [0, 1, 4] {
                let start = if steps == 0 {
                    on_floor
                } else {
                    on_floor + from * 0.5 * s
                };
                let mut path = vec![start];
                path.extend((1..=steps).map(|k| start.lerp(on_floor, k as f64 / steps as f64)));
                path.extend((1..=20).map(|k| on_floor + into * (k as f64 / 128.0)));
                let check = check_proxy(&scene, &path, ProxyOptions::default());
                assert_eq!(check.mismatches, 0, "{from} {into} {steps}: {check:?}");
                assert_eq!(check.inside, 0, "{from} {into} {steps}: {check:?}");
                let mut proxy = Proxy::new(start, ProxyOptions::default());
                let mut last = None;
                for &hip in &path {
                    let out = proxy.tick(&scene, hip, DVec3::ZERO);
                    let q = o.pose.to_object(out.proxy);
                    let side = classify_point(o.shape.surface(), o.shape.map(), q).0;
                    assert_ne!(side, Side::Inside, "{from} {into} {steps}: {out:?}");
                    last = Some(out);
                    checked += 1;
                }
                // The path ends inside the solid: the proxy is held at a wall.
                let last = last.unwrap();
                assert!(last.contact.is_some(), "{from} {into} {steps}: {last:?}");
            }
        }
    }
    assert!(checked > 100);
}
