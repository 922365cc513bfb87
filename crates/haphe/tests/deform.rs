//! Shapes that deform while they are touched: the proxy (point and tool) against the
//! brute-force oracle at every tick of a breathing, dented or twisting shape; queries on
//! deformed shapes against brute force; bad deformations refused; the editor's hand-off.

use std::sync::Arc;

use haphe::DVec3;
use haphe::map::MapOptions;
use haphe::mesh::shapes::Catalog;
use haphe::mesh::{Surface, SurfaceOptions};
use haphe::proxy::ProxyOptions;
use haphe::query::nearest_within_brute_force;
use haphe::rng::SplitMix64;
use haphe::scene::{
    DeformError, Edit, EditError, Material, ObjectId, Pose, Returned, Scene, SceneObject, Shape,
};
use haphe::verify::{
    Deformation, SegmentKind, check_crossings, check_deforming, check_inside,
    haptic_path_in_contact, one_object_scene,
};
use proptest::prelude::*;

fn shape(catalog: Catalog, triangles: usize) -> Arc<Shape> {
    let surface = Surface::new(
        catalog.with_triangles(triangles),
        &SurfaceOptions::default(),
    )
    .expect("a usable surface");
    Arc::new(
        Shape::build(surface, &MapOptions::default())
            .expect("a map")
            .with_clear_zones(),
    )
}

fn scene(catalog: Catalog, triangles: usize) -> Scene {
    one_object_scene(shape(catalog, triangles), Material::DEFAULT, 2).expect("room")
}

/// The fast proxy against the oracle while `deformation` moves `catalog`'s shape at
/// every tick: pressing paths 0–10 mm deep (so the hand is met by the moving surface
/// and leaves it), point and a 2 mm tool.
fn check(catalog: Catalog, deformation: Deformation, ticks: usize, seed: u64) {
    for radius in [0.0, 2e-3] {
        let mut scene = scene(catalog, 2000);
        let path = haptic_path_in_contact(&scene, ticks, (0.02, 0.3), (-2e-3, 10e-3), 1e3, seed);
        let options = ProxyOptions::default()
            .with_tool_radius(radius)
            .expect("a radius in its domain");
        let check = check_deforming(&mut scene, deformation, &path, options, 1e3)
            .expect("deformations within the grid's limits");
        let name = deformation.name();
        println!("{catalog:?} {name} r {radius}: {check:?}");
        assert!(
            check.contact_ticks > ticks / 5,
            "{name} r {radius}: too little contact: {check:?}"
        );
        assert_eq!(check.mismatches, 0, "{name} r {radius}: {check:?}");
        assert_eq!(check.inside, 0, "{name} r {radius}: {check:?}");
        assert_eq!(check.bad_forces, 0, "{name} r {radius}: {check:?}");
        assert_eq!(
            scene.objects()[0].shape.version(),
            ticks as u64,
            "one deformation a tick"
        );
    }
}

#[test]
fn a_breathing_sphere_with_a_travelling_dent_is_felt_exactly_at_every_tick() {
    check(Catalog::Sphere, Deformation::BreatheAndDent, 2000, 1);
}

#[test]
fn a_breathing_sphere_and_a_travelling_dent_alone() {
    check(Catalog::Sphere, Deformation::Breathe, 1000, 2);
    check(Catalog::Blob, Deformation::Dent, 1000, 3);
}

#[test]
fn a_twisting_box_is_felt_exactly_at_every_tick() {
    check(Catalog::Box, Deformation::Twist, 1500, 4);
}

