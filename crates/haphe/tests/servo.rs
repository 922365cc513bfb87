//! The servo loop closed with the simulated hand: a constant push settles at the
//! penetration F/k, sliding with friction sticks and slips, a fast strike never passes a
//! thin plate; replay is bit-for-bit repeatable; safe start and faults give zero force;
//! a short real-time smoke run.

use std::sync::Arc;

use haphe::DVec3;
use haphe::map::MapOptions;
use haphe::mesh::shapes::Catalog;
use haphe::mesh::{Surface, SurfaceOptions};
use haphe::scene::{Material, ObjectId, Pose, Scene, SceneObject, Shape};
use haphe::servo::{
    Device, DeviceError, DeviceFault, DeviceSpec, DeviceState, HandOptions, HipTrace, Motion,
    ObjectMotion, PathKind, Phase, RealtimeOptions, ReplayDevice, ScriptedDevice, Servo, ServoLoop,
    ServoOptions, SimulatedHand, StopReason, TickRecord, Trajectory, scripted_path, simulated_spec,
    write_csv_header,
};

fn shape(which: Catalog, triangles: usize) -> Arc<Shape> {
    let surface = Surface::new(which.with_triangles(triangles), &SurfaceOptions::default())
        .expect("a usable surface");
    Arc::new(Shape::build(surface, &MapOptions::default()).expect("a map"))
}

fn scene_of(shape: Arc<Shape>, material: Material) -> Scene {
    let mut scene = Scene::local(4);
    scene
        .insert(SceneObject::new(
            ObjectId(7),
            shape,
            Pose::IDENTITY,
            material,
        ))
        .expect("room");
    scene
}

fn options(rate_hz: f64) -> ServoOptions {
    ServoOptions::new(rate_hz).expect("a valid rate")
}

/// Runs `seconds` of simulation and returns every record.
fn run<D: Device>(servo: &mut Servo<D>, seconds: f64) -> Vec<TickRecord> {
    let ticks = (seconds * servo.options().rate_hz()).round() as u64;
    let mut records = Vec::with_capacity(ticks as usize);
    servo.run_simulated(ticks, |r| records.push(*r));
    records
}

/// The box's top face is at z = 0.05 m.
const BOX_TOP: f64 = 0.05;

/// A hand with no grip, only viscosity and a constant downward push, dropped onto the
/// top of the box, comes to rest at the penetration F/k, at 1 kHz and 10 kHz.
#[test]
fn constant_push_settles_at_force_over_stiffness() {
    for (rate, stiffness, push) in [(1e3, 500.0, 1.0), (1e3, 1000.0, 2.0), (1e4, 800.0, 1.5)] {
        let material = Material::builder()
            .stiffness(stiffness)
            .damping(0.5)
            .build()
            .expect("a valid material");
        let scene = scene_of(shape(Catalog::Box, 2_000), material);
        let hand = SimulatedHand::new(
            Trajectory::still(DVec3::new(0.01, -0.02, BOX_TOP + 0.03)),
            HandOptions {
                stiffness: 0.0,
                damping: 0.0,
                viscosity: 5.0,
                push: DVec3::new(0.0, 0.0, -push),
                ..HandOptions::default()
            },
        );
        let mut servo = Servo::new(hand, scene, options(rate)).expect("servo");
        let records = run(&mut servo, 3.0);
        let settled = &records[records.len() * 5 / 6..];
        let expected = push / stiffness;
        for r in settled {
            assert!(r.in_contact(), "{rate} Hz: lost contact at {}", r.t);
            assert!(
                (r.penetration - expected).abs() < 0.01 * expected,
                "{rate} Hz, k {stiffness}: penetration {} m, expected {expected} m",
                r.penetration
            );
            assert!((r.force.z - push).abs() < 0.01 * push, "{}", r.force);
            assert!(r.proxy.z >= BOX_TOP, "the proxy stays on the surface");
        }
    }
}

