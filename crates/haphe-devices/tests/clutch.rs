//! The clutch with the vendor devices, through the real loading and calling path, against
//! the stand-in libraries (tests/standin) holding a button over part of the scripted press:
//! the button reaches the record, and while it is held the tool stays where it was and
//! the mapping's offset follows the hand, so that afterwards the tool is the device point
//! moved by minus the hand's travel while held.

mod common;

use haphe::DVec3;
use haphe::servo::{
    Buttons, RealtimeOptions, Servo, ServoLoop, ServoOptions, StopReason, TickRecord,
};
use haphe_devices::{UdpOptions, open_device};

use common::{Standin, reference, scene, serial, standin, trajectory, trajectory_hd};

const TICKS: u64 = 3_000;
/// The clutch is held over these samples (ticks) of the press.
const HELD: std::ops::Range<usize> = 900..1_600;

/// Scripts `source`'s stand-in (named to the device by `variable`) with the reference press,
/// button 0 held over [`HELD`]; runs `spec` with the clutch on button 0, on the virtual
/// clock or, for a device with a scheduler, clocked by it; returns the reference, the
/// records and the servo's final mapping offset.
fn clutched(
    source: &str,
    variable: &str,
    spec: &str,
    frame: fn(&[TickRecord]) -> Vec<[f64; 6]>,
) -> (Vec<TickRecord>, Vec<TickRecord>, DVec3) {
    let lib = standin(source);
    // SAFETY: the tests of this binary run one at a time (`serial`), and nothing else
    // reads the environment meanwhile.
    unsafe { std::env::set_var(variable, &lib) };
    let standin = Standin::open(&lib);
    standin.reset(1);
    let expected = reference(TICKS);
    standin.set_path(&frame(&expected));
    let masks: Vec<u32> = (0..TICKS as usize)
        .map(|k| u32::from(HELD.contains(&k)))
        .collect();
    standin.set_buttons(&masks);
    let opened = open_device(spec, &scene(), 1.0, UdpOptions::default()).expect("opens");
    let options = ServoOptions::default().with_clutch_button(Some(0));
    let mut servo = Servo::new(opened.device, scene(), options).expect("servo");
    let mut records = Vec::new();
    match opened.clock {
        None => {
            assert_eq!(
                servo.run_simulated(TICKS, |r| records.push(*r)),
                StopReason::Finished
            );
            let offset = servo.mapping().offset();
            servo.close();
            (expected, records, offset)
        }
        Some(clock) => {
            standin.set_period_ns(0);
            let limit = Some(TICKS as f64 / 1000.0);
            let running = ServoLoop::spawn_clocked(servo, clock, limit, RealtimeOptions::default())
                .expect("spawn");
            let mut run = running.wait(|r| records.push(*r)).expect("no panic");
            assert_eq!(run.stop, StopReason::Finished);
            let offset = run.servo.mapping().offset();
            run.servo.close();
            (expected, records, offset)
        }
    }
}

/// Acceptance: while the button is held the tool stays, and the offset has moved by
/// minus the hand's travel, whatever the device.
fn check(expected: &[TickRecord], records: &[TickRecord], offset: DVec3) {
    assert_eq!(records.len(), expected.len());
    let before = expected[HELD.start - 1].hip;
    let travel = expected[HELD.end - 1].hip - before;
    // Guards the test's premise: the hand moves while the clutch is held.
    assert!(travel.length() > 5e-3, "the hand travels {travel}");
    for (k, (r, e)) in records.iter().zip(expected).enumerate() {
        let held = HELD.contains(&k);
        assert_eq!(r.buttons, Buttons(u32::from(held)), "tick {k}");
        assert_eq!(r.clutch, held, "tick {k}");
        let tool = if k < HELD.start {
            e.hip
        } else if held {
            before
        } else {
            e.hip - travel
        };
        assert!(
            r.hip.distance(tool) < 1e-12,
            "tick {k}: {} vs {tool}",
            r.hip
        );
        assert!(
            r.force.is_finite() && r.force.length() <= 3.3 + 1e-12,
            "tick {k}"
        );
    }
    assert!(
        (offset + travel).length() < 1e-12,
        "offset {offset}, travel {travel}"
    );
}

#[test]
fn dhd_clutch_keeps_the_tool_and_moves_the_offset_by_the_hands_travel() {
    let _one = serial();
    let (expected, records, offset) = clutched("dhd", "HAPHE_DHD_LIBRARY", "dhd", trajectory);
    check(&expected, &records, offset);
}

#[test]
fn openhaptics_clutch_keeps_the_tool_and_moves_the_offset_by_the_hands_travel() {
    let _one = serial();
    let (expected, records, offset) =
        clutched("hd", "HAPHE_HD_LIBRARY", "openhaptics", trajectory_hd);
    check(&expected, &records, offset);
}

#[test]
fn without_a_clutch_the_buttons_are_recorded_and_the_tool_follows() {
    let _one = serial();
    let lib = standin("dhd");
    // SAFETY: as above.
    unsafe { std::env::set_var("HAPHE_DHD_LIBRARY", &lib) };
    let standin = Standin::open(&lib);
    standin.reset(1);
    let expected = reference(TICKS);
    standin.set_path(&trajectory(&expected));
    standin.set_buttons(&[0, 0b10, 0b110]);
    let opened = open_device("dhd", &scene(), 1.0, UdpOptions::default()).expect("opens");
    let mut servo = Servo::new(opened.device, scene(), ServoOptions::default()).expect("servo");
    let mut records = Vec::new();
    servo.run_simulated(TICKS, |r| records.push(*r));
    let buttons: Vec<u32> = records.iter().take(4).map(|r| r.buttons.0).collect();
    assert_eq!(buttons, [0, 0b10, 0b110, 0]);
    assert!(records.iter().all(|r| !r.clutch));
    assert!(
        records
            .iter()
            .zip(&expected)
            .all(|(r, e)| r.hip == e.hip && r.force == e.force)
    );
    assert_eq!(servo.mapping().offset(), DVec3::ZERO);
}
