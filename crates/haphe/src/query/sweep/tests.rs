use super::*;
use crate::map::MapOptions;
use crate::mesh::shapes;
use crate::mesh::{Surface, SurfaceOptions};
use crate::rng::SplitMix64;

fn surface_and_map(mesh: crate::mesh::Mesh) -> (Surface, VoxelMap) {
    let surface = Surface::new(mesh, &SurfaceOptions::default()).unwrap();
    let map = VoxelMap::build(&surface, &MapOptions::default()).unwrap();
    (surface, map)
}

/// The distance from `p` to the nearest triangle, by testing every one.
fn distance(surface: &Surface, p: DVec3) -> f64 {
    (0..surface.triangle_count())
        .map(|t| p.distance(closest_point_triangle(p, surface.corners(TriId(t as u32))).point))
        .fold(f64::INFINITY, f64::min)
}

#[test]
fn equals_brute_force_and_touches_at_the_radius() {
    for mesh in [
        shapes::sphere(0.05, 3),
        shapes::cuboid(DVec3::splat(0.04), [3, 2, 4]),
    ] {
        let (surface, map) = surface_and_map(mesh);
        let mut rng = SplitMix64::new(11);
        let (mut touched, mut sampled) = (0, 0);
        for i in 0..3000 {
            let radius = [0.0005, 0.002, 0.01][i % 3];
            let a = rng.unit_vector() * rng.range(0.0, 0.09);
            let b = a + rng.unit_vector() * 10f64.powf(rng.range(-5.0, -1.3));
            let one_sided = i % 5 == 0;
            let hint = (i % 2 == 0).then(|| TriId((i % surface.triangle_count()) as u32));
            let fast =
                first_sphere_contact(&surface, &map, (a, b), (radius, 1e-7, one_sided), hint);
            let brute = first_sphere_contact_brute_force(&surface, (a, b), radius, 1e-7, one_sided);
            assert_eq!(fast, brute, "{a:?} → {b:?}, r {radius}");
            let Some(c) = fast else { continue };
            touched += 1;
            let centre = a + c.t * (b - a);
            let start = distance(&surface, a);
            if start > radius + 1e-7 && !one_sided {
                // The contact is at the radius, from the triangle reported, and nothing
                // along the way came closer (a one-sided surface is passed from behind).
                let at = distance(&surface, centre);
                assert!((at - radius).abs() < 1e-12, "{at} vs {radius}");
                assert!((centre.distance(c.point) - radius).abs() < 1e-12);
                for k in 0..50 {
                    let p = a + (k as f64 / 50.0) * c.t * (b - a);
                    assert!(distance(&surface, p) >= radius - 1e-12);
                    sampled += 1;
                }
            }
            assert!((c.normal.length() - 1.0).abs() < 1e-12);
            // The normal points from the triangle toward the centre.
            assert!(c.normal.dot(centre - c.point) >= -1e-15);
        }
        assert!(touched > 300 && sampled > 3000, "{touched} {sampled}");
    }
}

#[test]
fn a_sweep_that_misses_never_comes_within_the_radius() {
    let (surface, map) = surface_and_map(shapes::sphere(0.05, 2));
    let mut rng = SplitMix64::new(5);
    let mut missed = 0;
    for _ in 0..500 {
        let a = rng.unit_vector() * rng.range(0.06, 0.08);
        let b = a + rng.unit_vector() * 0.02;
        if first_sphere_contact(&surface, &map, (a, b), (0.004, 0.0, false), None).is_some() {
            continue;
        }
        missed += 1;
        for k in 0..=40 {
            let p = a + (k as f64 / 40.0) * (b - a);
            assert!(distance(&surface, p) >= 0.004 - 1e-12);
        }
    }
    assert!(missed > 50, "{missed}");
}

#[test]
fn features_of_one_triangle() {
    let corners = [DVec3::ZERO, DVec3::X, DVec3::Y];
    let face = DVec3::Z;
    let r = 0.1;
    // Straight down onto the face: touches at height r.
    let (s, p, n) = sphere_triangle(
        corners,
        face,
        (DVec3::new(0.2, 0.2, 1.0), DVec3::new(0.2, 0.2, -1.0), 1.0),
        r,
        0.0,
    )
    .unwrap();
    assert!(
        (s - 0.45).abs() < 1e-15 && p.distance(DVec3::new(0.2, 0.2, 0.0)) < 1e-15 && n == DVec3::Z
    );
    // Along the plane into the edge x = 0: touches the cylinder at distance r.
    let (s, p, n) = sphere_triangle(
        corners,
        face,
        (DVec3::new(-1.0, 0.5, 0.0), DVec3::new(1.0, 0.5, 0.0), 1.0),
        r,
        0.0,
    )
    .unwrap();
    assert!((s - 0.45).abs() < 1e-15 && p.distance(DVec3::new(0.0, 0.5, 0.0)) < 1e-15);
    assert!(n.distance(-DVec3::X) < 1e-15);
    // Toward the vertex at the origin along the diagonal below the plane.
    let dir = DVec3::new(-1.0, -1.0, -1.0).normalize();
    let (s, p, _) = sphere_triangle(corners, face, (dir, -dir, 1.0), r, 0.0).unwrap();
    assert!((s * 2.0 - (1.0 - r)).abs() < 1e-12 && p.length() < 1e-15);
    // Moving away from a start within the offset: no contact.
    assert!(
        sphere_triangle(
            corners,
            face,
            (DVec3::new(0.2, 0.2, 0.05), DVec3::new(0.2, 0.2, 0.5), 1.0),
            r,
            0.0
        )
        .is_none()
    );
    // Moving closer from within the offset: a contact at the start.
    let (s, _, n) = sphere_triangle(
        corners,
        face,
        (DVec3::new(0.2, 0.2, 0.05), DVec3::new(0.2, 0.2, -0.5), 1.0),
        r,
        0.0,
    )
    .unwrap();
    assert!(s == 0.0 && n == DVec3::Z);
}

#[test]
fn the_tool_touches_the_nearest_triangle_as_brute_force_does() {
    for mesh in [
        shapes::sphere(0.05, 3),
        shapes::cuboid(DVec3::splat(0.04), [3, 2, 4]),
    ] {
        let (surface, map) = surface_and_map(mesh);
        let mut rng = SplitMix64::new(3);
        let mut found = 0;
        for i in 0..3000 {
            let grow = [0.0005, 0.002, 0.01, 0.05][i % 4];
            let p = rng.unit_vector() * rng.range(0.0, 0.07);
            let fast = nearest_to_tool(&surface, &map, p, grow);
            assert_eq!(
                fast,
                crate::query::nearest_within_brute_force(&surface, p, grow),
                "{p:?} {grow}"
            );
            found += usize::from(fast.is_some());
        }
        assert!(found > 500, "{found}");
    }
}
