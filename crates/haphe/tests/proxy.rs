//! The god-object proxy: against the brute-force proxy on haptic trajectories, no
//! break-through, no direction problem, moving objects, physics sanity, bad input.

mod support;

#[path = "proxy/adversarial.rs"]
mod adversarial;
#[path = "proxy/deep.rs"]
mod deep;
#[path = "proxy/open.rs"]
mod open;

use std::sync::Arc;

use haphe::DVec3;
use haphe::glam::DQuat;
use haphe::map::MapOptions;
use haphe::mesh::shapes::{self, Catalog};
use haphe::mesh::{Mesh, Surface, SurfaceOptions};
use haphe::proxy::{Proxy, ProxyOptions};
use haphe::query::{Side, classify_point};
use haphe::scene::{
    ABSURD_FORCE_N, Material, ObjectId, Param, Pose, Scene, SceneObject, Shape, Sides,
};
use haphe::verify::{check_proxy, haptic_path, one_object_scene};

fn shape(mesh: Mesh) -> Arc<Shape> {
    let surface = Surface::new(mesh, &SurfaceOptions::default()).expect("a usable surface");
    Arc::new(Shape::build(surface, &MapOptions::default()).expect("a map"))
}

fn scene_of(shape: Arc<Shape>, material: Material) -> Scene {
    one_object_scene(shape, material, 4).expect("room")
}

fn friction() -> Material {
    Material::builder()
        .stiffness(800.0)
        .damping(1.0)
        .friction(0.6, 0.4)
        .build()
        .expect("a valid material")
}

/// The fast proxy equals the brute-force one at every tick, on every procedural shape
/// (thin plate, concave corner and knife-free convex ones), with and without friction.
#[test]
fn fast_proxy_equals_brute_force_on_procedural_shapes() {
    for (k, which) in Catalog::ALL.into_iter().enumerate() {
        for (m, material) in [Material::default(), friction()].into_iter().enumerate() {
            let scene = scene_of(shape(which.with_triangles(2_000)), material);
            let path = haptic_path(
                &scene,
                3_000,
                (0.01, 2.0),
                1e3,
                17 + k as u64 * 2 + m as u64,
            );
            let check = check_proxy(&scene, &path, ProxyOptions::default());
            println!("{which} material {m}: {check:?}");
            assert!(
                check.contact_ticks > 300,
                "{which}: too little contact: {check:?}"
            );
            assert_eq!(check.mismatches, 0, "{which}: {check:?}");
            assert_eq!(check.inside, 0, "{which}: {check:?}");
            assert_eq!(check.bad_forces, 0, "{which}: {check:?}");
        }
    }
}

/// The same on real models: those in the repository's `meshes/`...
#[test]
fn fast_proxy_equals_brute_force_on_real_models() {
    check_models(&["20mm-xyz-cube.stl", "cylinder.stl", "spot.obj"]);
}

/// ... and larger ones of the shared collection.
#[test]
#[cfg_attr(not(shared_meshes), ignore = "needs ../shared/meshes")]
fn fast_proxy_equals_brute_force_on_shared_models() {
    check_models(&["fandisk.obj", "bunny.ply"]);
}

/// The fast proxy against the brute-force one on a haptic path over each model, scaled to
/// hand size.
fn check_models(names: &[&str]) {
    for &name in names {
        let path = support::meshes().join("models").join(name);
        let bytes = std::fs::read(&path).expect("readable");
        let mut mesh = haphe::mesh::read_mesh(&path.to_string_lossy(), &bytes, &Default::default())
            .expect("loads");
        fit_to_hand_size(&mut mesh);
        let scene = scene_of(shape(mesh), friction());
        let path = haptic_path(&scene, 3_000, (0.01, 2.0), 1e3, 11);
        let check = check_proxy(&scene, &path, ProxyOptions::default());
        println!("{name}: {check:?}");
        assert!(
            check.contact_ticks > 300,
            "{name}: too little contact: {check:?}"
        );
        assert_eq!(check.mismatches, 0, "{name}: {check:?}");
        assert_eq!(check.inside, 0, "{name}: {check:?}");
        assert_eq!(check.bad_forces, 0, "{name}: {check:?}");
    }
}

