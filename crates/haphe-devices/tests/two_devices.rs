//! Two devices on one servo through the real loading and calling path, against stand-in
//! libraries with two devices behind them (each with its own state: its path, the forces
//! written to it, its faults): each device's forces are those of its own scripted run
//! (its own proxy), both are written every tick at the rate asked, on haphe's clock or the
//! OpenHaptics scheduler's, with devices of one vendor or mixed; a fault of either zeroes
//! both and names it; a device given twice, an index that does not exist and a name that is
//! not configured are refused with a clear error, and no force is sent to any device.

mod common;

use haphe::DVec3;
use haphe::servo::{
    Device, DeviceClock, DeviceFault, PathKind, RealtimeOptions, Servo, ServoLoop, ServoOptions,
    StopReason, TickRecord,
};
use haphe_devices::{OpenedDevice, SpecError, UdpOptions, open_devices};

use common::{Standin, from_hd, reference_of, scene, serial, standin, trajectory, trajectory_hd};

const TICKS: u64 = 2_000;

fn set(variable: &str, value: &std::path::Path) {
    // SAFETY: the tests of this binary run one at a time (`serial`), and nothing else
    // reads the environment meanwhile.
    unsafe { std::env::set_var(variable, value) };
}

/// A stand-in library with two devices, named to the devices by its variable.
fn two(source: &str, variable: &str) -> Standin {
    let lib = standin(source);
    set(variable, &lib);
    let s = Standin::open(&lib);
    s.reset(2);
    if source == "hd" {
        // Its scheduler ticks as fast as the servo goes.
        s.set_period_ns(0);
    }
    s
}

/// The two reference runs: a press (device 0) and circles (device 1) on the sphere.
fn references() -> [Vec<TickRecord>; 2] {
    [
        reference_of(PathKind::Press, TICKS),
        reference_of(PathKind::Circle, TICKS),
    ]
}

/// Opens `specs` as one run does.
fn open(specs: &[&str]) -> Result<Vec<OpenedDevice>, SpecError> {
    let specs: Vec<String> = specs.iter().map(|s| s.to_string()).collect();
    open_devices(&specs, &scene(), 1.0, UdpOptions::default())
}

/// A servo of boxed devices, and the clock of one of them.
type Clocked = (Servo<Box<dyn Device>>, Option<Box<dyn DeviceClock>>);

/// One servo over `opened`, each device with the default options.
fn servo_of(opened: Vec<OpenedDevice>) -> Clocked {
    let mut clock = None;
    let mut devices = Vec::new();
    for o in opened {
        clock = clock.or(o.clock);
        devices.push((o.device, ServoOptions::default()));
    }
    (
        Servo::with_devices(devices, scene()).expect("a servo"),
        clock,
    )
}

/// Splits a run's records by device.
fn by_device(records: &[TickRecord]) -> [Vec<TickRecord>; 2] {
    let of = |d: u32| records.iter().filter(|r| r.device == d).copied().collect();
    [of(0), of(1)]
}

/// The largest difference between the forces `written` to a device from `from` on (in
/// haphe's device frame) and those of its reference run, over the records.
fn worst(written: &[DVec3], records: &[TickRecord], expected: &[TickRecord]) -> f64 {
    assert_eq!(records.len(), expected.len());
    let mut worst = 0.0f64;
    for ((f, r), e) in written.iter().zip(records).zip(expected) {
        worst = worst
            .max(f.distance(e.force))
            .max(r.force.distance(e.force));
    }
    worst
}

fn dhd_forces(s: &Standin, i: i32) -> Vec<DVec3> {
    s.forces_of(i).into_iter().map(DVec3::from_array).collect()
}

fn hd_forces(s: &Standin, i: i32) -> Vec<DVec3> {
    s.forces_of(i).into_iter().map(from_hd).collect()
}

/// Guards on the references, counted on the scripted runs: both press, and not alike.
fn check_references(expected: &[Vec<TickRecord>; 2]) {
    for e in expected {
        let largest = e.iter().map(|r| r.force.length()).fold(0.0, f64::max);
        assert!(largest > 0.5, "{largest}");
    }
    let differ = expected[0]
        .iter()
        .zip(&expected[1])
        .filter(|(a, b)| a.force.distance(b.force) > 1e-3)
        .count();
    assert!(differ > TICKS as usize / 10, "{differ}");
}