/// Sliding a hand that presses down across a surface with friction: the proxy sticks
/// (stays put while the hand moves on) and slips (moves, held back by dynamic friction),
/// again and again (a loose grip dragged slowly: static friction above dynamic friction
/// gives stick–slip); the friction force never leaves the static cone and sits on the
/// dynamic cone while slipping.
#[test]
fn sliding_with_friction_sticks_and_slips() {
    let material = Material::builder()
        .stiffness(800.0)
        .damping(0.0)
        .friction(0.6, 0.4)
        .build()
        .expect("a valid material");
    let scene = scene_of(shape(Catalog::Box, 2_000), material);
    let a = DVec3::new(-0.02, 0.0, BOX_TOP);
    let b = DVec3::new(0.02, 0.0, BOX_TOP);
    let path = Trajectory::from_keys(&[
        (0.0, a + DVec3::Z * 0.01),
        (0.5, a),
        (1.5, a),
        (5.5, b),
        (6.0, b),
    ])
    .expect("a path");
    let hand = SimulatedHand::new(
        path,
        HandOptions {
            stiffness: 200.0,
            damping: 0.0,
            viscosity: 1.0,
            push: DVec3::new(0.0, 0.0, -1.5),
            ..HandOptions::default()
        },
    );
    let mut servo = Servo::new(hand, scene, options(1e3)).expect("servo");
    let records = run(&mut servo, 6.0);
    let slide = &records[1400..5500];
    let (mut stick, mut slip, mut stick_to_slip) = (0, 0, 0);
    for w in slide.windows(2) {
        let (r0, r) = (&w[0], &w[1]);
        assert!(r.in_contact(), "contact lost at {}", r.t);
        let n = r.force.z;
        let t = r.force.truncate().length();
        assert!(n > 0.5, "pressing: {}", r.force);
        assert!(
            t <= 0.6 * n * (1.0 + 1e-9) + 1e-12,
            "outside the static cone at {}",
            r.t
        );
        if r.status.sticking {
            stick += 1;
            assert_eq!(r.proxy, r0.proxy, "a sticking proxy does not move");
        } else {
            slip += 1;
            assert!(
                (t / n - 0.4).abs() < 1e-6,
                "slipping on the dynamic cone: {}",
                t / n
            );
            if r0.status.sticking {
                stick_to_slip += 1;
            }
        }
    }
    let travelled = slide[slide.len() - 1].proxy.x - slide[0].proxy.x;
    println!("stick {stick}, slip {slip}, breakaways {stick_to_slip}, travelled {travelled} m");
    assert!(stick > 100 && slip > 100, "stick {stick}, slip {slip}");
    assert!(
        stick_to_slip >= 3,
        "stick and slip alternate: {stick_to_slip}"
    );
    assert!(travelled > 0.03, "the proxy slid along: {travelled} m");
}

/// The plate is 0.1 mm thick with its top at z = 0.05 mm.
const PLATE_TOP: f64 = 5e-5;

fn assert_never_through(records: &[TickRecord], what: &str) {
    let mut contact = 0;
    for r in records {
        assert!(
            r.proxy.z >= PLATE_TOP,
            "{what}: the proxy went through the plate at {} s: {}",
            r.t,
            r.proxy
        );
        contact += usize::from(r.in_contact());
    }
    let deepest = records
        .iter()
        .map(|r| r.hip.z)
        .fold(f64::INFINITY, f64::min);
    assert!(contact > 50, "{what}: contact ticks {contact}");
    assert!(
        deepest < -PLATE_TOP,
        "{what}: the hand went through: {deepest}"
    );
}

/// A fast strike on the thin plate: the hand's point goes through the 0.1 mm plate between
/// two ticks, the proxy never does, at 1 kHz and 10 kHz; also a position-controlled strike
/// at 5 m/s.
#[test]
fn a_fast_strike_never_goes_through_the_thin_plate() {
    for rate in [1e3, 1e4] {
        let scene = scene_of(shape(Catalog::ThinPlate, 5_000), Material::default());
        let path = scripted_path(PathKind::Strike, &scene, 2.0, 0).expect("a path");
        let hand = SimulatedHand::new(path, HandOptions::default());
        let mut servo = Servo::new(hand, scene, options(rate)).expect("servo");
        let records = run(&mut servo, 2.0);
        let fastest = records
            .iter()
            .map(|r| r.velocity.length())
            .fold(0.0, f64::max);
        assert!(fastest > 1.0, "a fast strike: {fastest} m/s");
        assert_never_through(&records, &format!("hand at {rate} Hz"));
    }
    let scene = scene_of(shape(Catalog::ThinPlate, 5_000), Material::default());
    let path = Trajectory::from_keys(&[
        (0.0, DVec3::new(0.01, 0.02, 0.05)),
        (0.1, DVec3::new(0.01, 0.02, 0.04)),
        (0.11, DVec3::new(0.01, 0.02, -0.01)),
        (0.12, DVec3::new(0.01, 0.02, -0.06)),
        (0.5, DVec3::new(0.01, 0.02, -0.06)),
    ])
    .expect("a path");
    let mut servo = Servo::new(ScriptedDevice::new(path), scene, options(1e3)).expect("servo");
    assert_never_through(&run(&mut servo, 0.5), "scripted strike at 5 m/s");
}

