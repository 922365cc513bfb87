//! A servo clocked by its device ([`DeviceClock`], [`ServoLoop::spawn_clocked`]): the
//! records are those of the same device on haphe's virtual clock, tick for tick (forces
//! within 1e-9 N); the
//! clocked tick allocates nothing over 10^5 ticks; a device clock that skips deadlines
//! past the overrun budget stops the run with zero force; a clock that stops calling back
//! is a fault.

use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Duration;

use haphe::DVec3;
use haphe::scene::{Material, Scene};
use haphe::servo::{
    DeviceClock, DeviceFault, PathKind, RealtimeOptions, ScriptedDevice, Servo, ServoLoop,
    ServoOptions, StopReason, TickRecord, scripted_path,
};

fn scene() -> Scene {
    haphe::verify::sphere_scene(2_000, Material::default()).expect("the sphere scene")
}

fn servo(seconds: f64) -> Servo<ScriptedDevice> {
    let scene = scene();
    let path = scripted_path(PathKind::Press, &scene, seconds, 1).expect("a path");
    Servo::new(ScriptedDevice::new(path), scene, ServoOptions::default()).expect("servo")
}

/// A clock that calls back on its own thread as fast as it can (or `gap` apart), for at
/// most `limit` callbacks, and counts the allocations of callbacks `warm..limit`.
struct TestClock {
    gap: Duration,
    limit: u64,
    warm: u64,
    allocations: Arc<AtomicU64>,
}

impl DeviceClock for TestClock {
    fn run(&mut self, tick: &mut (dyn FnMut() -> bool + Send)) -> Result<(), DeviceFault> {
        for _ in 0..self.warm {
            if !tick() {
                return Ok(());
            }
        }
        let mut going = true;
        let mut n = self.warm;
        let info = allocation_counter::measure(|| {
            while going && n < self.limit {
                if !self.gap.is_zero() {
                    std::thread::sleep(self.gap);
                }
                going = tick();
                n += 1;
            }
        });
        self.allocations.store(info.count_total, Ordering::Relaxed);
        if going {
            // Stopped calling back on its own: as a device that went away.
            Err(DeviceFault::Disconnected)
        } else {
            Ok(())
        }
    }
}

fn run(
    clock: TestClock,
    seconds: f64,
    options: RealtimeOptions,
) -> (Vec<TickRecord>, StopReason, Servo<ScriptedDevice>) {
    let mut records = Vec::new();
    let running = ServoLoop::spawn_clocked(servo(seconds), Box::new(clock), Some(seconds), options)
        .expect("spawn");
    let run = running.wait(|r| records.push(*r)).expect("no panic");
    (records, run.stop, run.servo)
}

#[test]
fn clocked_ticks_match_the_virtual_clock_and_allocate_nothing() {
    let seconds = 100.2;
    let allocations = Arc::new(AtomicU64::new(u64::MAX));
    let clock = TestClock {
        gap: Duration::ZERO,
        limit: u64::MAX,
        warm: 200,
        allocations: Arc::clone(&allocations),
    };
    let options = RealtimeOptions::default().with_record_capacity(200_000);
    let (records, stop, clocked) = run(clock, seconds, options);
    assert_eq!(stop, StopReason::Finished);
    assert_eq!(records.len(), 100_200);
    assert_eq!(
        allocations.load(Ordering::Relaxed),
        0,
        "the clocked tick allocated"
    );
    assert_eq!(clocked.device().last_force(), DVec3::ZERO);
    let mut reference = servo(seconds);
    let mut k = 0usize;
    let mut contact = 0usize;
    reference.run_simulated(100_200, |r| {
        // Tick times differ in the last bit (k / rate here, k · period in nanoseconds
        // there), which the ramp and the path see.
        assert!(r.force.distance(records[k].force) < 1e-9, "tick {k}");
        assert!(r.hip.distance(records[k].hip) < 1e-12, "tick {k}");
        contact += usize::from(r.in_contact());
        k += 1;
    });
    assert!(contact > 1_000, "{contact}");
    assert_eq!(clocked.stats().ticks, 100_200);
}

#[test]
fn skipped_deadlines_past_the_budget_stop_with_zero_force() {
    let clock = TestClock {
        gap: Duration::from_millis(4),
        limit: 1_000,
        warm: 0,
        allocations: Arc::new(AtomicU64::new(0)),
    };
    let options = RealtimeOptions::default().with_overrun_budget(Some(10));
    let (records, stop, servo) = run(clock, 10.0, options);
    assert_eq!(stop, StopReason::Overruns);
    assert!(records.len() < 20, "{}", records.len());
    assert!(servo.stats().missed() > 10);
    assert_eq!(servo.device().last_force(), DVec3::ZERO);
}

#[test]
fn a_clock_that_stops_calling_back_is_a_fault() {
    let clock = TestClock {
        gap: Duration::ZERO,
        limit: 500,
        warm: 0,
        allocations: Arc::new(AtomicU64::new(0)),
    };
    let (records, stop, servo) = run(clock, 10.0, RealtimeOptions::default());
    assert_eq!(stop, StopReason::Fault(DeviceFault::Disconnected));
    assert_eq!(records.len(), 500);
    assert_eq!(servo.device().last_force(), DVec3::ZERO);
}
