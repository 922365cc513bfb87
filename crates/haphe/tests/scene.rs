//! Scenes edited from another thread while the servo thread ticks, and force shading.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use haphe::DVec3;
use haphe::map::MapOptions;
use haphe::mesh::shapes;
use haphe::mesh::{Surface, SurfaceOptions};
use haphe::proxy::{Proxy, ProxyOptions};
use haphe::scene::{
    Edit, EditError, Material, ObjectId, ObjectKey, Pose, Returned, Scene, SceneObject, Shape,
};

fn shape(mesh: haphe::mesh::Mesh) -> Arc<Shape> {
    let surface = Surface::new(mesh, &SurfaceOptions::default()).expect("a usable surface");
    Arc::new(Shape::build(surface, &MapOptions::default()).expect("a map"))
}

/// An editor thread inserts, moves and removes objects while the servo thread ticks; every
/// object that leaves the scene comes back to the editor, and shapes are freed there.
#[test]
fn edits_from_another_thread() {
    let ball = shape(shapes::sphere(0.05, 3));
    let (mut scene, mut editor) = Scene::new(4);
    let done = Arc::new(AtomicBool::new(false));
    let servo_done = done.clone();
    let servo = std::thread::spawn(move || {
        let mut proxy = Proxy::new(DVec3::new(0.0, 0.0, 0.2), ProxyOptions::default());
        let mut ticks = 0u64;
        let mut contacts = 0u64;
        let mut applied = 0usize;
        while !servo_done.load(Ordering::Acquire) || ticks < 10_000 {
            applied += scene.begin_tick();
            // The device rests 1 cm below where the ball's top passes.
            let out = proxy.tick(&scene, DVec3::new(0.0, 0.0, 0.04), DVec3::ZERO);
            assert!(out.force.is_finite());
            contacts += u64::from(out.contact.is_some());
            ticks += 1;
        }
        // Edits sent before `done` was set may still wait (a loaded machine can leave the
        // servo no turn between the last send and `done`): apply them before counting.
        loop {
            let more = scene.begin_tick();
            if more == 0 {
                break;
            }
            applied += more;
        }
        (ticks, contacts, applied, scene)
    });
    let mut returned = 0;
    let mut sent = 0;
    for round in 0..200u32 {
        let id = ObjectId(round % 3);
        let object = SceneObject::new(id, ball.clone(), Pose::IDENTITY, Material::default());
        let mut edits = vec![
            Edit::Insert(object),
            Edit::SetPose(
                id,
                Pose::from_translation(DVec3::new(0.0, 0.0, -0.01)).expect("a valid pose"),
            ),
            Edit::Remove(ObjectId((round + 1) % 3)),
        ];
        while let Some(edit) = edits.pop() {
            match editor.send(edit) {
                Ok(()) => sent += 1,
                Err((EditError::Busy, edit)) => {
                    edits.push(edit);
                    std::thread::yield_now();
                }
                Err((e, _)) => panic!("{e}"),
            }
            returned += editor.collect().len();
        }
        std::thread::sleep(std::time::Duration::from_micros(200));
    }
    done.store(true, Ordering::Release);
    let (ticks, contacts, applied, scene) = servo.join().expect("the servo thread");
    returned += editor.collect().len();
    assert_eq!(applied, sent, "every edit applied");
    // Inserted minus still in the scene came back (removed, or refused as duplicates).
    assert_eq!(returned + scene.objects().len(), 200);
    assert!(ticks >= 10_000);
    assert!(contacts > 0, "the ball was touched");
    // Only the scene and this thread still hold the shape.
    assert_eq!(Arc::strong_count(&ball), 1 + scene.objects().len());
}