/// A proxy resting on a face that moves rides it: the hand held still just under a
/// surface that rises pushes the proxy up with the surface, a skin above it.
#[test]
fn a_proxy_resting_on_a_rising_face_rides_it() {
    let mut scene = scene(Catalog::Box, 500);
    let id = scene.objects()[0].id;
    let rest = scene.objects()[0].shape.surface().vertices().to_vec();
    let top = rest.iter().map(|p| p.z).fold(f64::MIN, f64::max);
    let mut proxy =
        haphe::proxy::Proxy::new(DVec3::new(0.01, 0.01, top + 0.01), ProxyOptions::default());
    let hip = DVec3::new(0.01, 0.01, top - 0.002);
    for tick in 0..200u64 {
        let lift = 1e-5 * tick as f64;
        let lifted: Vec<DVec3> = rest
            .iter()
            .map(|&p| {
                if p.z > top - 1e-9 {
                    p + DVec3::Z * lift
                } else {
                    p
                }
            })
            .collect();
        scene.deform(id, &lifted).expect("a deformation");
        scene.begin_tick();
        let out = proxy.tick(&scene, hip, DVec3::ZERO);
        if tick > 20 {
            let contact = out.contact.expect("in contact");
            assert!(
                (out.proxy.z - (top + lift)).abs() < 1e-5,
                "tick {tick}: proxy at z {} for a face at {}",
                out.proxy.z,
                top + lift
            );
            assert!(contact.normal.z > 0.99);
            assert_eq!(contact.version, tick + 1, "the tick felt this deformation");
            assert!(out.force.z > 0.0);
        }
    }
}

#[test]
fn bad_deformations_are_refused_and_leave_the_scene_unchanged() {
    let mut scene = scene(Catalog::Sphere, 320);
    let id = scene.objects()[0].id;
    let before = Arc::clone(&scene.objects()[0].shape);
    let mut vertices = before.surface().vertices().to_vec();
    let n = vertices.len();
    assert_eq!(
        scene.deform(id, &vertices[..n - 1]),
        Err(DeformError::Count {
            given: n - 1,
            vertices: n
        })
    );
    vertices[7].y = f64::NAN;
    assert_eq!(
        scene.deform(id, &vertices),
        Err(DeformError::NotFinite { row: 7 })
    );
    vertices[7].y = f64::INFINITY;
    let message = scene.deform(id, &vertices).unwrap_err().to_string();
    assert!(message.contains("row 7"), "{message}");
    vertices[7].y = 1e12;
    assert_eq!(
        scene.deform(id, &vertices),
        Err(DeformError::NotFinite { row: 7 })
    );
    assert_eq!(
        scene.deform(ObjectId(99), before.surface().vertices()),
        Err(DeformError::UnknownObject(99))
    );
    assert_eq!(
        scene.deform_at(id, &[0, 1], &[DVec3::ZERO]),
        Err(DeformError::IndicesCount {
            indices: 2,
            positions: 1
        })
    );
    assert_eq!(
        scene.deform_at(id, &[3, n as u32], &[DVec3::ZERO, DVec3::ZERO]),
        Err(DeformError::Index {
            row: 1,
            index: n as u64,
            vertices: n
        })
    );
    assert!(Arc::ptr_eq(&scene.objects()[0].shape, &before));
    assert_eq!(scene.objects()[0].shape.version(), 0);
}

#[test]
fn deforming_one_object_leaves_the_others_sharing_its_shape() {
    let ball = shape(Catalog::Sphere, 320);
    let mut scene = Scene::local(2);
    for (id, x) in [(1, 0.0), (2, 0.5)] {
        let pose = Pose::from_translation(DVec3::new(x, 0.0, 0.0)).expect("a pose");
        let object = SceneObject::new(ObjectId(id), Arc::clone(&ball), pose, Material::DEFAULT);
        scene.insert(object).expect("room");
    }
    let bigger: Vec<DVec3> = ball.surface().vertices().iter().map(|&p| 1.1 * p).collect();
    scene.deform(ObjectId(1), &bigger).expect("a deformation");
    let (one, two) = (&scene.objects()[0].shape, &scene.objects()[1].shape);
    assert_eq!(one.version(), 1);
    assert!(Arc::ptr_eq(two, &ball));
    assert_eq!(ball.version(), 0);
    assert_eq!(two.surface().vertices()[0], ball.surface().vertices()[0]);
    assert!((one.bound_radius() - 1.1 * ball.bound_radius()).abs() < 1e-12);
    // Subsets move only what they name.
    scene
        .deform_at(ObjectId(2), &[5], &[DVec3::new(0.0, 0.0, 0.2)])
        .expect("a deformation");
    let moved = scene.objects()[1].shape.surface().vertices();
    assert_eq!(moved[5], DVec3::new(0.0, 0.0, 0.2));
    assert_eq!(moved[4], ball.surface().vertices()[4]);
}

