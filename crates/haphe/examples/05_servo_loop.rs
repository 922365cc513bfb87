//! The servo loop without hardware: a simulated hand presses on a sphere while a plate
//! beside it rocks up and down; first on a virtual clock (as fast as possible, exactly
//! repeatable), then for half a second on a real-time thread at 4 kHz, with its timing.
//!
//! ```sh
//! cargo run --release --example 05_servo_loop
//! ```

use std::sync::Arc;

use haphe::DVec3;
use haphe::map::MapOptions;
use haphe::mesh::shapes::Catalog;
use haphe::mesh::{Surface, SurfaceOptions};
use haphe::scene::{Material, ObjectId, Pose, Scene, SceneObject, Shape};
use haphe::servo::{
    HandOptions, Motion, ObjectMotion, PathKind, RealtimeOptions, Servo, ServoLoop, ServoOptions,
    SimulatedHand, scripted_path,
};

fn shape(which: Catalog) -> Result<Arc<Shape>, Box<dyn std::error::Error>> {
    let surface = Surface::new(which.with_triangles(5_000), &SurfaceOptions::default())?;
    Ok(Arc::new(Shape::build(surface, &MapOptions::default())?))
}

/// A sphere at the origin and a thin plate beside it, oscillating 5 mm up and down.
fn make_scene() -> Result<(Scene, ObjectMotion), Box<dyn std::error::Error>> {
    let mut scene = Scene::local(2);
    let material = Material::builder()
        .stiffness(800.0)
        .damping(1.0)
        .friction(0.4, 0.3)
        .build()
        .expect("a valid material");
    scene
        .insert(SceneObject::new(
            ObjectId(0),
            shape(Catalog::Sphere)?,
            Pose::IDENTITY,
            material,
        ))
        .map_err(|(e, _)| e)?;
    let plate_pose = Pose::from_translation(DVec3::new(0.3, 0.0, 0.0)).expect("a valid pose");
    scene
        .insert(SceneObject::new(
            ObjectId(1),
            shape(Catalog::ThinPlate)?,
            plate_pose,
            material,
        ))
        .map_err(|(e, _)| e)?;
    let rocking = ObjectMotion {
        id: ObjectId(1),
        base: plate_pose,
        motion: Motion::Oscillating {
            amplitude: DVec3::new(0.0, 0.0, 0.005),
            frequency: 1.0,
        },
    };
    Ok((scene, rocking))
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // 1. Simulation mode: 3 s of a press at 1 kHz on the virtual clock.
    let (scene, rocking) = make_scene()?;
    let path = scripted_path(PathKind::Press, &scene, 3.0, 0)?;
    let hand = SimulatedHand::new(path, HandOptions::default());
    let mut servo = Servo::new(hand, scene, ServoOptions::default())?;
    servo.set_motions(vec![rocking]);
    let (mut deepest, mut strongest, mut contact) = (0.0f64, 0.0f64, 0);
    servo.run_simulated(3_000, |r| {
        deepest = deepest.max(r.penetration);
        strongest = strongest.max(r.force.length());
        contact += usize::from(r.in_contact());
    });
    let stats = servo.stats();
    println!(
        "simulated: {} ticks in {:.3} s of compute; in contact {} ticks; deepest {:.2} mm; strongest {:.2} N",
        stats.ticks,
        stats.wall_seconds,
        contact,
        deepest * 1e3,
        strongest
    );
    println!(
        "  tick time p50 {} ns, p99 {} ns, max {} ns",
        stats.compute.quantile(0.5),
        stats.compute.quantile(0.99),
        stats.compute.max()
    );

    // 2. Real-time mode: the same on its own thread at 4 kHz for half a second.
    let (scene, rocking) = make_scene()?;
    let path = scripted_path(PathKind::Press, &scene, 1.0, 0)?;
    let hand = SimulatedHand::new(path, HandOptions::default());
    let mut servo = Servo::new(hand, scene, ServoOptions::new(4_000.0)?)?;
    servo.set_motions(vec![rocking]);
    let running = ServoLoop::spawn(servo, Some(0.5), RealtimeOptions::default())?;
    let mut records = 0;
    let run = running.wait(|_| records += 1)?;
    let stats = run.servo.stats();
    println!(
        "real time: {} ticks at {:.0} Hz, {records} records; lateness p50 {} ns, p99 {} ns, max {} ns; {} overruns",
        stats.ticks,
        stats.achieved_rate(),
        stats.lateness.quantile(0.5),
        stats.lateness.quantile(0.99),
        stats.lateness.max(),
        stats.overruns
    );
    println!(
        "  thread: real-time priority {}, core {:?} {:?}",
        run.setup.realtime_priority, run.setup.pinned_core, run.setup.notes
    );
    Ok(())
}
