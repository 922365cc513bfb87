//! The servo path with the view's hand-offs allocates nothing: the mouse device (read
//! through the triple buffer while another thread writes points into it) inside the timing
//! wrapper (a wait-free push per tick), ticked under a counting allocator, with the sphere
//! moved by a script (the view draws moving objects from the same motions, on its pump
//! thread: the servo hands nothing more over for them); and a volume the mouse cuts, each
//! new version of its shape made off the servo path and handed over through the scene's
//! editor as the live view's cutting thread does.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use haphe::DVec3;
use haphe::glam::DAffine3;
use haphe::map::MapOptions;
use haphe::scene::{Edit, Material, ObjectId, Pose, Scene, SceneObject};
use haphe::servo::{Device, Motion, ObjectMotion, Servo, ServoOptions, TickRecord};
use haphe::volume::{CutOptions, Cutter, Volume};
use haphe_view::{MouseDevice, Timed};

#[test]
fn mouse_ticks_with_the_view_hand_offs_allocate_nothing() {
    let scene = haphe::verify::sphere_scene(2_000, Material::default()).expect("the sphere scene");
    let (mouse, mut handle) =
        MouseDevice::new(DVec3::new(0.0, 0.0, 0.15), DVec3::splat(-1.0), DVec3::ONE);
    let device: Box<dyn Device> = Box::new(mouse);
    let (timed, mut timings) = Timed::new(device);
    let mut servo = Servo::new(timed, scene, ServoOptions::default()).expect("servo");
    servo.set_motions(vec![ObjectMotion {
        id: ObjectId(0),
        base: Pose::IDENTITY,
        motion: Motion::Oscillating {
            amplitude: DVec3::new(0.0, 0.0, 0.005),
            frequency: 1.0,
        },
    }]);

    // "The page": another thread moves the point down into the sphere and out again.
    let done = Arc::new(AtomicBool::new(false));
    let stop = Arc::clone(&done);
    let writer = std::thread::spawn(move || {
        let mut k = 0u32;
        while !stop.load(Ordering::Relaxed) {
            let z = 0.05 + 0.1 * (f64::from(k % 100) / 50.0 - 1.0).abs();
            handle.set(DVec3::new(0.01, 0.0, z));
            k += 1;
            std::thread::sleep(Duration::from_micros(300));
        }
    });

    let (mut total, mut contact, mut timed_ticks) = (0, 0usize, 0usize);
    for _ in 0..40 {
        let info = allocation_counter::measure(|| {
            servo.run_simulated(500, |r| contact += usize::from(r.in_contact()));
        });
        total += info.count_total;
        while timings.pop().is_ok() {
            timed_ticks += 1;
        }
        std::thread::sleep(Duration::from_millis(1));
    }
    done.store(true, Ordering::Relaxed);
    writer.join().expect("writer");
    println!("20000 ticks, {contact} in contact, {timed_ticks} timed");
    assert_eq!(total, 0, "the servo path allocated");
    // The counter counts: an allocation here is seen.
    let seen = allocation_counter::measure(|| drop(std::hint::black_box(vec![0u8; 64])));
    assert!(seen.count_total >= 1);
    assert!(contact > 1_000, "{contact}");
    assert_eq!(timed_ticks, 20_000);
}

/// A block of 20³ voxels of 1 mm, material (1) inside a margin of 3, air (0) around it.
fn block() -> Volume {
    let n = 20;
    let inside = |i: usize| (3..n - 3).contains(&i);
    let mut values = Vec::with_capacity(n * n * n);
    for k in 0..n {
        for j in 0..n {
            for i in 0..n {
                values.push(f32::from(u8::from(inside(i) && inside(j) && inside(k))));
            }
        }
    }
    let to_world = DAffine3::from_scale(DVec3::splat(1e-3));
    Volume::new([n; 3], values, to_world, 0.5).expect("a volume")
}

/// The mouse presses into a volume while a cutter, off the servo path, removes what it
/// presses on and hands each new version of the shape to the servo through the scene's
/// editor: the ticks, which take each version from the editor and hand the old one back,
/// allocate nothing.
#[test]
fn mouse_ticks_on_a_volume_being_cut_allocate_nothing() {
    let volume = block();
    // Placed with the centre of its grid at the origin, as the command places a volume.
    let pose = Pose::from_translation(-volume.centre()).expect("a pose");
    let mut cutter = Cutter::new("block", volume, MapOptions::default()).expect("a cutter");
    let tool_radius = 0.002;
    cutter
        .set_options(CutOptions::new(tool_radius, 0.5).expect("options"))
        .expect("options set");
    let first = cutter.shape().surface().triangle_count();
    let (mut scene, mut editor) = Scene::new(4);
    scene
        .insert(SceneObject::new(
            ObjectId(0),
            Arc::clone(cutter.shape()),
            pose,
            Material::default(),
        ))
        .map_err(|(e, _)| e)
        .expect("room");
    let (mouse, mut handle) = MouseDevice::new(
        DVec3::new(0.0, 0.0, 0.03),
        DVec3::splat(-0.1),
        DVec3::splat(0.1),
    );
    let device: Box<dyn Device> = Box::new(mouse);
    let (timed, mut timings) = Timed::new(device);
    let options = ServoOptions::default();
    let proxy = options
        .proxy()
        .with_tool_radius(tool_radius)
        .expect("a radius");
    let mut servo = Servo::new(timed, scene, options.with_proxy(proxy)).expect("servo");

    let mut records: Vec<TickRecord> = Vec::with_capacity(500);
    let (mut total, mut sent, mut contact) = (0, 0u32, 0usize);
    for block in 0..40 {
        // "The page" moves the point from above the material (its top at z = 7 mm) down
        // to 3 mm, where it holds.
        let z = (0.015 - 0.001 * f64::from(block)).max(0.003);
        handle.set(DVec3::new(0.0, 0.0, z));
        records.clear();
        let info = allocation_counter::measure(|| {
            servo.run_simulated(500, |r| records.push(*r));
        });
        total += info.count_total;
        while timings.pop().is_ok() {}
        // The cutting thread's part, off the servo path: the presses, the next version.
        for r in &records {
            if r.object == Some(ObjectId(0)) {
                contact += 1;
                cutter.press(pose.to_object(r.proxy), r.force.length(), 1e-3);
            }
        }
        for _ in editor.collect() {}
        if let Some(shape) = cutter.refresh().expect("material is left") {
            sent += u32::from(editor.send(Edit::SetShape(ObjectId(0), shape)).is_ok());
        }
    }
    let now = servo.scene().objects()[0].shape.surface().triangle_count();
    println!(
        "20000 ticks, {contact} in contact; {sent} versions sent, {} voxels removed, {first} triangles then {now}",
        cutter.removed()
    );
    assert_eq!(total, 0, "the servo path allocated");
    assert!(contact > 1_000, "{contact}");
    assert!(sent >= 2 && cutter.removed() > 0, "{sent}");
    // The servo ticked against the versions sent.
    assert!(servo.scene().objects()[0].shape.version() > 0);
    assert_ne!(now, first);
}
