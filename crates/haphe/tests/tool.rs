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
use haphe::scene::{Material, Scene, Shape};
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
        let scene =
            one_object_scene(shape(which.with_triangles(2_000)), friction(), 4).expect("room");
        check_tool(&which.to_string(), &scene, 2_000, 31 + k as u64);
    }
}

/// The same on the repository's real models, scaled to a hand's size.
#[test]
fn tool_equals_brute_force_on_real_models() {
    check_models(&["20mm-xyz-cube.stl", "cylinder.stl", "spot.obj"]);
}

/// ... and on the closed models of the shared collection.
#[test]
#[cfg_attr(not(shared_meshes), ignore = "needs ../shared/meshes")]
fn tool_equals_brute_force_on_shared_models() {
    check_models(&["fandisk.obj", "bunny.ply"]);
}

fn check_models(names: &[&str]) {
    for (k, &name) in names.iter().enumerate() {
        let path = support::meshes().join("models").join(name);
        let bytes = std::fs::read(&path).expect("readable");
        let mesh = haphe::mesh::read_mesh(&path.to_string_lossy(), &bytes, &Default::default())
            .expect("loads");
        let surface = Surface::new(mesh, &SurfaceOptions::default()).expect("usable");
        let (mesh, _) = haphe::verify::hand_sized(&surface);
        let scene = one_object_scene(shape(mesh), friction(), 4).expect("room");
        check_tool(name, &scene, 1_500, 7 + k as u64);
    }
}

/// Deep strikes (0.5–10 m/s, up to 70° from the normal, on through the object): from the
/// tick the hand goes deeper than the saturation depth, no force pushes it on along the
/// strike, contact is never lost and the tool never rests on the far side.
#[test]
fn deep_strikes_hold_the_side_of_entry() {
    for which in [
        Catalog::Sphere,
        Catalog::Blob,
        Catalog::ConcaveCorner,
        Catalog::Torus,
    ] {
        let scene = one_object_scene(shape(which.with_triangles(2_000)), Material::default(), 4)
            .expect("room");
        for radius in [0.5e-3, 2e-3] {
            let check = check_strikes(&scene, tool(radius), 30, 0.25, 1e3, 5);
            println!("{which} r {radius}: {check:?}");
            assert!(check.passed(), "{which} r {radius}: {check:?}");
        }
    }
}

/// A mesh of boxes given by their lower and upper corners (overlapping closed parts: the
/// solid is their union).
fn boxes(parts: &[(DVec3, DVec3)]) -> Mesh {
    let mut mesh = Mesh {
        vertices: Vec::new(),
        triangles: Vec::new(),
    };
    for &(lo, hi) in parts {
        let part = shapes::cuboid((hi - lo) / 2.0, [2, 2, 2]);
        let base = mesh.vertices.len() as u32;
        mesh.vertices
            .extend(part.vertices.iter().map(|&v| v + (lo + hi) / 2.0));
        mesh.triangles
            .extend(part.triangles.iter().map(|t| t.map(|i| i + base)));
    }
    mesh
}