#[test]
fn two_dhd_devices_each_render_their_own_proxy() {
    let _one = serial();
    let s = two("dhd", "HAPHE_DHD_LIBRARY");
    let expected = references();
    check_references(&expected);
    for (i, e) in expected.iter().enumerate() {
        s.set_path_of(i as i32, &trajectory(e));
    }
    let opened = open(&["dhd:0", "dhd:1"]).expect("both open");
    assert!(opened[0].description.contains("stand-in omega.3"));
    assert!(opened[1].description.contains("stand-in sigma.7"));
    let (mut servo, _) = servo_of(opened);
    let mut records = Vec::new();
    let stop = servo.run_simulated(TICKS, |r| records.push(*r));
    assert_eq!(stop, StopReason::Finished);
    servo.close();
    let records = by_device(&records);
    for i in 0..2 {
        let written = dhd_forces(&s, i as i32);
        // Zero at open, one per tick, zero at close (twice: the servo's, the device's).
        assert_eq!(written.len(), 1 + TICKS as usize + 2, "device {i}");
        let w = worst(&written[1..=TICKS as usize], &records[i], &expected[i]);
        println!("dhd:{i}: largest force difference {w:e} N over {TICKS} ticks");
        assert!(w <= 1e-9, "device {i}: {w}");
        assert_eq!(written[written.len() - 1], DVec3::ZERO);
        assert_eq!(s.flag_of("standin_opened_of", i as i32), 0, "closed");
        assert_eq!(s.flag_of("standin_force_enabled_of", i as i32), 0);
    }
}

#[test]
fn both_forces_are_written_every_tick_at_the_rate_asked() {
    let _one = serial();
    let s = two("dhd", "HAPHE_DHD_LIBRARY");
    let expected = references();
    for (i, e) in expected.iter().enumerate() {
        s.set_path_of(i as i32, &trajectory(e));
    }
    let (servo, _) = servo_of(open(&["dhd:1", "dhd:0"]).expect("both open"));
    let running = ServoLoop::spawn(
        servo,
        Some(0.5),
        RealtimeOptions::default().with_realtime_priority(false),
    )
    .expect("a thread");
    let mut records = Vec::new();
    let mut run = running.wait(|r| records.push(*r)).expect("no panic");
    run.servo.close();
    let stats = run.servo.stats();
    assert_eq!(run.stop, StopReason::Finished);
    // Every deadline of 0.5 s at 1 kHz, ticked (or skipped when the machine fell behind,
    // which is printed, not asserted: the machine is shared).
    assert_eq!(stats.ticks + stats.skipped, 500);
    println!(
        "{} ticks, {} skipped, {:.0} Hz achieved",
        stats.ticks,
        stats.skipped,
        stats.achieved_rate()
    );
    assert_eq!(records.len() as u64, 2 * stats.ticks);
    for i in 0..2 {
        // Zero at open, one per tick, zero when the loop stopped, zero at close twice.
        let written = dhd_forces(&s, i);
        assert_eq!(written.len() as u64, 1 + stats.ticks + 3, "device {i}");
    }
    // Servo device 0 is dhd:1: its records are those of the circles, on their path.
    let records = by_device(&records);
    let n = records[0].len();
    let hips = |r: &[TickRecord]| r.iter().map(|r| r.hip).collect::<Vec<_>>();
    // The stand-in gives one sample per read: ticks, not deadlines, step along its path.
    assert_eq!(hips(&records[0]), hips(&expected[1][..n]));
    assert_eq!(hips(&records[1]), hips(&expected[0][..n]));
}

/// Two Touch devices (by name) and a Force Dimension device mixed with a Touch, each
/// clocked by the HD scheduler, ticking every device in its callback.
#[test]
fn the_openhaptics_scheduler_clocks_every_device() {
    let _one = serial();
    let expected = references();
    check_references(&expected);
    for specs in [
        ["openhaptics", "openhaptics:Right"],
        ["dhd:1", "openhaptics:Left"],
    ] {
        let hd = two("hd", "HAPHE_HD_LIBRARY");
        let dhd = two("dhd", "HAPHE_DHD_LIBRARY");
        // Each device's index in its own stand-in.
        let index = |spec: &str| i32::from(spec.ends_with(":1") || spec.ends_with(":Right"));
        for (spec, e) in specs.iter().zip(&expected) {
            if spec.starts_with("dhd") {
                dhd.set_path_of(index(spec), &trajectory(e));
            } else {
                hd.set_path_of(index(spec), &trajectory_hd(e));
            }
        }
        let (servo, clock) = servo_of(open(&specs).expect("both open"));
        let clock = clock.expect("the HD scheduler clocks the servo");
        let running = ServoLoop::spawn_clocked(
            servo,
            clock,
            Some(TICKS as f64 / 1000.0),
            RealtimeOptions::default(),
        )
        .expect("a thread");
        let mut records = Vec::new();
        let mut run = running.wait(|r| records.push(*r)).expect("no panic");
        assert_eq!(run.stop, StopReason::Finished, "{specs:?}");
        assert_eq!(run.servo.stats().ticks, TICKS);
        run.servo.close();
        let records = by_device(&records);
        for (i, spec) in specs.iter().enumerate() {
            let written = if spec.starts_with("dhd") {
                // Zero at open first.
                dhd_forces(&dhd, index(spec))[1..].to_vec()
            } else {
                hd_forces(&hd, index(spec))
            };
            let w = worst(&written[..TICKS as usize], &records[i], &expected[i]);
            println!("{spec} in {specs:?}: largest force difference {w:e} N");
            assert!(w <= 1e-9, "{spec} in {specs:?}: {w}");
            assert!(
                written[TICKS as usize..].iter().all(|f| *f == DVec3::ZERO),
                "{spec}: zero after the run"
            );
        }
    }
}