#[test]
fn a_full_scene_refuses_and_hands_back() {
    let ball = shape(shapes::sphere(0.05, 1));
    let (mut scene, mut editor) = Scene::new(1);
    let object = |id| {
        SceneObject::new(
            ObjectId(id),
            ball.clone(),
            Pose::IDENTITY,
            Material::default(),
        )
    };
    editor
        .send(Edit::Insert(object(1)))
        .expect("room in the ring");
    scene.begin_tick();
    editor
        .send(Edit::Insert(object(2)))
        .expect("room in the ring");
    scene.begin_tick();
    let back = editor.collect();
    assert!(
        matches!(back.as_slice(), [Returned::Refused(o, EditError::Full)] if o.id == ObjectId(2))
    );
    assert_eq!(scene.objects().len(), 1);
}

/// Force shading: on a coarse sphere, the rendered force on a face is much closer to the
/// true (radial) normal than the flat face normal is.
#[test]
fn force_shading_follows_the_smooth_normal() {
    // 320 triangles: every dihedral angle below the 30° crease angle (the 80-triangle
    // sphere has 42° creases, which shading rightly keeps sharp).
    let ball = shape(shapes::sphere(0.1, 2));
    let mut scene = Scene::local(1);
    scene
        .insert(SceneObject::new(
            ObjectId(0),
            ball,
            Pose::IDENTITY,
            Material::default(),
        ))
        .expect("room");
    let mut worst_face = 0.0f64;
    let mut worst_force = 0.0f64;
    let mut random = haphe::rng::SplitMix64::new(9);
    for _ in 0..200 {
        let dir = random.unit_vector();
        let mut proxy = Proxy::new(dir * 0.15, ProxyOptions::default());
        let out = proxy.tick(&scene, dir * 0.093, DVec3::ZERO);
        let Some(c) = out.contact.filter(|c| c.constraints == 1) else {
            continue;
        };
        let radial = c.point.normalize();
        worst_face = worst_face.max(c.normal.angle_between(radial));
        worst_force = worst_force.max(out.force.normalize().angle_between(radial));
    }
    assert!(worst_face > 0.08, "facets: {worst_face}");
    println!("shaded {worst_force} rad, flat {worst_face} rad");
    assert!(
        worst_force < 0.5 * worst_face,
        "shaded {worst_force} vs flat {worst_face}"
    );
}

/// Keys move the object they name: made before the object is inserted, after a removal
/// moved it and another object took its index (a stale index), in a batch; never another
/// object, and a key of a removed object moves nothing.
#[test]
fn keys_move_the_object_they_name() {
    let ball = shape(shapes::sphere(0.05, 1));
    let mut scene = Scene::local(8);
    let at = |x: f64| Pose::from_translation(DVec3::new(x, 0.0, 0.0)).expect("a valid pose");
    let mut early = ObjectKey::new(ObjectId(7));
    assert!(
        !scene.set_pose_keyed(&mut early, at(1.0)),
        "no object 7 yet"
    );
    for k in 0..5 {
        let o = SceneObject::new(ObjectId(k), ball.clone(), at(0.0), Material::default());
        scene.insert(o).expect("room");
    }
    let o = SceneObject::new(ObjectId(7), ball.clone(), at(0.0), Material::default());
    scene.insert(o).expect("room");
    let x_of = |scene: &Scene, id: u32| {
        let i = scene.index_of(ObjectId(id)).expect("in the scene");
        scene.objects()[i].pose.translation().x
    };
    assert!(scene.set_pose_keyed(&mut early, at(1.0)));
    assert_eq!(x_of(&scene, 7), 1.0);
    assert_eq!(early, scene.key_of(ObjectId(7)).expect("a key"));

    // Objects 0, 1, 2, 3, 4, 7: removing 1 puts 7 in its place, and 8 takes 7's old
    // index, where `early` points.
    scene.remove(ObjectId(1)).expect("removed");
    let o = SceneObject::new(ObjectId(8), ball.clone(), at(0.0), Material::default());
    scene.insert(o).expect("room");
    assert!(scene.set_pose_keyed(&mut early, at(-7.0)));
    assert_eq!(x_of(&scene, 7), -7.0);
    for id in [0, 2, 3, 4, 8] {
        assert_eq!(x_of(&scene, id), 0.0, "object {id} moved");
    }
    assert_eq!(early, scene.key_of(ObjectId(7)).expect("a key"));
    let key3 = scene.key_of(ObjectId(3)).expect("a key");
    assert_eq!(key3.id(), ObjectId(3));

    scene.begin_tick();
    let mut moves = [
        (ObjectKey::new(ObjectId(4)), at(4.0)),
        (key3, at(-3.0)),
        (ObjectKey::new(ObjectId(1)), at(9.0)),
        (early, at(7.0)),
    ];
    assert_eq!(scene.set_poses(&mut moves), 3, "object 1 is gone");
    for (id, x) in [(4, 4.0), (3, -3.0), (7, 7.0), (0, 0.0), (2, 0.0), (8, 0.0)] {
        assert_eq!(x_of(&scene, id), x, "object {id}");
    }
    let moved: Vec<ObjectId> = scene
        .objects()
        .iter()
        .filter(|o| o.moved())
        .map(|o| o.id)
        .collect();
    // In index order: 7 took index 1.
    assert_eq!(moved, [ObjectId(7), ObjectId(3), ObjectId(4)]);
    // Setting an object's pose to where it already is moves nothing.
    scene.begin_tick();
    assert!(scene.set_pose(ObjectId(4), at(4.0)));
    assert!(scene.objects().iter().all(|o| !o.moved()));
}