fn csv_of(records: &[TickRecord]) -> Vec<u8> {
    let mut out = Vec::new();
    write_csv_header(&mut out).expect("write");
    for r in records {
        r.write_csv(&mut out).expect("write");
    }
    out
}

/// Replaying a recorded HIP trace twice gives byte-identical traces, with a moving object
/// and friction in the scene.
#[test]
fn replay_is_bit_for_bit_repeatable() {
    let material = Material::builder()
        .stiffness(700.0)
        .damping(1.0)
        .friction(0.5, 0.3)
        .build()
        .expect("a valid material");
    let blob = shape(Catalog::Blob, 3_000);
    let scene = scene_of(blob.clone(), material);
    let path = scripted_path(PathKind::Explore, &scene, 3.0, 11).expect("a path");
    let mut servo = Servo::new(
        SimulatedHand::new(path, HandOptions::default()),
        scene,
        options(1e3),
    )
    .expect("servo");
    let recorded = csv_of(&run(&mut servo, 3.0));
    let trace = HipTrace::read("recorded", recorded.as_slice()).expect("its own output reads back");
    assert_eq!(trace.len(), 3000);

    let replay = || {
        let scene = scene_of(blob.clone(), material);
        let mut servo =
            Servo::new(ReplayDevice::new(trace.clone()), scene, options(1e3)).expect("servo");
        servo.set_motions(vec![ObjectMotion {
            id: ObjectId(7),
            base: Pose::IDENTITY,
            motion: Motion::Oscillating {
                amplitude: DVec3::new(0.0, 0.01, 0.0),
                frequency: 0.5,
            },
        }]);
        let mut records = Vec::new();
        let stop = servo.run_simulated(10_000, |r| records.push(*r));
        assert_eq!(stop, StopReason::Fault(DeviceFault::Ended));
        csv_of(&records)
    };
    let (a, b) = (replay(), replay());
    assert!(a.len() > 100_000);
    assert!(a == b, "two replays of one trace differ");
}

/// Safe start: a device that starts inside an object gets zero force until it is out;
/// then the force ramps up from zero.
#[test]
fn safe_start_holds_until_the_device_is_outside() {
    let scene = scene_of(shape(Catalog::Sphere, 2_000), Material::default());
    // From the centre of the sphere straight up and out, then back down onto it.
    let path = Trajectory::from_keys(&[
        (0.0, DVec3::ZERO),
        (1.0, DVec3::new(0.0, 0.0, 0.13)),
        (1.5, DVec3::new(0.0, 0.0, 0.13)),
        (2.5, DVec3::new(0.0, 0.0, 0.09)),
    ])
    .expect("a path");
    let mut servo = Servo::new(ScriptedDevice::new(path), scene, options(1e3)).expect("servo");
    let records = run(&mut servo, 2.5);
    let first_out = records
        .iter()
        .position(|r| r.phase != Phase::Holding)
        .expect("it comes out");
    for r in &records[..first_out] {
        assert_eq!(r.force, DVec3::ZERO);
        assert!(
            r.hip.length() < 0.1 + 1e-3,
            "held only while inside: {}",
            r.hip
        );
    }
    assert!(records[first_out].hip.length() > 0.099);
    assert_eq!(servo.stats().held_ticks, first_out as u64);
    // Pressed back into the sphere from outside, it is felt.
    let last = records[records.len() - 1];
    assert_eq!(last.phase, Phase::Running);
    assert!(last.in_contact() && last.force.z > 1.0, "{last:?}");
}

/// A device that faults after a number of reads, and remembers the last force.
struct Flaky {
    reads: u32,
    last_force: Arc<std::sync::Mutex<DVec3>>,
}