/// Scales a model (in whatever units its file used) to 0.2 m across, the size of an
/// object explored with a desktop device.
fn fit_to_hand_size(mesh: &mut Mesh) {
    let (lo, hi) = mesh.bounds().expect("vertices");
    let scale = 0.2 / (hi - lo).max_element();
    mesh.vertices
        .iter_mut()
        .for_each(|v| *v = (*v - lo) * scale);
}

/// A flat floor: the top face of a box, z = 0 over x, y in [−0.1, 0.1].
pub(crate) fn floor(material: Material) -> Scene {
    let mesh = shapes::cuboid(DVec3::new(0.1, 0.1, 0.05), [4, 4, 2]);
    let mut scene = Scene::local(4);
    scene
        .insert(SceneObject::new(
            ObjectId(1),
            shape(mesh),
            Pose::from_translation(DVec3::new(0.0, 0.0, -0.05)).expect("a valid pose"),
            material,
        ))
        .expect("room");
    scene
}

#[test]
fn resting_on_a_floor_renders_a_spring() {
    let scene = floor(Material::default());
    let mut proxy = Proxy::new(DVec3::new(0.0, 0.0, 0.01), ProxyOptions::default());
    let out = proxy.tick(&scene, DVec3::new(0.01, 0.02, 0.01), DVec3::ZERO);
    assert!(out.contact.is_none());
    assert_eq!(out.force, DVec3::ZERO);
    let out = proxy.tick(&scene, DVec3::new(0.01, 0.02, -0.002), DVec3::ZERO);
    let contact = out.contact.expect("in contact");
    assert!(
        (out.proxy - DVec3::new(0.01, 0.02, 1e-6)).length() < 1e-12,
        "{out:?}"
    );
    assert!((contact.penetration - 0.002 - 1e-6).abs() < 1e-12);
    assert!(contact.normal.distance(DVec3::Z) < 1e-12);
    assert!((out.force - DVec3::new(0.0, 0.0, 500.0 * (0.002 + 1e-6))).length() < 1e-9);
    assert_eq!(contact.constraints, 1);
}

/// Fast strikes (1 cm per tick) against a plate 0.1 mm thick, through vertices and edges
/// hit exactly: the proxy never reaches the far side and the force points back.
#[test]
fn no_break_through_on_a_thin_plate() {
    let plate = shape(Catalog::ThinPlate.with_triangles(2_000));
    let scene = scene_of(plate.clone(), Material::default());
    let options = ProxyOptions::default()
        .with_max_force(ABSURD_FORCE_N)
        .expect("the largest force");
    let vertices: Vec<DVec3> = plate.surface().vertices().to_vec();
    let mut strikes = 0;
    for (i, v) in vertices.iter().enumerate().step_by(3) {
        // Strikes that stay over the plate (it spans ±0.1 m in x and y).
        if v.x.abs() > 0.08 || v.y.abs() > 0.09 {
            continue;
        }
        // Straight down through a vertex, through an edge midpoint, and slanted.
        let w = vertices[(i * 31 + 5) % vertices.len()];
        if w.x.abs() > 0.08 || w.y.abs() > 0.09 {
            continue;
        }
        for target in [*v, 0.5 * (*v + w)] {
            for side in [1.0, -1.0] {
                let start = DVec3::new(target.x, target.y, side * 0.03);
                let mut proxy = Proxy::new(start, options);
                for k in 1..=8 {
                    let hip = start - DVec3::new(0.002 * k as f64, 0.0, side * 0.01 * k as f64);
                    let out = proxy.tick(&scene, hip, DVec3::ZERO);
                    assert!(out.proxy.z * side > 0.0, "through the plate: {out:?}");
                    if out.contact.is_some() {
                        assert!(out.force.z * side > 0.0, "force flipped: {out:?}");
                    }
                }
                strikes += 1;
            }
        }
    }
    assert!(strikes > 100);
}