/// The proxy keeps the objects it touches by index; removing an object puts the last one
/// in its place. A hold on the object that moved goes on as before, and a hold on a
/// removed object is forgotten, never carried over to the object that took its index.
#[test]
fn a_held_contact_follows_its_object_across_removals() {
    let ball = shape(shapes::Catalog::Sphere.with_triangles(2_000));
    let mut scene = Scene::local(8);
    for k in 0..4 {
        let pose = Pose::from_translation(DVec3::new(k as f64, 0.0, 0.0)).expect("a valid pose");
        let object = SceneObject::new(ObjectId(k), ball.clone(), pose, Material::default());
        scene.insert(object).expect("room");
    }
    // Press 15 mm into the last sphere's top (beyond the 6.6 mm saturation depth).
    let top = DVec3::new(3.0, 0.0, 0.12);
    let mut proxy = Proxy::new(top, ProxyOptions::default());
    let mut out = None;
    for k in 0..=100 {
        let hip = top - DVec3::Z * (0.035 * k as f64 / 100.0);
        scene.begin_tick();
        out = Some(proxy.tick(&scene, hip, DVec3::ZERO));
    }
    let pressed = out.expect("ticked");
    let hip = top - DVec3::Z * 0.035;
    assert!(pressed.status.deep_hold, "{pressed:?}");
    assert_eq!(pressed.contact.map(|c| c.id), Some(ObjectId(3)));
    // Remove the first sphere: the held one takes index 0.
    assert!(scene.remove(ObjectId(0)).is_some());
    assert_eq!(scene.index_of(ObjectId(3)), Some(0));
    scene.begin_tick();
    let out = proxy.tick(&scene, hip, DVec3::ZERO);
    assert!(out.status.deep_hold, "{out:?}");
    assert_eq!(
        out.contact.map(|c| (c.object, c.id)),
        Some((0, ObjectId(3)))
    );
    assert!(
        out.force.distance(pressed.force) < 1e-9,
        "{out:?} {pressed:?}"
    );
    // Remove the held sphere: sphere 2 takes its index, far from the hand.
    assert!(scene.remove(ObjectId(3)).is_some());
    scene.begin_tick();
    let out = proxy.tick(&scene, hip, DVec3::ZERO);
    assert!(!out.status.deep_hold, "{out:?}");
    assert!(out.contact.is_none(), "{out:?}");
    assert_eq!(out.force, DVec3::ZERO);
}
