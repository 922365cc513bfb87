//! The servo path with the view's hand-offs allocates nothing: the mouse device (read
//! through the triple buffer while another thread writes points into it) inside the timing
//! wrapper (a wait-free push per tick), ticked under a counting allocator, with the sphere
//! moved by a script (the view draws moving objects from the same motions, on its pump
//! thread: the servo hands nothing more over for them).

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use haphe::DVec3;
use haphe::scene::{Material, ObjectId, Pose};
use haphe::servo::{Device, Motion, ObjectMotion, Servo, ServoOptions};
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
