//! The Force Dimension and OpenHaptics devices, through the real loading and calling
//! path, against stand-in libraries that export the vendors' C symbols and simulate a
//! point pressed into a sphere and released: the forces haphe writes are those of the
//! scripted run on the same trajectory (within 1e-9 N); an unplugged device gives zero
//! force in the tick that finds it and a clear error; a missing library names itself,
//! the variable to set and the SDK.

mod common;

use std::sync::MutexGuard;

use haphe::DVec3;
use haphe::servo::{
    Device, DeviceClock, DeviceFault, RealtimeOptions, RealtimeRun, Servo, ServoLoop, ServoOptions,
    StopReason, TickRecord,
};
use haphe_devices::{UdpOptions, open_device};

use common::{Standin, from_hd, reference, scene, serial, standin, trajectory, trajectory_hd};

const TICKS: u64 = 3_000;

fn set(variable: &str, value: &std::path::Path) {
    // SAFETY: the tests of this binary run one at a time (`serial`), and nothing else
    // reads the environment meanwhile.
    unsafe { std::env::set_var(variable, value) };
}

/// A vendor's stand-in, as a test drives it.
struct Vendor {
    /// The C source in tests/standin.
    source: &'static str,
    /// The variable that names the library to the device.
    variable: &'static str,
    /// The reference trajectory in the stand-in's units and frame.
    trajectory: fn(&[TickRecord]) -> Vec<[f64; 6]>,
    /// Whether its scheduler clocks the servo (OpenHaptics): then it ticks as fast as
    /// the servo goes rather than at 1 kHz.
    scheduler: bool,
}

const DHD: Vendor = Vendor {
    source: "dhd",
    variable: "HAPHE_DHD_LIBRARY",
    trajectory,
    scheduler: false,
};

const HD: Vendor = Vendor {
    source: "hd",
    variable: "HAPHE_HD_LIBRARY",
    trajectory: trajectory_hd,
    scheduler: true,
};

/// The `vendor`'s stand-in with one device that replays the reference run of `TICKS`
/// ticks, named to the device by its variable; with the lock that keeps the other tests
/// out meanwhile, and the reference records.
fn replaying(vendor: &Vendor) -> (MutexGuard<'static, ()>, Standin, Vec<TickRecord>) {
    let one = serial();
    let lib = standin(vendor.source);
    set(vendor.variable, &lib);
    let standin = Standin::open(&lib);
    standin.reset(1);
    if vendor.scheduler {
        standin.set_period_ns(0);
    }
    let expected = reference(TICKS);
    standin.set_path(&(vendor.trajectory)(&expected));
    (one, standin, expected)
}

/// Makes the device fail (unplugged) from the tick after the first that presses into
/// the sphere; returns that tick.
fn unplug_while_pressing(standin: &Standin, expected: &[TickRecord]) -> usize {
    let k = expected
        .iter()
        .position(|r| r.force.length() > 0.5)
        .expect("a press")
        + 1;
    standin.fail_from(i32::try_from(k).expect("fits"));
    k
}

/// The records of a run of `spec` on the virtual clock (every tick on this thread).
fn run_simulated(spec: &str, ticks: u64) -> (Vec<TickRecord>, StopReason, String) {
    let opened = open_device(spec, &scene(), 1.0, UdpOptions::default()).expect("opens");
    let mut servo = Servo::new(opened.device, scene(), ServoOptions::default()).expect("servo");
    let mut records = Vec::new();
    let stop = servo.run_simulated(ticks, |r| records.push(*r));
    servo.close();
    (records, stop, (opened.report)().unwrap_or_default())
}

/// The records of a run of `TICKS` ticks of `device`, clocked by its own `clock`, and
/// the run (the servo not yet closed).
fn run_clocked(
    device: Box<dyn Device>,
    clock: Box<dyn DeviceClock>,
) -> (Vec<TickRecord>, RealtimeRun<Box<dyn Device>>) {
    let servo = Servo::new(device, scene(), ServoOptions::default()).expect("servo");
    let running = ServoLoop::spawn_clocked(
        servo,
        clock,
        Some(TICKS as f64 / 1000.0),
        RealtimeOptions::default(),
    )
    .expect("spawn");
    let mut records = Vec::new();
    let run = running.wait(|r| records.push(*r)).expect("no panic");
    (records, run)
}

#[test]
fn dhd_forces_equal_the_scripted_run() {
    let (_one, standin, expected) = replaying(&DHD);
    let (records, stop, _) = run_simulated("dhd", TICKS);
    assert_eq!(stop, StopReason::Finished);
    assert_eq!(records.len(), expected.len());
    // The force written at open (zero), one per tick, then zero at close.
    let written = standin.forces();
    assert_eq!(written.len(), 1 + TICKS as usize + 2, "{}", written.len());
    assert_eq!(written[0], [0.0; 3]);
    let mut worst = 0.0f64;
    for (k, (r, e)) in records.iter().zip(&expected).enumerate() {
        let f = DVec3::from_array(written[1 + k]);
        worst = worst
            .max(f.distance(e.force))
            .max(r.force.distance(e.force));
    }
    println!("dhd: largest force difference {worst:e} N over {TICKS} ticks");
    assert!(worst <= 1e-9, "{worst}");
    assert!(
        expected
            .iter()
            .map(|e| e.force.length())
            .fold(0.0, f64::max)
            > 0.5
    );
    assert_eq!(written[written.len() - 1], [0.0; 3]);
    assert_eq!(
        standin.flag("standin_force_enabled"),
        0,
        "forces disabled at close"
    );
    assert_eq!(standin.flag("standin_opened"), 0, "closed");
}