/// The channel test: a U channel 10 mm wide made of three overlapping closed boxes (a
/// floor, its top at z = 0, and two walls 20 mm high). A tool narrower than the channel
/// reaches its floor; a wider one rests on the walls' edges, its centre
/// `sqrt(r² − (W/2)²)` above them. Pressed down 2 mm beyond where it rests, a little off
/// the channel's middle.
#[test]
fn a_tool_reaches_the_floor_of_a_channel_wider_than_it_and_rests_on_a_narrower_one() {
    let w = 0.01;
    let mesh = boxes(&[
        (DVec3::new(-0.05, -0.05, -0.02), DVec3::new(0.05, 0.05, 0.0)),
        (
            DVec3::new(-0.05, -0.05, -0.01),
            DVec3::new(-w / 2.0, 0.05, 0.02),
        ),
        (
            DVec3::new(w / 2.0, -0.05, -0.01),
            DVec3::new(0.05, 0.05, 0.02),
        ),
    ]);
    let scene = one_object_scene(shape(mesh), Material::default(), 4).expect("room");
    for (radius, rest_z) in [
        (0.003, 0.003),
        (0.0045, 0.0045),
        (0.006, 0.02 + (0.006f64.powi(2) - (w / 2.0).powi(2)).sqrt()),
        (0.009, 0.02 + (0.009f64.powi(2) - (w / 2.0).powi(2)).sqrt()),
    ] {
        let options = tool(radius);
        let start = DVec3::new(0.0003, 0.0, 0.05);
        let goal = DVec3::new(0.0003, 0.0, rest_z - 0.002);
        let mut path: Vec<DVec3> = (0..=200)
            .map(|k| start.lerp(goal, k as f64 / 200.0))
            .collect();
        path.extend(std::iter::repeat_n(goal, 300));
        let mut proxy = Proxy::new(start, options);
        let mut last = start;
        let mut still = Vec::new();
        for (k, &hip) in path.iter().enumerate() {
            last = proxy.tick(&scene, hip, DVec3::ZERO).proxy;
            if k >= path.len() - 50 {
                still.push(last);
            }
        }
        // On the floor the tool stays under the hand; on the edges it is centred.
        let rest_x = if radius < w / 2.0 { goal.x } else { 0.0 };
        assert!(
            (last.z - rest_z).abs() < 1e-5 && (last.x - rest_x).abs() < 1e-5,
            "r {radius}: rests at {last:?}, expected x {rest_x} z {rest_z}"
        );
        // At rest, no jitter: the last 50 ticks within a skin of each other.
        assert!(
            still.iter().all(|p| p.distance(last) < options.skin()),
            "r {radius}"
        );
        let gap = distance_to_surface(scene.objects()[0].shape.surface(), last);
        assert!(gap >= radius - options.skin(), "r {radius}: {gap}");
        let check = check_proxy(&scene, &path, options);
        assert_eq!(check.mismatches, 0, "r {radius}: {check:?}");
        assert_eq!(check.inside, 0, "r {radius}: {check:?}");
    }
}

/// Sliding over a box's convex edge, the force's direction turns smoothly from the top
/// face's normal to the side's (no jump larger than the slide can explain), and in a
/// concave corner of three faces the tool rests without jitter.
#[test]
fn convex_edges_feel_round_and_concave_corners_hold_still() {
    let scene = one_object_scene(
        shape(shapes::cuboid(DVec3::splat(0.05), [3, 3, 3])),
        Material::default(),
        4,
    )
    .expect("room");
    let radius = 0.004;
    let mut proxy = Proxy::new(DVec3::new(0.0, 0.0, 0.08), tool(radius));
    // Down onto the top, 2 mm in, then over the edge at x = 0.05 and down the side.
    let mut previous: Option<DVec3> = None;
    let (mut turned, mut worst) = (0.0f64, 0.0f64);
    for k in 0..=2000 {
        let a = k as f64 / 2000.0 * std::f64::consts::FRAC_PI_2;
        // The hand circles the edge 2 mm inside the tool's offset, top to side.
        let hip =
            DVec3::new(0.05, 0.0, 0.05) + (radius - 0.002) * DVec3::new(a.sin(), 0.0, a.cos());
        let out = proxy.tick(&scene, hip, DVec3::ZERO);
        let Some(c) = out.contact else { continue };
        if let Some(n) = previous {
            let step = n.angle_between(c.normal);
            worst = worst.max(step);
        }
        turned = turned.max(c.normal.angle_between(DVec3::Z));
        previous = Some(c.normal);
    }
    assert!(turned > 1.5, "the normal turned {turned} rad over the edge");
    assert!(worst < 0.01, "the largest turn in one tick {worst} rad");
    // A concave corner: three boxes meeting, the tool pressed into their inner corner.
    let corner = boxes(&[
        (DVec3::new(-0.05, -0.05, -0.05), DVec3::new(0.05, 0.05, 0.0)),
        (DVec3::new(-0.05, -0.05, -0.05), DVec3::new(0.0, 0.05, 0.05)),
        (DVec3::new(-0.05, -0.05, -0.05), DVec3::new(0.05, 0.0, 0.05)),
    ]);
    let scene = one_object_scene(shape(corner), Material::default(), 4).expect("room");
    let mut proxy = Proxy::new(DVec3::splat(0.03), tool(radius));
    let hip = DVec3::splat(radius - 0.002);
    let mut rest = Vec::new();
    for k in 0..600 {
        let p = proxy.tick(
            &scene,
            DVec3::splat(0.03).lerp(hip, (k as f64 / 200.0).min(1.0)),
            DVec3::ZERO,
        );
        if k >= 500 {
            assert_eq!(p.contact.map(|c| c.constraints), Some(3), "tick {k}");
            rest.push(p.proxy);
        }
    }
    let last = *rest.last().expect("ticks");
    assert!(last.distance(DVec3::splat(radius)) < 1e-5, "{last:?}");
    assert!(
        rest.iter().all(|p| p.distance(last) < 1e-9),
        "jitter: {rest:?}"
    );
}

