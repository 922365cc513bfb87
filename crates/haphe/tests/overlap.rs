//! Overlapping closed parts: a mesh whose parts pass through each other is solid wherever a
//! point is inside any part (the non-zero winding rule), in the fast inside query, the
//! map's fill, a saved map and the proxy; a part inside another facing inwards is a cavity
//! (outside), and an inside-out part on its own leaves the mesh without an inside.

mod support;

use std::sync::Arc;

use haphe::DVec3;
use haphe::map::{MapOptions, VoxelMap, decode, encode};
use haphe::mesh::shapes::{cuboid, torus};
use haphe::mesh::{Mesh, Surface, SurfaceOptions};
use haphe::proxy::ProxyOptions;
use haphe::query::{Side, classify_point};
use haphe::rng::SplitMix64;
use haphe::scene::{Material, ObjectId, Pose, Scene, SceneObject, Shape};
use haphe::verify::{WindingOracle, check_inside, check_proxy, haptic_path, point_on, strike_path};
use support::union;

/// `mesh` facing inwards.
fn inside_out(mesh: Mesh) -> Mesh {
    Mesh {
        vertices: mesh.vertices,
        triangles: mesh.triangles.iter().map(|&[a, b, c]| [a, c, b]).collect(),
    }
}

/// Two 0.1 m boxes overlapping in a 0.04 × 0.07 × 0.08 m box around (0.03, 0.015, 0.01).
fn two_boxes() -> Mesh {
    let part = || cuboid(DVec3::splat(0.05), [5, 5, 5]);
    union(&[
        (part(), DVec3::ZERO),
        (part(), DVec3::new(0.06, 0.03, 0.02)),
    ])
}

/// Two tori (ring 0.07 m, tube 0.03 m) side by side in one plane, 0.05 m apart: their
/// tubes pass through each other in two places.
fn torus_pair() -> Mesh {
    let part = || torus(0.07, 0.03, 56, 24);
    union(&[
        (part(), DVec3::new(-0.025, 0.0, 0.0)),
        (part(), DVec3::new(0.025, 0.0, 0.004)),
    ])
}

fn surface(mesh: Mesh) -> Surface {
    Surface::new(mesh, &SurfaceOptions::default()).expect("a usable surface")
}

/// The fast classification equals the winding-number oracle (inside = winding ≠ 0) on
/// random points of the bounding box and on points within a cell or two of the surface
/// (where the map counts crossings); returns how many points had a winding number other
/// than 0 and 1, after asserting there were some.
fn assert_inside_matches(name: &str, surface: &Surface, map: &VoxelMap) -> usize {
    let check = check_inside(surface, map, 20_000, 11);
    println!("{name}: {check:?}");
    assert_eq!(check.mismatches, 0, "{name}: {check:?}");
    let oracle = WindingOracle::new(surface);
    let mut random = SplitMix64::new(5);
    let h = map.grid().cell_size();
    let (mut counted, mut compared, mut wound) = (0, 0, 0);
    for _ in 0..20_000 {
        let t = haphe::mesh::TriId(random.index(surface.triangle_count()) as u32);
        let on = point_on(surface, t, &mut random);
        let p = on + random.unit_vector() * random.range(0.01, 2.0) * h;
        let winding = oracle.winding(p);
        if haphe::verify::distance_to_surface(surface, p) < 1e-9 {
            continue;
        }
        let (side, status) = classify_point(surface, map, p);
        counted += usize::from(status == haphe::query::SideStatus::Counted);
        wound += usize::from(!(0..=1).contains(&winding));
        compared += 1;
        assert_eq!(
            side == Side::Inside,
            winding != 0,
            "{name}: {p} winding {winding}, {status:?}"
        );
    }
    println!("{name}: {compared} points near the surface, {counted} counted, {wound} overlapping");
    assert!(counted > compared / 4, "{name}: {counted} of {compared}");
    check.overlap + wound
}

#[test]
fn points_where_two_boxes_overlap_are_inside() {
    let surface = surface(two_boxes());
    assert!(surface.is_solid());
    let map = VoxelMap::build(&surface, &MapOptions::default()).expect("a map");
    let overlapping = assert_inside_matches("two boxes", &surface, &map);
    assert!(overlapping > 1000, "{overlapping}");
    // Every point of the overlap box, also next to the inner faces, is inside.
    let mut random = SplitMix64::new(3);
    let (lo, hi) = (DVec3::new(0.01, -0.02, -0.03), DVec3::new(0.05, 0.05, 0.05));
    for _ in 0..10_000 {
        let p = random.point_in(lo + 1e-6, hi - 1e-6);
        assert_eq!(classify_point(&surface, &map, p).0, Side::Inside, "{p}");
    }
    // A saved map keeps the overlap cells.
    let (surface2, map2) = decode(&encode(&surface, &map)).expect("a valid file");
    assert_eq!(map2, map);
    for _ in 0..1_000 {
        let p = random.point_in(lo + 1e-6, hi - 1e-6);
        assert_eq!(classify_point(&surface2, &map2, p).0, Side::Inside, "{p}");
    }
}

