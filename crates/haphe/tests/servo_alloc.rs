//! The servo path allocates nothing with the device and the statistics in the loop: the
//! simulated hand exploring two textured objects (with a clutch held twice) under every kind
//! of force effect, one of them moving by
//! script, another moved and re-inserted by edits from "another thread", with tick timing
//! and counters, run in simulation mode on this thread under a counting allocator; and the
//! same for replay.

use std::sync::Arc;

use haphe::DVec3;
use haphe::map::MapOptions;
use haphe::mesh::shapes::Catalog;
use haphe::mesh::{Surface, SurfaceOptions};
use haphe::scene::{Edit, Material, ObjectId, Pose, Returned, Scene, SceneObject, Shape};
use haphe::servo::{
    HandOptions, HipTrace, Motion, ObjectMotion, PathKind, ReplayDevice, Servo, ServoOptions,
    SimulatedHand, TickRecord, scripted_path,
};

fn shape(which: Catalog, triangles: usize) -> Arc<Shape> {
    let surface = Surface::new(which.with_triangles(triangles), &SurfaceOptions::default())
        .expect("a usable surface");
    Arc::new(Shape::build(surface, &MapOptions::default()).expect("a map"))
}

#[test]
fn servo_ticks_allocate_nothing() {
    let material = Material::builder()
        .stiffness(800.0)
        .damping(1.0)
        .friction(0.5, 0.3)
        .build()
        .expect("a valid material");
    let blob = shape(Catalog::Blob, 20_000);
    let plate = shape(Catalog::ThinPlate, 5_000);
    let torus = shape(Catalog::Torus, 5_000);
    let (mut scene, mut editor) = Scene::new(8);
    scene
        .insert(
            SceneObject::new(ObjectId(0), blob, Pose::IDENTITY, material)
                .with_texture("noise:0.0001:0.002".parse().expect("a valid texture")),
        )
        .expect("room");
    let plate_pose = Pose::from_translation(DVec3::new(0.3, 0.0, 0.0)).expect("a valid pose");
    scene
        .insert(
            SceneObject::new(ObjectId(1), plate, plate_pose, material)
                .with_texture("sine:0.0002:0.002".parse().expect("a valid texture")),
        )
        .expect("room");
    // Every kind of effect, evaluated on the servo path.
    for spec in [
        "vibration:150:0.3",
        "viscosity:1:inside:0",
        "viscosity:1:box:-0.1:-0.1:-0.1:0:0:0",
        "spring:5:0:0:0.1",
        "magnet:0.005:0.3",
        "constant:0:0:-0.1",
        "stick-slip",
    ] {
        scene
            .add_effect(spec.parse().expect("a valid effect"))
            .expect("room for the effect");
    }
    let path = scripted_path(PathKind::Explore, &scene, 20.0, 5).expect("a path");
    // The clutch held twice: its presses are read and its offset moved on the servo path.
    let hand = SimulatedHand::new(path, HandOptions::default())
        .press(0, 3.0, 3.1)
        .and_then(|h| h.press(0, 11.0, 11.1))
        .expect("valid presses");
    let options = ServoOptions::default().with_clutch_button(Some(0));
    let mut servo = Servo::new(hand, scene, options).expect("servo");
    servo.set_motions(vec![ObjectMotion {
        id: ObjectId(1),
        base: plate_pose,
        motion: Motion::Oscillating {
            amplitude: DVec3::new(0.0, 0.0, 0.005),
            frequency: 1.0,
        },
    }]);

    let mut records = vec![TickRecord::default(); 20_000];
    let mut spare = Some(SceneObject::new(
        ObjectId(2),
        torus,
        Pose::from_translation(DVec3::new(-0.3, 0.0, 0.0)).expect("a valid pose"),
        material,
    ));
    let mut total = 0;
    let mut n = 0usize;
    for chunk in 0..20 {
        // Another thread's edits, sent between blocks of ticks.
        if let Some(o) = spare.take() {
            let _ = editor.send(Edit::Insert(o));
        } else {
            let _ = editor.send(Edit::Remove(ObjectId(2)));
        }
        let _ = editor.send(Edit::SetPose(
            ObjectId(0),
            Pose::from_translation(DVec3::new(0.0, 0.0, 1e-4 * f64::from(chunk)))
                .expect("a valid pose"),
        ));
        let info = allocation_counter::measure(|| {
            servo.run_simulated(1_000, |r| {
                records[n] = *r;
                n += 1;
            });
        });
        total += info.count_total;
        for r in editor.collect() {
            if let Returned::Removed(o) = r {
                spare = Some(o);
            }
        }
    }
    let contact = records.iter().filter(|r| r.in_contact()).count();
    let stats = servo.stats();
    println!(
        "{n} ticks, {contact} in contact, compute p50 {} ns p99 {} ns max {} ns",
        stats.compute.quantile(0.5),
        stats.compute.quantile(0.99),
        stats.compute.max()
    );
    let clutched = records.iter().filter(|r| r.clutch).count();
    assert_eq!(clutched, 200, "the clutch was held 0.2 s");
    assert_eq!(n, 20_000);
    assert_eq!(stats.compute.count(), 20_000);
    assert!(contact > 5_000, "{contact}");
    assert_eq!(total, 0, "the servo path allocated");

    // Replay of what was just recorded, on the same terms.
    let mut csv = Vec::new();
    for r in &records {
        r.write_csv(&mut csv).expect("write");
    }
    let trace = HipTrace::read("recorded", csv.as_slice()).expect("reads back");
    let mut scene = Scene::local(2);
    scene
        .insert(SceneObject::new(
            ObjectId(0),
            shape(Catalog::Blob, 2_000),
            Pose::IDENTITY,
            material,
        ))
        .expect("room");
    let mut servo =
        Servo::new(ReplayDevice::new(trace), scene, ServoOptions::default()).expect("servo");
    let info = allocation_counter::measure(|| {
        servo.run_simulated(25_000, |r| {
            std::hint::black_box(r);
        });
    });
    // 20 000 samples, and the tick that found the trace ended.
    assert_eq!(
        servo.stats().ticks,
        20_001,
        "the replay ends with the trace"
    );
    assert_eq!(info.count_total, 0, "the replay allocated");
}