#[test]
fn dhd_unplugged_mid_run_gives_zero_force_and_a_clear_error() {
    let (_one, standin, expected) = replaying(&DHD);
    let k = unplug_while_pressing(&standin, &expected);
    let (records, stop, report) = run_simulated("dhd", TICKS);
    assert_eq!(stop, StopReason::Fault(DeviceFault::Hardware(5)));
    assert_eq!(records.len(), k + 1);
    assert_eq!(records[k].fault, Some(DeviceFault::Hardware(5)));
    let written = standin.forces();
    assert!(
        DVec3::from_array(written[k]).length() > 0.5,
        "pressing before"
    );
    assert_eq!(
        written[1 + k],
        [0.0; 3],
        "zero force in the tick that found it"
    );
    assert!(written[1 + k..].iter().all(|f| *f == [0.0; 3]));
    assert!(
        report.contains("communication error between the host and the haptic device"),
        "{report}"
    );
}

#[test]
fn openhaptics_forces_equal_the_scripted_run_clocked_by_the_scheduler() {
    let (_one, standin, expected) = replaying(&HD);
    let opened = open_device("openhaptics", &scene(), 1.0, UdpOptions::default()).expect("opens");
    assert!(
        opened.description.contains("stand-in Touch at 1000 Hz"),
        "{}",
        opened.description
    );
    assert!(
        opened.description.contains("70 × 160 × 120 mm"),
        "{}",
        opened.description
    );
    let clock = opened.clock.expect("the HD scheduler clocks the servo");
    let (records, mut run) = run_clocked(opened.device, clock);
    assert_eq!(run.stop, StopReason::Finished);
    assert_eq!(records.len(), TICKS as usize);
    run.servo.close();
    let written = standin.forces();
    // One per tick, zero in the last callback, zero after the scheduler stopped, and at close.
    assert!(written.len() > TICKS as usize, "{}", written.len());
    let mut worst = 0.0f64;
    for (k, (r, e)) in records.iter().zip(&expected).enumerate() {
        worst = worst
            .max(from_hd(written[k]).distance(e.force))
            .max(r.force.distance(e.force));
    }
    println!("openhaptics: largest force difference {worst:e} N over {TICKS} ticks");
    assert!(worst <= 1e-9, "{worst}");
    assert!(written[TICKS as usize..].iter().all(|f| *f == [0.0; 3]));
    assert_eq!(
        standin.flag("standin_force_output"),
        0,
        "force output off at close"
    );
    assert_eq!(run.servo.stats().ticks, TICKS);
}

#[test]
fn openhaptics_unplugged_mid_run_gives_zero_force_and_a_clear_error() {
    let (_one, standin, expected) = replaying(&HD);
    let k = unplug_while_pressing(&standin, &expected);
    let opened = open_device("openhaptics", &scene(), 1.0, UdpOptions::default()).expect("opens");
    let clock = opened.clock.expect("a clock");
    let (records, run) = run_clocked(opened.device, clock);
    assert_eq!(run.stop, StopReason::Fault(DeviceFault::Hardware(0x0302)));
    assert_eq!(records.len(), k + 1);
    let written = standin.forces();
    assert!(from_hd(written[k - 1]).length() > 0.5, "pressing before");
    assert_eq!(written[k], [0.0; 3], "zero force in the tick that found it");
    let report = (opened.report)().unwrap_or_default();
    assert!(
        report.contains("Communication error (HD error 0x0302)"),
        "{report}"
    );
}

#[test]
fn a_missing_library_names_itself_the_variable_and_the_sdk() {
    let _one = serial();
    for (spec, variable, file, sdk) in [
        (
            "dhd",
            "HAPHE_DHD_LIBRARY",
            "libdhd.so",
            "Force Dimension SDK",
        ),
        ("openhaptics", "HAPHE_HD_LIBRARY", "libHD.so", "OpenHaptics"),
    ] {
        set(variable, std::path::Path::new("/nonexistent/libvendor.so"));
        let error = open_device(spec, &scene(), 1.0, UdpOptions::default())
            .err()
            .expect("no library there")
            .to_string();
        for needed in [
            file,
            variable,
            sdk,
            "/nonexistent/libvendor.so",
            "docs/devices.md",
        ] {
            assert!(error.contains(needed), "{needed:?} missing from: {error}");
        }
        println!("{error}");
    }
}

#[test]
fn no_device_connected_is_a_clear_error() {
    let _one = serial();
    let lib = standin("dhd");
    set("HAPHE_DHD_LIBRARY", &lib);
    let standin = Standin::open(&lib);
    standin.reset(0);
    let error = open_device("dhd", &scene(), 1.0, UdpOptions::default())
        .err()
        .expect("nothing connected")
        .to_string();
    assert!(
        error.contains("no Force Dimension device is connected"),
        "{error}"
    );
    let found = haphe_devices::list_devices();
    let dhd = found.iter().find(|f| f.spec == "dhd").expect("listed");
    assert!(
        !dhd.ready
            && dhd
                .lines
                .iter()
                .any(|l| l.contains("0 device(s) connected")),
        "{dhd:?}"
    );
}