#[test]
fn a_deformation_sent_from_another_thread_comes_in_at_a_tick() {
    let ball = shape(Catalog::Sphere, 320);
    let (mut scene, mut editor) = Scene::new(4);
    let object = SceneObject::new(
        ObjectId(1),
        Arc::clone(&ball),
        Pose::IDENTITY,
        Material::DEFAULT,
    );
    scene.insert(object).expect("room");
    let grown = |shape: &Shape, by: f64| {
        let vertices: Vec<DVec3> = shape.surface().vertices().iter().map(|&p| by * p).collect();
        Arc::new(shape.deformed(&vertices).expect("a deformation"))
    };
    let sender = std::thread::spawn(move || {
        let first = grown(&ball, 1.2);
        for edit in [
            Edit::SetShape(ObjectId(1), Arc::clone(&first)),
            Edit::SetShape(ObjectId(1), shape(Catalog::Box, 500)),
            Edit::SetShape(ObjectId(7), ball),
        ] {
            editor.send(edit).expect("room in the ring");
        }
        (editor, first)
    });
    let (mut editor, first) = sender.join().expect("the editor thread");
    assert_eq!(scene.objects()[0].shape.version(), 0, "not before a tick");
    assert_eq!(scene.begin_tick(), 3);
    assert!(Arc::ptr_eq(&scene.objects()[0].shape, &first));
    let back = editor.collect();
    assert_eq!(
        back.len(),
        2,
        "the shape before is kept for the proxy: {back:?}"
    );
    assert!(matches!(
        &back[0],
        Returned::RefusedShape(ObjectId(1), _, EditError::NotADeformation)
    ));
    assert!(matches!(
        &back[1],
        Returned::RefusedShape(ObjectId(7), _, EditError::UnknownObject)
    ));
    // The next deformation, a tick later, sends back the first shape.
    editor
        .send(Edit::SetShape(ObjectId(1), grown(&first, 0.9)))
        .expect("room in the ring");
    assert_eq!(scene.begin_tick(), 1);
    assert_eq!(scene.objects()[0].shape.version(), 2);
    let back = editor.collect();
    assert!(
        matches!(&back[..], [Returned::Replaced(ObjectId(1), s)] if s.version() == 0),
        "{back:?}"
    );
}

/// Material cut away: a box replaced by a lower box with other triangles
/// ([`Shape::replacing`]). The proxy pressing on the top forgets the triangle it rested on
/// and follows the face down; a shape with other triangles not made to replace the
/// object's is refused.
#[test]
fn a_proxy_pressing_on_material_cut_away_follows_the_new_surface() {
    let cuboid = |height: f64, divisions: u32| {
        let mut mesh =
            haphe::mesh::shapes::cuboid(DVec3::new(0.02, 0.02, height / 2.0), [divisions; 3]);
        for v in &mut mesh.vertices {
            v.z += height / 2.0;
        }
        let surface = Surface::new(mesh, &SurfaceOptions::default()).expect("a usable surface");
        Shape::build(surface, &MapOptions::default()).expect("a map")
    };
    let first = Arc::new(cuboid(0.02, 4));
    let mut scene = one_object_scene(first.clone(), Material::DEFAULT, 2).expect("room");
    let id = scene.objects()[0].id;
    let mut proxy =
        haphe::proxy::Proxy::new(DVec3::new(0.003, 0.002, 0.03), ProxyOptions::default());
    let hip = DVec3::new(0.003, 0.002, 0.012);
    let mut current = first.clone();
    for tick in 0..300u64 {
        if tick > 0 && tick % 30 == 0 {
            let height = 0.02 - 7e-4 * (tick / 30) as f64;
            let next = Arc::new(cuboid(height, 3 + (tick / 30) as u32 % 3).replacing(&current));
            scene
                .replace(id, next.clone())
                .expect("a version replacing the object's");
            current = next;
        }
        scene.begin_tick();
        let out = proxy.tick(&scene, hip, DVec3::ZERO);
        let top = 0.02 - 7e-4 * (tick / 30) as f64;
        if tick % 30 > 10 {
            let contact = out.contact.expect("in contact");
            assert!(
                (out.proxy.z - top).abs() < 1e-5,
                "tick {tick}: proxy at z {} on a top at {top}",
                out.proxy.z
            );
            assert_eq!(contact.version, tick / 30);
        }
        assert!(out.proxy.z >= top - 1e-5, "tick {tick}: below the top");
    }
    let unrelated = Arc::new(cuboid(0.01, 5));
    assert_eq!(
        scene.replace(id, unrelated).err(),
        Some(EditError::NotADeformation)
    );
    assert_eq!(scene.objects()[0].shape.version(), current.version());
}

