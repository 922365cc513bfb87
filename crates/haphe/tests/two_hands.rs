//! Several devices on one servo (two hands in one scene): each device's records — device
//! point, proxy, force, contact, phase — are those of a servo of that device alone on the
//! same scene, at every tick, with its own options (maximum force, ramp, clutch); a fault
//! of either device writes zero force to both, stops both and names it; a set of devices
//! the servo cannot tick together is refused, and a device that does not open closes the
//! ones opened before it; a real-time run hands on one record per device per tick.

use std::sync::{Arc, Mutex};

use haphe::DVec3;
use haphe::map::MapOptions;
use haphe::mesh::shapes::Catalog;
use haphe::mesh::{Surface, SurfaceOptions};
use haphe::proxy::ProxyOptions;
use haphe::scene::{Material, ObjectId, Pose, Scene, SceneObject, Shape};
use haphe::servo::{
    Device, DeviceError, DeviceFault, DeviceSpec, DeviceState, HandOptions, Motion, ObjectMotion,
    PathKind, Phase, RealtimeOptions, Servo, ServoError, ServoLoop, ServoOptions, SimulatedHand,
    StopReason, TickRecord, scripted_path, simulated_spec,
};

const TICKS: u64 = 3_000;

fn shape(which: Catalog, triangles: usize) -> Arc<Shape> {
    let surface = Surface::new(which.with_triangles(triangles), &SurfaceOptions::default())
        .expect("a usable surface");
    Arc::new(Shape::build(surface, &MapOptions::default()).expect("a map"))
}

/// A blob at the origin and a sphere beside it that moves up and down by script.
struct World {
    blob: Arc<Shape>,
    sphere: Arc<Shape>,
}

impl World {
    fn new() -> World {
        World {
            blob: shape(Catalog::Blob, 2_000),
            sphere: shape(Catalog::Sphere, 1_000),
        }
    }

    fn sphere_pose() -> Pose {
        Pose::from_translation(DVec3::new(0.25, 0.0, 0.0)).expect("a valid pose")
    }

    fn scene(&self) -> Scene {
        let mut scene = Scene::local(4);
        let material = Material::default();
        scene
            .insert(SceneObject::new(
                ObjectId(0),
                Arc::clone(&self.blob),
                Pose::IDENTITY,
                material,
            ))
            .expect("room");
        scene
            .insert(SceneObject::new(
                ObjectId(1),
                Arc::clone(&self.sphere),
                World::sphere_pose(),
                material,
            ))
            .expect("room");
        scene
    }

    fn motions() -> Vec<ObjectMotion> {
        vec![ObjectMotion {
            id: ObjectId(1),
            base: World::sphere_pose(),
            motion: Motion::Oscillating {
                amplitude: DVec3::new(0.0, 0.0, 0.01),
                frequency: 1.0,
            },
        }]
    }

    /// The simulated hand exploring the scene along the path of `seed`, holding button 0
    /// from `press` seconds for 0.1 s.
    fn hand(&self, seed: u64, press: f64) -> SimulatedHand {
        let path = scripted_path(PathKind::Explore, &self.scene(), 3.0, seed).expect("a path");
        SimulatedHand::new(path, HandOptions::default())
            .press(0, press, press + 0.1)
            .expect("a valid press")
    }
}

/// The two hands' options: the first clamps at 2 N with a 20 ms ramp, the second at the
/// default force with a 100 ms ramp; both hold a clutch on button 0.
fn options() -> [ServoOptions; 2] {
    let first = ServoOptions::new(1000.0)
        .expect("a rate")
        .with_proxy(
            ProxyOptions::default()
                .with_max_force(2.0)
                .expect("a force"),
        )
        .with_ramp_seconds(0.02)
        .expect("a ramp")
        .with_clutch_button(Some(0));
    let second = ServoOptions::new(1000.0)
        .expect("a rate")
        .with_ramp_seconds(0.1)
        .expect("a ramp")
        .with_clutch_button(Some(0));
    [first, second]
}

/// Every record of a run of `ticks` ticks.
fn run<D: Device>(servo: &mut Servo<D>, ticks: u64) -> (Vec<TickRecord>, StopReason) {
    let mut records = Vec::new();
    let stop = servo.run_simulated(ticks, |r| records.push(*r));
    (records, stop)
}