#[test]
fn points_where_two_tori_overlap_are_inside() {
    let surface = surface(torus_pair());
    assert!(surface.is_solid());
    let map = VoxelMap::build(&surface, &MapOptions::default()).expect("a map");
    let overlapping = assert_inside_matches("torus pair", &surface, &map);
    assert!(overlapping > 100, "{overlapping}");
    // The centres of the tubes where they cross: at y = ±√(0.07² − 0.025²), both tubes.
    let y = (0.07f64.powi(2) - 0.025f64.powi(2)).sqrt();
    for p in [DVec3::new(0.0, y, 0.002), DVec3::new(0.0, -y, 0.002)] {
        assert_eq!(classify_point(&surface, &map, p).0, Side::Inside, "{p}");
        assert_eq!(WindingOracle::new(&surface).winding(p), 2, "{p}");
    }
}

/// An inside-out box (winding number −1 inside) on its own makes the mesh a surface without
/// an inside (`haphe validate` lists the component as inside-out): no point is inside, not
/// even in the other, outward box. The same box inside a larger outward box is a cavity
/// (winding 0): outside, with the larger box's rest inside.
#[test]
fn an_inside_out_part_is_no_solid_alone_and_a_cavity_within_one() {
    let small = || cuboid(DVec3::splat(0.03), [3, 3, 3]);
    let alone = surface(union(&[
        (cuboid(DVec3::splat(0.05), [5, 5, 5]), DVec3::ZERO),
        (inside_out(small()), DVec3::new(0.2, 0.0, 0.0)),
    ]));
    assert!(!alone.is_solid());
    assert_eq!(alone.report().defects.inverted_components.len(), 1);
    let map = VoxelMap::build(&alone, &MapOptions::default()).expect("a map");
    for p in [
        DVec3::new(0.2, 0.001, 0.002),
        DVec3::new(0.001, 0.002, 0.003),
    ] {
        assert_eq!(classify_point(&alone, &map, p).0, Side::Outside, "{p}");
    }
    let cavity = surface(union(&[
        (cuboid(DVec3::splat(0.1), [5, 5, 5]), DVec3::ZERO),
        (inside_out(small()), DVec3::ZERO),
    ]));
    assert!(cavity.is_solid());
    let map = VoxelMap::build(&cavity, &MapOptions::default()).expect("a map");
    assert_inside_matches("cavity", &cavity, &map);
    assert_eq!(
        classify_point(&cavity, &map, DVec3::new(0.001, 0.002, 0.003)).0,
        Side::Outside
    );
    assert_eq!(
        classify_point(&cavity, &map, DVec3::new(0.06, 0.0, 0.0)).0,
        Side::Inside
    );
}

fn scene_of(mesh: Mesh) -> Scene {
    let shape = Shape::build(surface(mesh), &MapOptions::default()).expect("a map");
    let mut scene = Scene::local(4);
    scene
        .insert(SceneObject::new(
            ObjectId(0),
            Arc::new(shape),
            Pose::IDENTITY,
            Material::default(),
        ))
        .expect("room");
    scene
}

/// The proxy (fast and brute force, equal at every tick) never rests inside either part,
/// on exploring paths and on strikes aimed through the overlap from every side.
#[test]
fn the_proxy_never_rests_inside_overlapping_parts() {
    for (name, mesh, through) in [
        ("two boxes", two_boxes(), DVec3::new(0.03, 0.015, 0.01)),
        (
            "torus pair",
            torus_pair(),
            DVec3::new(0.0, (0.07f64.powi(2) - 0.025f64.powi(2)).sqrt(), 0.002),
        ),
    ] {
        let scene = scene_of(mesh);
        let mut path = haptic_path(&scene, 3_000, (0.05, 0.5), 1e3, 17);
        let mut random = SplitMix64::new(23);
        for k in 0..12 {
            let dir = random.unit_vector();
            let start = through - 0.2 * dir;
            let (strike, _) = strike_path(start, dir, 0.5 + k as f64 * 0.5, 0.4, 1e3);
            path.extend(strike.iter().chain(strike.iter().rev()));
        }
        let check = check_proxy(&scene, &path, ProxyOptions::default());
        println!("{name}: {check:?}");
        assert!(check.contact_ticks > 1000, "{name}: {check:?}");
        assert_eq!(check.mismatches, 0, "{name}: {check:?}");
        assert_eq!(check.inside, 0, "{name}: {check:?}");
        assert_eq!(check.bad_forces, 0, "{name}: {check:?}");
    }
}