impl Device for Flaky {
    fn spec(&self) -> DeviceSpec {
        simulated_spec()
    }
    fn open(&mut self) -> Result<(), DeviceError> {
        Ok(())
    }
    fn read(&mut self, _t: f64) -> Result<DeviceState, DeviceFault> {
        if self.reads == 0 {
            return Err(DeviceFault::Disconnected);
        }
        self.reads -= 1;
        Ok(DeviceState {
            position: DVec3::new(0.0, 0.0, 0.095),
            ..DeviceState::default()
        })
    }
    fn write_force(&mut self, force: DVec3) -> Result<(), DeviceFault> {
        *self.last_force.lock().expect("not poisoned") = force;
        Ok(())
    }
    fn close(&mut self) {}
}

/// A fault stops the loop with zero force on the device.
#[test]
fn a_fault_stops_with_zero_force() {
    let scene = scene_of(shape(Catalog::Sphere, 2_000), Material::default());
    let last_force = Arc::new(std::sync::Mutex::new(DVec3::ZERO));
    let device = Flaky {
        reads: 200,
        last_force: last_force.clone(),
    };
    // Start outside, then the point is 5 mm deep: pressed.
    let mut servo = Servo::new(device, scene, options(1e3)).expect("servo");
    servo.set_motions(vec![ObjectMotion {
        id: ObjectId(7),
        base: Pose::from_translation(DVec3::new(0.0, 0.0, -0.2)).expect("a valid pose"),
        motion: Motion::Linear {
            velocity: DVec3::new(0.0, 0.0, 1.0),
        },
    }]);
    let mut records = Vec::new();
    let stop = servo.run_simulated(1000, |r| records.push(*r));
    assert_eq!(stop, StopReason::Fault(DeviceFault::Disconnected));
    assert_eq!(records.len(), 201);
    assert!(records[199].force.length() > 0.5, "{:?}", records[199]);
    assert_eq!(*last_force.lock().expect("not poisoned"), DVec3::ZERO);
    assert_eq!(servo.phase(), Phase::Faulted);
}

/// The simulated hand on `path` over a 2k-triangle blob, at 2 kHz.
fn hand_on_a_blob(path: PathKind) -> Servo<SimulatedHand> {
    let scene = scene_of(shape(Catalog::Blob, 2_000), Material::default());
    let path = scripted_path(path, &scene, 1.0, 0).expect("a path");
    Servo::new(
        SimulatedHand::new(path, HandOptions::default()),
        scene,
        options(2e3),
    )
    .expect("servo")
}

/// The loop on its own thread on the wall clock, briefly: it runs, delivers every record
/// and reports its timing (no timing assertion: the machine is shared).
#[test]
fn realtime_smoke() {
    let running = ServoLoop::spawn(
        hand_on_a_blob(PathKind::Press),
        Some(0.3),
        RealtimeOptions::default().with_realtime_priority(false),
    )
    .expect("a thread");
    let mut n = 0u64;
    let mut last_tick = None;
    let run = running
        .wait(|r| {
            n += 1;
            last_tick = Some(r.tick);
        })
        .expect("no panic");
    let stats = run.servo.stats();
    println!(
        "{} ticks, {:.0} Hz, lateness p50 {} ns p99 {} ns max {} ns, compute p50 {} ns, overruns {}, skipped {}, setup {:?}, {:?}",
        stats.ticks,
        stats.achieved_rate(),
        stats.lateness.quantile(0.5),
        stats.lateness.quantile(0.99),
        stats.lateness.max(),
        stats.compute.quantile(0.5),
        stats.overruns,
        stats.skipped,
        run.setup,
        run.interference
    );
    assert_eq!(run.stop, StopReason::Finished);
    if cfg!(target_os = "linux") {
        // The thread's own counters are always there on Linux; the core's steal when it
        // was pinned. Sleeping before deadlines shows as voluntary switches.
        let i = run.interference;
        assert!(
            i.preemptions.is_some() && i.sleeps.is_some_and(|s| s > 0),
            "{i:?}"
        );
        assert_eq!(
            i.steal_seconds.is_some(),
            run.setup.pinned_core.is_some(),
            "{i:?}"
        );
        assert!(
            i.steal_seconds.is_none_or(|s| (0.0..1.0).contains(&s)),
            "{i:?}"
        );
    }
    assert!(stats.ticks > 0 && stats.ticks <= 600);
    assert_eq!(n + run.dropped_records, stats.ticks);
    assert_eq!(last_tick, Some(stats.ticks - 1));
    assert_eq!(stats.lateness.count(), stats.ticks);
}