/// Two hands on one servo, each with its own proxy, options and clutch, exploring two
/// objects of which one moves: every tick reads both, ticks both proxies and writes both
/// forces without allocating.
#[test]
fn two_devices_on_one_servo_allocate_nothing() {
    let blob = shape(Catalog::Blob, 5_000);
    let plate = shape(Catalog::ThinPlate, 2_000);
    let plate_pose = Pose::from_translation(DVec3::new(0.3, 0.0, 0.0)).expect("a valid pose");
    let scene = || {
        let mut scene = Scene::local(4);
        for (id, shape, pose) in [(0, &blob, Pose::IDENTITY), (1, &plate, plate_pose)] {
            let o = SceneObject::new(ObjectId(id), Arc::clone(shape), pose, Material::default());
            scene.insert(o).expect("room");
        }
        scene
    };
    let hand = |seed: u64, press: f64| {
        let path = scripted_path(PathKind::Explore, &scene(), 20.0, seed).expect("a path");
        SimulatedHand::new(path, HandOptions::default())
            .press(0, press, press + 0.1)
            .expect("a valid press")
    };
    let options = ServoOptions::default().with_clutch_button(Some(0));
    let hands = vec![(hand(5, 3.0), options), (hand(6, 7.0), options)];
    let mut servo = Servo::with_devices(hands, scene()).expect("two hands");
    servo.set_motions(vec![ObjectMotion {
        id: ObjectId(1),
        base: plate_pose,
        motion: Motion::Oscillating {
            amplitude: DVec3::new(0.0, 0.0, 0.005),
            frequency: 1.0,
        },
    }]);
    let mut contact = [0usize; 2];
    let mut clutched = [0usize; 2];
    let mut n = 0usize;
    let info = allocation_counter::measure(|| {
        servo.run_simulated(10_000, |r| {
            let d = r.device as usize;
            contact[d] += usize::from(r.in_contact());
            clutched[d] += usize::from(r.clutch);
            n += 1;
        });
    });
    println!("{n} records, contact {contact:?}");
    assert_eq!(n, 20_000, "one record per device per tick");
    assert!(contact.iter().all(|&c| c > 1_000), "{contact:?}");
    assert_eq!(clutched, [100, 100], "each clutch held 0.1 s");
    assert_eq!(
        info.count_total, 0,
        "the servo path of two devices allocated"
    );
}