#[test]
fn each_hand_renders_as_if_it_were_alone() {
    let world = World::new();
    let [first, second] = options();
    let hands = [(world.hand(1, 0.8), first), (world.hand(2, 1.7), second)];
    let mut both = Servo::with_devices(hands.to_vec(), world.scene()).expect("two hands");
    both.set_motions(World::motions());
    assert_eq!(both.devices(), 2);
    let (records, stop) = run(&mut both, TICKS);
    assert_eq!(stop, StopReason::Finished);
    assert_eq!(records.len(), 2 * TICKS as usize);

    for (i, (hand, options)) in hands.into_iter().enumerate() {
        let mut alone = Servo::new(hand, world.scene(), options).expect("one hand");
        alone.set_motions(World::motions());
        let (expected, _) = run(&mut alone, TICKS);
        let mine: Vec<&TickRecord> = records.iter().skip(i).step_by(2).collect();
        assert_eq!(mine.len(), expected.len());
        for (k, (got, want)) in mine.iter().zip(&expected).enumerate() {
            let want = TickRecord {
                device: i as u32,
                ..*want
            };
            assert_eq!(**got, want, "device {i}, tick {k}");
        }
        let proxy = both.proxy_of(i).expect("a proxy").position();
        assert_eq!(proxy, alone.proxy().position(), "device {i}");
        assert_eq!(both.mapping_of(i), Some(alone.mapping()), "device {i}");
        // Guards, counted on the run of the hand alone: it touched, was clamped at its
        // own maximum, and held its clutch.
        let contact = expected.iter().filter(|r| r.in_contact()).count();
        assert!(contact > 200, "device {i}: {contact} contact ticks");
        assert_eq!(expected.iter().filter(|r| r.clutch).count(), 100);
        let largest = expected
            .iter()
            .map(|r| r.force.length())
            .fold(0.0, f64::max);
        assert!(largest <= options.proxy().max_force() + 1e-12);
    }
    // Not the first device's forces on both (each comes from its own proxy).
    let differ = records
        .chunks(2)
        .filter(|pair| pair[0].force.distance(pair[1].force) > 1e-6)
        .count();
    assert!(differ > 200, "{differ}");
    assert_eq!(both.stats().ticks, TICKS);
}

/// A device at a fixed point that faults at a given read or write, and logs every force
/// written to it.
struct Pressing {
    at: DVec3,
    fail_read: Option<u32>,
    fail_write: Option<u32>,
    calls: u32,
    forces: Arc<Mutex<Vec<DVec3>>>,
}

impl Pressing {
    fn new(at: DVec3) -> (Pressing, Arc<Mutex<Vec<DVec3>>>) {
        let forces = Arc::new(Mutex::new(Vec::new()));
        let device = Pressing {
            at,
            fail_read: None,
            fail_write: None,
            calls: 0,
            forces: Arc::clone(&forces),
        };
        (device, forces)
    }
}

impl Device for Pressing {
    fn spec(&self) -> DeviceSpec {
        simulated_spec()
    }
    fn open(&mut self) -> Result<(), DeviceError> {
        Ok(())
    }
    fn read(&mut self, t: f64) -> Result<DeviceState, DeviceFault> {
        if self.fail_read == Some(self.calls) {
            return Err(DeviceFault::Disconnected);
        }
        // From 5 cm above the point down to 5 mm below it over the first 0.1 s.
        let depth = (t / 0.1).min(1.0) * 0.055 - 0.05;
        Ok(DeviceState {
            position: self.at * (1.0 - depth / self.at.length()),
            ..DeviceState::default()
        })
    }
    fn write_force(&mut self, force: DVec3) -> Result<(), DeviceFault> {
        self.forces.lock().expect("not poisoned").push(force);
        self.calls += 1;
        if self.fail_write == Some(self.calls - 1) {
            return Err(DeviceFault::Hardware(7));
        }
        Ok(())
    }
    fn close(&mut self) {}
}