/// Pushing deep into a thin part keeps the force pointing back to the side of entry,
/// where the nearest-point method flips as soon as the device passes the middle.
#[test]
fn no_direction_problem() {
    // A slab 4 mm thick: z in [−0.002, 0.002].
    let slab = shape(shapes::cuboid(DVec3::new(0.1, 0.1, 0.002), [4, 4, 1]));
    let scene = scene_of(slab.clone(), Material::default());
    let mut proxy = Proxy::new(DVec3::new(0.0, 0.0, 0.01), ProxyOptions::default());
    let mut flips = 0;
    for k in 0..120 {
        let hip = DVec3::new(0.0, 0.0, 0.01 - 0.0002 * k as f64);
        let out = proxy.tick(&scene, hip, DVec3::ZERO);
        if hip.z < 0.002 {
            // Inside the slab and beyond it: always back up through the top.
            assert!(out.force.z > 0.0, "tick {k}: {out:?}");
            assert!(out.proxy.z > 0.002, "tick {k}: {out:?}");
            // The nearest-point method pushes out through the nearer face.
            let nearest = haphe::query::nearest_point_brute_force(slab.surface(), hip);
            if (nearest.point - hip).z < 0.0 {
                flips += 1;
            }
        }
    }
    // The device is in the lower half of the slab for 10 ticks.
    assert_eq!(
        flips, 10,
        "the nearest-point method flips in the lower half"
    );
}

/// A box moving at 1 m/s into a device point at rest pushes the proxy: no pop-through.
#[test]
fn a_moving_box_pushes_the_proxy() {
    let cube = shape(shapes::cuboid(DVec3::splat(0.02), [2, 2, 2]));
    let mut scene = Scene::local(2);
    let id = ObjectId(7);
    let start = Pose::from_translation(DVec3::new(-0.05, 0.0, 0.0)).expect("a valid pose");
    scene
        .insert(SceneObject::new(id, cube, start, Material::default()))
        .expect("room");
    let hip = DVec3::ZERO;
    let mut proxy = Proxy::new(hip, ProxyOptions::default());
    let mut pushed = 0;
    for k in 1..=60 {
        // 1 mm per tick at 1 kHz.
        let x = -0.05 + 0.001 * k as f64;
        scene.begin_tick();
        scene.set_pose(
            id,
            Pose::new(
                DQuat::from_rotation_z(0.001 * k as f64),
                DVec3::new(x, 0.0, 0.0),
            )
            .expect("a valid pose"),
        );
        let out = proxy.tick(&scene, hip, DVec3::ZERO);
        let o = &scene.objects()[0];
        let q = o.pose.to_object(out.proxy);
        assert_ne!(
            classify_point(o.shape.surface(), o.shape.map(), q).0,
            Side::Inside,
            "tick {k}: proxy inside the box"
        );
        if out.contact.is_some() {
            pushed += 1;
            assert!(out.force.x > 0.0, "tick {k}: {out:?}");
            assert!(out.proxy.x > x + 0.019, "tick {k}: {out:?}");
        }
    }
    assert!(pushed > 20, "{pushed}");
}

/// A point mass pressed onto a floor with a constant force settles at `F / k`.
#[test]
fn constant_push_settles_at_force_over_stiffness() {
    let material = Material::builder()
        .stiffness(1000.0)
        .damping(2.0)
        .build()
        .expect("a valid material");
    let scene = floor(material);
    let mut proxy = Proxy::new(DVec3::new(0.0, 0.0, 0.005), ProxyOptions::default());
    let (mass, push, dt) = (0.05, 1.5, 1e-3);
    let mut x = DVec3::new(0.0, 0.0, 0.005);
    let mut v = DVec3::ZERO;
    for _ in 0..5_000 {
        let out = proxy.tick(&scene, x, v);
        let a = (out.force + DVec3::new(0.0, 0.0, -push)) / mass;
        v += a * dt;
        x += v * dt;
    }
    let expected = -push / 1000.0 + 1e-6;
    assert!(
        (x.z - expected).abs() < 1e-6,
        "settled at {} not {}",
        x.z,
        expected
    );
}

