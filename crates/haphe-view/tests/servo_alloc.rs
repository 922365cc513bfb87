//! The servo path with the view's hand-offs allocates nothing: the mouse device (read
//! through the triple buffer while another thread writes points into it) inside the timing
//! wrapper (a wait-free push per tick), ticked under a counting allocator.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use haphe::DVec3;
use haphe::map::MapOptions;
use haphe::mesh::shapes::Catalog;
use haphe::mesh::{Surface, SurfaceOptions};
use haphe::scene::{Material, ObjectId, Pose, Scene, SceneObject, Shape};
use haphe::servo::{Device, Servo, ServoOptions};
use haphe_view::{MouseDevice, Timed};

#[test]
fn mouse_ticks_with_the_view_hand_offs_allocate_nothing() {
    let surface = Surface::new(
        Catalog::Sphere.with_triangles(2_000),
        &SurfaceOptions::default(),
    )
    .expect("surface");
    let shape = Arc::new(Shape::build(surface, &MapOptions::default()).expect("map"));
    shape.prepare_clear_zones();
    let mut scene = Scene::local(2);
    scene
        .insert(SceneObject::new(
            ObjectId(0),
            shape,
            Pose::IDENTITY,
            Material::default(),
        ))
        .map_err(|(e, _)| e)
        .expect("room");
    let (mouse, mut handle) =
        MouseDevice::new(DVec3::new(0.0, 0.0, 0.15), DVec3::splat(-1.0), DVec3::ONE);
    let device: Box<dyn Device> = Box::new(mouse);
    let (timed, mut timings) = Timed::new(device);
    let mut servo = Servo::new(timed, scene, ServoOptions::default()).expect("servo");

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