#[test]
fn a_fault_of_either_device_zeroes_both_and_names_it() {
    let sphere = shape(Catalog::Sphere, 2_000);
    let scene = || {
        let mut scene = Scene::local(2);
        let o = SceneObject::new(
            ObjectId(0),
            Arc::clone(&sphere),
            Pose::IDENTITY,
            Material::default(),
        );
        scene.insert(o).expect("room");
        scene
    };
    for (faulty, on_write) in [(0usize, false), (1, false), (0, true), (1, true)] {
        // Pressing the sphere (radius 0.1 m) from above and from the side.
        let (mut a, forces_a) = Pressing::new(DVec3::new(0.0, 0.0, 0.1));
        let (mut b, forces_b) = Pressing::new(DVec3::new(0.1, 0.0, 0.0));
        // The 200th tick: both devices are pressing by then.
        let at = 200;
        let culprit = if faulty == 0 { &mut a } else { &mut b };
        if on_write {
            culprit.fail_write = Some(at);
        } else {
            culprit.fail_read = Some(at);
        }
        let devices: Vec<(Box<dyn Device>, ServoOptions)> = vec![
            (Box::new(a), ServoOptions::default()),
            (Box::new(b), ServoOptions::default()),
        ];
        let mut servo = Servo::with_devices(devices, scene()).expect("two devices");
        let (records, stop) = run(&mut servo, 1_000);
        let fault = if on_write {
            DeviceFault::Hardware(7)
        } else {
            DeviceFault::Disconnected
        };
        let what = format!(
            "device {faulty} faults on {}",
            if on_write { "write" } else { "read" }
        );
        assert_eq!(stop, StopReason::Fault(fault), "{what}");
        assert_eq!(servo.faulted_device(), Some(faulty), "{what}");
        assert_eq!(records.len(), 2 * (at as usize + 1), "{what}");
        let last = &records[records.len() - 2..];
        assert_eq!(last[faulty].fault, Some(fault), "{what}");
        assert_eq!(last[1 - faulty].fault, None, "{what}");
        for (i, forces) in [&forces_a, &forces_b].into_iter().enumerate() {
            let forces = forces.lock().expect("not poisoned");
            // Pressing before the fault: a force the fault has to zero.
            let before = records[2 * (at as usize - 1) + i].force;
            assert!(before.length() > 0.5, "{what}: device {i} {before}");
            assert_eq!(forces.last(), Some(&DVec3::ZERO), "{what}: device {i}");
            assert_eq!(last[i].force, DVec3::ZERO, "{what}: device {i}");
            assert_eq!(last[i].phase, Phase::Faulted, "{what}: device {i}");
        }
        // Later ticks write nothing but zero, to both.
        let (later, _) = run(&mut servo, 3);
        assert!(later.iter().all(|r| r.force == DVec3::ZERO));
        for forces in [&forces_a, &forces_b] {
            let forces = forces.lock().expect("not poisoned");
            assert!(forces[forces.len() - 3..].iter().all(|f| *f == DVec3::ZERO));
        }
    }
}

/// A device that cannot be opened, and one that logs its closing.
#[derive(Debug)]
struct Closing {
    opens: bool,
    closed: Arc<Mutex<bool>>,
}

impl Device for Closing {
    fn spec(&self) -> DeviceSpec {
        simulated_spec()
    }
    fn open(&mut self) -> Result<(), DeviceError> {
        if self.opens {
            Ok(())
        } else {
            Err(DeviceError::Open("not there".into()))
        }
    }
    fn read(&mut self, _t: f64) -> Result<DeviceState, DeviceFault> {
        Ok(DeviceState::default())
    }
    fn write_force(&mut self, _force: DVec3) -> Result<(), DeviceFault> {
        Ok(())
    }
    fn close(&mut self) {
        *self.closed.lock().expect("not poisoned") = true;
    }
}

#[test]
fn devices_the_servo_cannot_tick_together_are_refused() {
    let world = World::new();
    let none: Vec<(SimulatedHand, ServoOptions)> = Vec::new();
    assert!(matches!(
        Servo::with_devices(none, world.scene()),
        Err(ServoError::Devices(_))
    ));
    let rates = vec![
        (world.hand(1, 0.5), ServoOptions::default()),
        (
            world.hand(2, 0.5),
            ServoOptions::new(2000.0).expect("a rate"),
        ),
    ];
    let e = Servo::with_devices(rates, world.scene()).expect_err("two rates");
    assert!(e.to_string().contains("one rate"), "{e}");
    let closed = Arc::new(Mutex::new(false));
    let devices = vec![
        (
            Closing {
                opens: true,
                closed: Arc::clone(&closed),
            },
            ServoOptions::default(),
        ),
        (
            Closing {
                opens: false,
                closed: Arc::new(Mutex::new(false)),
            },
            ServoOptions::default(),
        ),
    ];
    let e = Servo::with_devices(devices, world.scene()).expect_err("the second fails");
    assert!(matches!(e, ServoError::DeviceAt { device: 1, .. }), "{e:?}");
    assert_eq!(e.to_string(), "device 1: cannot open the device: not there");
    assert!(
        *closed.lock().expect("not poisoned"),
        "the first was closed"
    );
}

#[test]
fn a_realtime_run_hands_on_every_devices_record_of_every_tick() {
    let world = World::new();
    let [first, second] = options();
    let hands = vec![(world.hand(3, 0.1), first), (world.hand(4, 0.2), second)];
    let servo = Servo::with_devices(hands, world.scene()).expect("two hands");
    let running = ServoLoop::spawn(
        servo,
        Some(0.2),
        RealtimeOptions::default().with_realtime_priority(false),
    )
    .expect("a thread");
    let mut records = Vec::new();
    let run = running.wait(|r| records.push(*r)).expect("no panic");
    assert_eq!(run.stop, StopReason::Finished);
    assert_eq!(run.dropped_records, 0);
    let stats = run.servo.stats();
    let ticks = stats.ticks;
    // Every deadline of 0.2 s at 1 kHz, ticked or skipped when the machine fell behind.
    assert_eq!(ticks + stats.skipped, 200);
    assert_eq!(records.len() as u64, 2 * ticks);
    for (n, r) in records.iter().enumerate() {
        assert_eq!((r.tick, r.device), ((n / 2) as u64, (n % 2) as u32));
    }
}