/// A deformation that leaves the map's grid grows it; the grown map still answers
/// inside exactly.
#[test]
fn a_shape_deformed_beyond_its_grid_grows_it() {
    let ball = shape(Catalog::Sphere, 1280);
    let stretched: Vec<DVec3> = ball
        .surface()
        .vertices()
        .iter()
        .map(|&p| DVec3::new(3.0 * p.x, p.y, p.z))
        .collect();
    let long = ball.deformed(&stretched).expect("a deformation");
    assert!(long.map().grid().max_corner().x > ball.map().grid().max_corner().x);
    let check = check_inside(long.surface(), long.map(), 4000, 9);
    assert_eq!(check.mismatches, 0, "{check:?}");
}

/// Random vertices of a shape moved by random amounts (up to a fifth of its size, so
/// that the surface may pass through itself): inside, first crossing and nearest
/// triangle equal brute force on the deformed mesh.
fn deformed_randomly(catalog: Catalog, seed: u64, fraction: f64, amount: f64) -> Shape {
    let base = shape(catalog, 1500);
    let mut random = SplitMix64::new(seed);
    let (lo, hi) = base.surface().bounds();
    let size = (hi - lo).max_element();
    let mut vertices = base.surface().vertices().to_vec();
    for p in &mut vertices {
        if random.next_unit() < fraction {
            *p += amount * size * random.next_unit() * random.unit_vector();
        }
    }
    base.deformed(&vertices).expect("a deformation")
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]
    #[test]
    fn queries_on_a_deformed_shape_equal_brute_force(
        catalog in prop::sample::select(vec![Catalog::Sphere, Catalog::Torus, Catalog::Box, Catalog::Blob]),
        seed in 0u64..1000,
        fraction in prop::sample::select(vec![0.01, 0.2, 1.0]),
        amount in prop::sample::select(vec![0.002, 0.05, 0.2]),
    ) {
        let s = deformed_randomly(catalog, seed, fraction, amount);
        let (surface, map) = (s.surface(), s.map());
        let inside = check_inside(surface, map, 1500, seed);
        prop_assert_eq!(inside.mismatches, 0, "{:?}", inside);
        for kind in [SegmentKind::Random, SegmentKind::ThroughVertex, SegmentKind::Short] {
            let crossing = check_crossings(surface, map, kind, 300, seed);
            prop_assert_eq!(crossing.mismatches, 0, "{:?}", crossing);
        }
        let mut random = SplitMix64::new(seed);
        let (lo, hi) = surface.bounds();
        for _ in 0..200 {
            let p = random.point_in(lo - 0.1 * (hi - lo), hi + 0.1 * (hi - lo));
            let radius = 0.05 * (hi - lo).max_element();
            let fast = haphe::query::nearest_within(surface, map, p, radius);
            let brute = nearest_within_brute_force(surface, p, radius);
            prop_assert_eq!(fast.map(|n| (n.triangle, n.distance)), brute.map(|n| (n.triangle, n.distance)));
        }
    }
}