/// Friction holds the proxy while the tangential force is inside the cone and lets it
/// slide outside it.
#[test]
fn friction_sticks_inside_the_cone_and_slips_outside() {
    let scene = floor(friction());
    let mut proxy = Proxy::new(DVec3::new(0.0, 0.0, 0.005), ProxyOptions::default());
    proxy.tick(&scene, DVec3::new(0.0, 0.0, -0.001), DVec3::ZERO);
    let anchor = proxy.position();
    // Tangential 0.5 mm at 1 mm depth: ratio 0.5 < 0.6, sticks.
    let out = proxy.tick(&scene, DVec3::new(0.0005, 0.0, -0.001), DVec3::ZERO);
    assert!(out.status.sticking);
    assert!(out.proxy.distance(anchor) < 1e-12);
    let ratio = out.force.x.abs() / out.force.z;
    assert!((ratio - 0.5).abs() < 1e-3, "{ratio}");
    // Tangential 1 mm: ratio 1 > 0.6, slips to the dynamic cone (0.4).
    let out = proxy.tick(&scene, DVec3::new(0.001, 0.0, -0.001), DVec3::ZERO);
    assert!(!out.status.sticking);
    let ratio = out.force.x.abs() / out.force.z;
    assert!((ratio - 0.4).abs() < 1e-3, "{ratio}");
}

/// Two boxes side by side make a concave corner with the floor: the proxy rests in it,
/// constrained by both objects.
#[test]
fn corner_between_two_objects() {
    let mut scene = floor(Material::default());
    let wall = shape(shapes::cuboid(DVec3::new(0.01, 0.1, 0.05), [1, 4, 2]));
    scene
        .insert(SceneObject::new(
            ObjectId(2),
            wall,
            Pose::from_translation(DVec3::new(0.03, 0.0, 0.05)).expect("a valid pose"),
            Material::default(),
        ))
        .expect("room");
    // The wall's face at x = 0.02 rises from the floor.
    let mut proxy = Proxy::new(DVec3::new(0.0, 0.0, 0.01), ProxyOptions::default());
    let out = proxy.tick(&scene, DVec3::new(0.025, 0.0, -0.003), DVec3::ZERO);
    let contact = out.contact.expect("contact");
    assert_eq!(contact.constraints, 2, "{out:?}");
    assert!(
        (out.proxy - DVec3::new(0.02 - 1e-6, 0.0, 1e-6)).length() < 1e-9,
        "{out:?}"
    );
    assert!(out.force.x < 0.0 && out.force.z > 0.0);
}