#[test]
fn a_fault_on_either_device_zeroes_both_and_names_it() {
    let _one = serial();
    let expected = references();
    // The first tick both press, plus one: a force to zero on each.
    let k = (0..TICKS as usize)
        .find(|&k| expected.iter().all(|e| e[k].force.length() > 0.5))
        .expect("both press")
        + 1;
    for faulty in 0..2 {
        let s = two("dhd", "HAPHE_DHD_LIBRARY");
        for (i, e) in expected.iter().enumerate() {
            s.set_path_of(i as i32, &trajectory(e));
        }
        s.fail_from_of(faulty, i32::try_from(k).expect("fits"));
        let (mut servo, _) = servo_of(open(&["dhd:0", "dhd:1"]).expect("both open"));
        let mut records = Vec::new();
        let stop = servo.run_simulated(TICKS, |r| records.push(*r));
        assert_eq!(stop, StopReason::Fault(DeviceFault::Hardware(5)));
        assert_eq!(servo.faulted_device(), Some(faulty as usize));
        let last = &records[records.len() - 2..];
        assert_eq!(last[faulty as usize].fault, Some(DeviceFault::Hardware(5)));
        assert_eq!(last[1 - faulty as usize].fault, None);
        for i in 0..2 {
            let written = dhd_forces(&s, i);
            // Zero at open, then k ticks that pressed, then zero in the tick of the fault.
            assert!(written[k].length() > 0.5, "device {i} pressed before");
            assert_eq!(
                written.len(),
                k + 2,
                "device {i}: one zero force, then none"
            );
            assert_eq!(written[k + 1], DVec3::ZERO, "device {i}");
        }
        drop(servo);
        for i in 0..2 {
            let written = dhd_forces(&s, i);
            assert!(written[k + 1..].iter().all(|f| *f == DVec3::ZERO));
        }
    }
}

#[test]
fn bad_devices_are_refused_and_no_force_is_sent() {
    let _one = serial();
    let s = two("dhd", "HAPHE_DHD_LIBRARY");
    let hd = two("hd", "HAPHE_HD_LIBRARY");
    let cases: [(&[&str], &[&str]); 4] = [
        (
            &["dhd:0", "dhd:0"],
            &["device 2 (dhd:0) is device 1 (dhd:0) again"],
        ),
        (
            &["dhd:0", "dhd:2"],
            &[
                "device 2 (dhd:2)",
                "no Force Dimension device at index 2 (dhd:2): 2 connected, dhd:0 to dhd:1",
            ],
        ),
        (
            &["openhaptics:Left", "openhaptics:Nobody"],
            &[
                "device 2 (openhaptics:Nobody)",
                "hdInitDevice(\"Nobody\") failed: Device fault",
                "configured under that name",
            ],
        ),
        (&["dhd:1", "dhd:7x"], &["unknown device \"dhd:7x\""]),
    ];
    for (case, (specs, needed)) in cases.into_iter().enumerate() {
        let e = open(specs).err().expect("refused").to_string();
        // Refused before any device was opened (dhd:1 is never opened).
        if case == 0 {
            assert!(dhd_forces(&s, 0).is_empty());
        }
        assert!(dhd_forces(&s, 1).is_empty());
        for n in needed {
            assert!(e.contains(n), "{specs:?}: {n:?} missing from: {e}");
        }
        println!("{specs:?}: {e}");
        for i in 0..2 {
            // Never opened, or opened and closed again: never a force.
            assert!(
                dhd_forces(&s, i).iter().all(|f| *f == DVec3::ZERO),
                "{specs:?}: device {i}"
            );
            assert_eq!(s.flag_of("standin_opened_of", i), 0, "{specs:?}");
            assert!(hd_forces(&hd, i).iter().all(|f| *f == DVec3::ZERO));
            assert_eq!(hd.flag_of("standin_force_output_of", i), 0, "{specs:?}");
        }
    }
}