/// Two objects that move and turn (up to 0.3 m/s and 1 rad/s) push the tool: the fast
/// proxy equals the brute-force one at every tick, and the tool never comes closer than
/// its radius less the skin to either.
#[test]
fn moving_objects_push_the_tool() {
    use haphe::glam::DQuat;
    use haphe::scene::{ObjectId, Pose, SceneObject};
    let mut scene = Scene::local(4);
    let parts = [
        (shape(Catalog::Blob.with_triangles(2_000)), 0.0),
        (shape(Catalog::ThinPlate.with_triangles(1_000)), 0.12),
    ];
    for (k, (s, z)) in parts.into_iter().enumerate() {
        let pose = Pose::from_translation(DVec3::new(0.0, 0.0, z)).expect("a valid pose");
        let o = SceneObject::new(ObjectId(k as u32), s, pose, friction());
        scene.insert(o).expect("room");
    }
    let path = haptic_path(&scene, 3_000, (0.01, 2.0), 1e3, 3);
    let options = tool(0.002);
    let mut fast = Proxy::new(path[0], options);
    let mut brute = haphe::verify::BruteProxy::new(&scene, path[0], options);
    let mut contacts = 0;
    for (k, &hip) in path.iter().enumerate() {
        let t = k as f64 * 1e-3;
        scene.begin_tick();
        let blob = Pose::new(
            DQuat::from_rotation_z(t),
            DVec3::new(0.03 * (10.0 * t).sin(), 0.0, 0.0),
        );
        let plate = Pose::new(
            DQuat::from_rotation_x(0.3 * t),
            DVec3::new(0.0, 0.0, 0.12 - 0.01 * t),
        );
        scene.set_pose(ObjectId(0), blob.expect("a valid pose"));
        scene.set_pose(ObjectId(1), plate.expect("a valid pose"));
        let out = fast.tick(&scene, hip, DVec3::ZERO);
        brute.sync(&scene);
        let (b, b_contact) = brute.tick(hip);
        assert!(
            out.proxy.distance(b) <= haphe::verify::PROXY_TOLERANCE_M,
            "tick {k}: fast {out:?}, brute {b:?}"
        );
        assert_eq!(out.contact.is_some(), b_contact, "tick {k}");
        contacts += usize::from(b_contact);
        for o in scene.objects() {
            let gap = distance_to_surface(o.shape.surface(), o.pose.to_object(out.proxy));
            assert!(
                gap >= 0.002 - options.skin(),
                "tick {k}: {gap} from {:?}",
                o.id
            );
        }
    }
    assert!(contacts > 300, "{contacts}");
}