/// With a standby thread on another core: every tick runs once, in order, whichever
/// thread runs it; the standby reports what it did (how many ticks it took over depends on
/// the machine, so it is printed, not asserted).
#[test]
fn realtime_with_a_standby_thread_ticks_each_deadline_once() {
    let cores = std::thread::available_parallelism().map_or(1, usize::from);
    if cores < 2 {
        println!("one core: a standby needs a second one; not run here");
        return;
    }
    let running = ServoLoop::spawn(
        hand_on_a_blob(PathKind::Explore),
        Some(0.3),
        RealtimeOptions::default()
            .with_realtime_priority(false)
            .with_core(Some(cores - 1))
            .with_spin_seconds(Some(500e-6))
            .expect("a valid spin")
            .with_standby_core(Some(0)),
    )
    .expect("a thread");
    let mut ticks = Vec::new();
    let run = running
        .wait(|r| ticks.push((r.tick, r.t)))
        .expect("no panic");
    let stats = run.servo.stats();
    let standby = run.standby.expect("a standby report");
    println!(
        "{} ticks, {} by the standby ({:?}), overruns {}, skipped {}",
        stats.ticks, standby.ticks, standby.pinned_core, stats.overruns, stats.skipped
    );
    assert_eq!(run.stop, StopReason::Finished);
    assert_eq!(ticks.len() as u64, stats.ticks);
    assert!(stats.ticks > 0 && standby.ticks <= stats.ticks);
    // Each tick once, in order, at increasing deadlines.
    assert!(
        ticks
            .iter()
            .enumerate()
            .all(|(i, &(tick, _))| tick == i as u64)
    );
    assert!(ticks.windows(2).all(|w| w[1].1 > w[0].1));
    if cfg!(target_os = "linux") {
        assert_eq!(standby.pinned_core, Some(0), "core 0 exists everywhere");
    }
}

/// A standby asked for on the servo thread's own core is not started, and the setup says
/// why: two threads on one core could only take turns.
#[test]
fn no_standby_on_the_servo_threads_own_core() {
    let running = ServoLoop::spawn(
        hand_on_a_blob(PathKind::Press),
        Some(0.05),
        RealtimeOptions::default()
            .with_realtime_priority(false)
            .with_core(Some(0))
            .with_standby_core(Some(0)),
    )
    .expect("a thread");
    let run = running.wait(|_| {}).expect("no panic");
    assert_eq!(run.stop, StopReason::Finished);
    assert!(run.servo.stats().ticks > 0);
    if run.setup.pinned_core == Some(0) {
        assert!(run.standby.is_none(), "{:?}", run.standby);
        assert!(
            run.setup.notes.iter().any(|n| n.contains("no standby")),
            "{:?}",
            run.setup.notes
        );
    }
}

/// On a grid of many objects the explore path strokes over the first object at a hand's
/// speed, hovering just above it, instead of crossing the whole scene.
#[test]
fn explore_on_a_large_scene_stays_on_one_object() {
    let ball = shape(Catalog::Sphere, 320);
    let r = ball.bound_radius();
    let mut scene = Scene::local(64);
    for k in 0..64u32 {
        let at = DVec3::new(f64::from(k % 4), f64::from((k / 4) % 4), f64::from(k / 16)) * 0.25;
        let o = SceneObject::new(
            ObjectId(k),
            ball.clone(),
            Pose::from_translation(at).expect("a valid pose"),
            Material::default(),
        );
        scene.insert(o).expect("room");
    }
    let path = scripted_path(PathKind::Explore, &scene, 5.0, 3).expect("a path");
    let mut fastest = 0.0f64;
    let steps = 5_000;
    for k in 0..=steps {
        let (p, v) = path.sample(path.end_time() * f64::from(k) / f64::from(steps));
        fastest = fastest.max(v.length());
        assert!(
            p.truncate().length() < r,
            "{p} is not over the first object"
        );
        assert!(
            p.z > -r && p.z < r + 0.05,
            "{p} is not at the first object's height"
        );
    }
    assert!(fastest < 1.0, "{fastest} m/s");
}