/// Moving objects: the fast proxy equals the brute-force one while two objects move and
/// turn under the device (relative motion tested in each object's frame).
#[test]
fn fast_proxy_equals_brute_force_with_moving_objects() {
    let blob = shape(Catalog::Blob.with_triangles(2_000));
    let plate = shape(Catalog::ThinPlate.with_triangles(1_000));
    let mut scene = Scene::local(4);
    scene
        .insert(SceneObject::new(
            ObjectId(0),
            blob,
            Pose::IDENTITY,
            friction(),
        ))
        .expect("room");
    scene
        .insert(SceneObject::new(
            ObjectId(1),
            plate,
            Pose::from_translation(DVec3::new(0.0, 0.0, 0.12)).expect("a valid pose"),
            Material::default(),
        ))
        .expect("room");
    let path = haptic_path(&scene, 4_000, (0.01, 2.0), 1e3, 3);
    let options = ProxyOptions::default();
    let mut fast = Proxy::new(path[0], options);
    let mut brute = haphe::verify::BruteProxy::new(&scene, path[0], options);
    let mut contacts = 0;
    for (k, &hip) in path.iter().enumerate() {
        let t = k as f64 * 1e-3;
        scene.begin_tick();
        // Up to 0.3 m/s and 1 rad/s.
        scene.set_pose(
            ObjectId(0),
            Pose::new(
                DQuat::from_rotation_z(t),
                DVec3::new(0.03 * (10.0 * t).sin(), 0.0, 0.0),
            )
            .expect("a valid pose"),
        );
        scene.set_pose(
            ObjectId(1),
            Pose::new(
                DQuat::from_rotation_x(0.3 * t),
                DVec3::new(0.0, 0.0, 0.12 - 0.01 * t),
            )
            .expect("a valid pose"),
        );
        let out = fast.tick(&scene, hip, DVec3::ZERO);
        brute.sync(&scene);
        let (b, b_contact) = brute.tick(hip);
        assert!(
            out.proxy.distance(b) <= haphe::verify::PROXY_TOLERANCE_M,
            "tick {k}: fast {out:?}, brute {b:?}"
        );
        assert_eq!(out.contact.is_some(), b_contact, "tick {k}");
        contacts += usize::from(b_contact);
        for o in scene.objects().iter().filter(|o| o.shape.is_solid()) {
            let q = o.pose.to_object(out.proxy);
            assert_ne!(
                classify_point(o.shape.surface(), o.shape.map(), q).0,
                Side::Inside,
                "tick {k}: inside {:?}",
                o.id
            );
        }
    }
    assert!(contacts > 500, "{contacts}");
}

use proptest::prelude::Strategy as _;

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(64))]

    /// Any device input — non-finite, huge, wildly jumping — and any material and force
    /// limit their domains allow, the extremes included: no panic, and the force is finite
    /// and within the clamp. (Values outside the domains cannot be built: the hostile
    /// suite's `values` tests show each refused.)
    #[test]
    fn any_input_gives_a_bounded_force(
        hips in proptest::collection::vec(
            proptest::prop_oneof![
                (-0.3f64..0.3, -0.3f64..0.3, -0.3f64..0.3).prop_map(|(x, y, z)| DVec3::new(x, y, z)),
                proptest::num::f64::ANY.prop_map(DVec3::splat),
                (proptest::num::f64::ANY, proptest::num::f64::ANY, proptest::num::f64::ANY)
                    .prop_map(|(x, y, z)| DVec3::new(x, y, z)),
            ],
            1..200,
        ),
        stiffness in proptest::prop_oneof![
            proptest::strategy::Just(Param::Stiffness.domain().high),
            proptest::strategy::Just(f64::MIN_POSITIVE),
            1e-9f64..1e6,
        ],
        friction in 0.0f64..3.0,
        max_force in proptest::prop_oneof![
            proptest::strategy::Just(Param::MaxForce.domain().high),
            proptest::strategy::Just(f64::MIN_POSITIVE),
            1e-9f64..100.0,
        ],
    ) {
        let scene = thread_scene(Material::builder().stiffness(stiffness).damping(1.0).friction(friction, friction * 0.5).build().expect("a valid material"));
        let options = ProxyOptions::default().with_max_force(max_force).expect("a valid force");
        let mut proxy = Proxy::new(DVec3::new(0.0, 0.0, 0.2), options);
        let limit = if max_force.is_finite() && max_force >= haphe::proxy::MIN_MAX_FORCE { max_force } else { 0.0 };
        for hip in hips {
            let out = proxy.tick(&scene, hip, hip);
            proptest::prop_assert!(out.force.is_finite(), "{out:?}");
            proptest::prop_assert!(out.force.length() <= limit * (1.0 + 1e-12), "{out:?}");
            proptest::prop_assert!(out.proxy.is_finite(), "{out:?}");
        }
    }
}

/// A small blob scene for the property test (built once per case: cheap at 320 triangles).
fn thread_scene(material: Material) -> Scene {
    scene_of(shape(shapes::sphere(0.1, 2)), material)
}
