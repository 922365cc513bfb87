//! Force effects as felt through the servo, each against its definition: a vibration's
//! spectrum in contact and its absence in free space, a viscosity's drag (everywhere, in a
//! box, inside an object), a spring, a constant force, a magnet, a stick-slip's saw-tooth;
//! their sum clamped to the device's maximum; a vibration the servo's rate cannot render
//! refused; and every passive effect's work around closed paths at most 0.

mod feel;

use haphe::DVec3;
use haphe::scene::{Effect, ObjectId, Zone};
use haphe::servo::{ScriptedDevice, Servo, ServoError, ServoOptions, TickRecord, Trajectory};

use feel::{Run, peak_near, slab_scene, spectrum, work_around};

fn effect(spec: &str) -> Effect {
    spec.parse().expect("a valid effect")
}

/// The records of a run at `rate` Hz along `keys` over the slab with `effects`.
fn run(effects: &[Effect], keys: &[(f64, DVec3)], rate: f64) -> Vec<TickRecord> {
    Run::new(slab_scene(None, effects), rate).keys(keys)
}

/// Still at `p` for `seconds`.
fn still(p: DVec3, seconds: f64) -> Vec<(f64, DVec3)> {
    vec![(0.0, p + DVec3::Z * 0.004), (0.1, p), (0.1 + seconds, p)]
}

/// Along x at `speed` from `p` for `seconds`, after coming down onto `p`.
fn along_x(p: DVec3, speed: f64, seconds: f64) -> Vec<(f64, DVec3)> {
    let mut keys = vec![(0.0, p + DVec3::Z * 0.004), (0.1, p)];
    for i in 1..=100 {
        let t = seconds * f64::from(i) / 100.0;
        keys.push((0.1 + t, p + DVec3::X * (speed * t)));
    }
    keys
}

/// The records from `t0` seconds on.
fn from(records: &[TickRecord], t0: f64) -> Vec<TickRecord> {
    records.iter().filter(|r| r.t >= t0).copied().collect()
}

/// The force of each record less that of the run without effects, tick by tick.
fn added(with: &[TickRecord], without: &[TickRecord]) -> Vec<DVec3> {
    assert_eq!(with.len(), without.len());
    with.iter()
        .zip(without)
        .map(|(a, b)| {
            assert_eq!(a.hip, b.hip);
            a.force - b.force
        })
        .collect()
}

const DEEP: DVec3 = DVec3::new(0.0, 0.0, -0.001);
const ABOVE: DVec3 = DVec3::new(0.0, 0.0, 0.005);

/// Acceptance 2: `vibration:150:0.3` peaks at 150 Hz with 0.3 N in contact, and is absent
/// in free space.
#[test]
fn a_vibration_is_felt_in_contact_only() {
    let rate = 1000.0;
    let e = [effect("vibration:150:0.3")];
    let pressed = from(&run(&e, &still(DEEP, 2.2), rate), 0.2);
    let z: Vec<f64> = pressed.iter().take(2000).map(|r| r.force.z).collect();
    let (freqs, mags) = spectrum(&z, rate);
    let (f, m) = peak_near(&freqs, &mags, 1.0, rate / 2.0);
    assert_eq!(f, 150.0);
    assert!((m - 0.3).abs() < 0.01, "{m} N");
    assert!(pressed.iter().all(|r| r.status.in_contact));
    let free = from(&run(&e, &still(ABOVE, 1.0), rate), 0.2);
    assert!(
        free.iter()
            .all(|r| r.force == DVec3::ZERO && !r.status.in_contact)
    );
}

/// Acceptance 2: `viscosity:2` gives −0.2 N at 0.1 m/s in free space; in a box only inside
/// it; inside an object only where the device point is inside it.
#[test]
fn a_viscosity_drags_where_its_zone_says() {
    let rate = 1000.0;
    let moving = run(&[effect("viscosity:2")], &along_x(ABOVE, 0.1, 0.5), rate);
    // Past the ends of the path, where the speed changes.
    let steady: Vec<_> = from(&moving, 0.15)
        .into_iter()
        .filter(|r| r.t <= 0.5)
        .collect();
    assert!(steady.len() > 300);
    for r in &steady {
        assert!(
            (r.velocity - DVec3::new(0.1, 0.0, 0.0)).length() < 1e-9,
            "{r:?}"
        );
        assert!(
            (r.force - DVec3::new(-0.2, 0.0, 0.0)).length() < 1e-9,
            "{r:?}"
        );
    }
    // A box over x from 0.01 to 0.02: the drag there only.
    let boxed = Effect::viscosity(
        2.0,
        Zone::Box {
            min: DVec3::new(0.01, -1.0, -1.0),
            max: DVec3::new(0.02, 1.0, 1.0),
        },
    )
    .expect("a valid box");
    let records = run(&[boxed], &along_x(ABOVE, 0.1, 0.5), rate);
    let inside = |r: &TickRecord| (0.01..=0.02).contains(&r.hip.x);
    assert!(records.iter().filter(|r| inside(r)).count() > 50);
    for r in &records {
        let expected = if inside(r) {
            -2.0 * r.velocity
        } else {
            DVec3::ZERO
        };
        assert!((r.force - expected).length() < 1e-12, "{r:?}");
    }
    // Inside the slab (object 1): the drag is added to the contact force while the device
    // point is inside, nothing above it.
    let keys = [
        (0.0, ABOVE),
        (0.2, DVec3::new(0.0, 0.0, -0.002)),
        (0.4, ABOVE),
    ];
    let zone = [Effect::viscosity(2.0, Zone::Inside(ObjectId(1))).expect("valid")];
    let with = run(&zone, &keys, rate);
    let without = run(&[], &keys, rate);
    let mut inside_ticks = 0;
    for ((a, b), d) in with.iter().zip(&without).zip(added(&with, &without)) {
        let expected = if a.hip.z < 0.0 {
            inside_ticks += 1;
            -2.0 * a.velocity
        } else {
            DVec3::ZERO
        };
        assert!((d - expected).length() < 1e-12, "{a:?} {b:?}");
    }
    assert!(inside_ticks > 100);
}

/// Acceptance 2: a spring pulls toward its anchor by `K (anchor − p)`; a constant force is
/// itself; both add to the contact force in contact.
#[test]
fn a_spring_and_a_constant_force_are_their_definitions() {
    let rate = 1000.0;
    let anchor = DVec3::new(0.02, -0.01, 0.03);
    let keys = along_x(ABOVE, 0.05, 0.4);
    let records = run(&[effect("spring:40:0.02:-0.01:0.03")], &keys, rate);
    for r in &records {
        assert!(
            (r.force - 40.0 * (anchor - r.hip)).length() < 1e-12,
            "{r:?}"
        );
    }
    let c = [effect("constant:0.1:0.2:-0.5")];
    for keys in [still(ABOVE, 0.3), still(DEEP, 0.3)] {
        let (with, without) = (run(&c, &keys, rate), run(&[], &keys, rate));
        for d in added(&with, &without) {
            assert!((d - DVec3::new(0.1, 0.2, -0.5)).length() < 1e-12, "{d}");
        }
    }
}

/// Acceptance 2: a magnet pulls toward the nearest surface within its distance (straight
/// down above the slab's top), with its force, not farther; in contact, into the surface.
#[test]
fn a_magnet_pulls_toward_the_surface_within_its_distance() {
    let rate = 1000.0;
    let keys = [
        (0.0, DVec3::new(0.0, 0.0, 0.02)),
        (0.3, DEEP),
        (0.6, DVec3::new(0.0, 0.0, 0.02)),
    ];
    let m = [effect("magnet:0.01:0.7")];
    let (with, without) = (run(&m, &keys, rate), run(&[], &keys, rate));
    let (mut near, mut far, mut touching) = (0, 0, 0);
    for (r, d) in with.iter().zip(added(&with, &without)) {
        let expected = if r.status.in_contact || r.hip.z < 0.01 {
            DVec3::new(0.0, 0.0, -0.7)
        } else {
            DVec3::ZERO
        };
        match (r.status.in_contact, r.hip.z < 0.01) {
            (true, _) => touching += 1,
            (false, true) => near += 1,
            (false, false) => far += 1,
        }
        assert!((d - expected).length() < 1e-9, "{r:?}: {d}");
    }
    assert!(
        near > 50 && far > 50 && touching > 50,
        "{near} {far} {touching}"
    );
}

/// Acceptance 2: stick-slip while sliding in contact: the added force is `K` times the
/// device point's offset across the surface from the anchor, which starts where contact
/// began and jumps to the device point whenever that force would exceed the breakaway
/// force (a saw-tooth: `speed · K / breakaway` slips a second).
#[test]
fn stick_slip_is_a_saw_tooth_across_the_surface() {
    let rate = 1000.0;
    let (k, breakaway, speed) = (1000.0, 0.5, 0.01);
    let keys = along_x(DEEP, speed, 2.0);
    let e = [Effect::stick_slip(k, breakaway).expect("valid")];
    let (with, without) = (run(&e, &keys, rate), run(&[], &keys, rate));
    // The definition, tick by tick.
    let mut anchor: Option<DVec3> = None;
    let mut slips = 0;
    for (r, d) in with.iter().zip(added(&with, &without)) {
        let expected = if r.status.in_contact {
            let a = *anchor.get_or_insert(r.hip);
            let across = DVec3::new(a.x - r.hip.x, a.y - r.hip.y, 0.0);
            if k * across.length() > breakaway {
                anchor = Some(r.hip);
                slips += 1;
                DVec3::ZERO
            } else {
                k * across
            }
        } else {
            anchor = None;
            DVec3::ZERO
        };
        assert!((d - expected).length() < 1e-9, "{r:?}: {d} vs {expected}");
    }
    let sliding_seconds = 2.0;
    let expected_slips = speed * sliding_seconds * k / breakaway;
    assert!(
        (f64::from(slips) - expected_slips).abs() <= 2.0,
        "{slips} slips, {expected_slips} expected"
    );
}

/// Effects add to the contact force and the sum is clamped to the device's maximum.
#[test]
fn effects_add_up_and_the_sum_is_clamped() {
    let rate = 1000.0;
    let e = [effect("constant:0:0:-2.5"), effect("constant:0:0:-2.5")];
    let records = from(&run(&e, &still(ABOVE, 0.2), rate), 0.15);
    let max = ServoOptions::default().proxy().max_force();
    for r in &records {
        assert!(
            (r.force - DVec3::new(0.0, 0.0, -max)).length() < 1e-12,
            "{r:?}"
        );
        assert!(r.status.force_clamped);
    }
    // Each effect is bounded by the maximum on its own.
    let big = [effect("constant:0:0:-90"), effect("constant:0:0:85")];
    let records = from(&run(&big, &still(ABOVE, 0.2), rate), 0.15);
    for r in &records {
        assert!((r.force - DVec3::ZERO).length() < 1e-12, "{r:?}");
    }
}

/// A vibration above half the servo rate is refused when the servo is made.
#[test]
fn a_vibration_the_rate_cannot_render_is_refused() {
    let scene = slab_scene(None, &[effect("vibration:600:0.3")]);
    let device = ScriptedDevice::new(Trajectory::still(ABOVE));
    let options = ServoOptions::new(1000.0).expect("valid");
    match Servo::new(device, scene, options) {
        Err(ServoError::Effect(e)) => {
            let m = e.to_string();
            assert!(
                m.starts_with("vibration frequency must be at most half"),
                "{m}"
            );
        }
        other => panic!("{:?}", other.map(|_| ())),
    }
    let scene = slab_scene(None, &[effect("vibration:600:0.3")]);
    let device = ScriptedDevice::new(Trajectory::still(ABOVE));
    assert!(Servo::new(device, scene, ServoOptions::new(1200.0).expect("valid")).is_ok());
}

/// Acceptance 3: around closed paths in and out of contact, the work every passive effect
/// does on the hand is at most 0 (1e-8 J: the discretisation), both ways round; the
/// dissipative ones (viscosity, stick-slip) take work.
#[test]
fn passive_effects_give_back_no_more_work_than_they_took() {
    let cases = [
        ("spring:40:0.01:0.02:0.03", false),
        ("constant:0.3:-0.2:-0.4", false),
        ("magnet:0.01:0.7", false),
        ("viscosity:2", true),
        ("stick-slip:1000:0.2", true),
    ];
    for (spec, dissipative) in cases {
        for turn in [1.0, -1.0] {
            let scene = slab_scene(None, &[effect(spec)]);
            let (work, _) = work_around(scene, DVec3::ZERO, 0.002, turn);
            assert!(work <= 1e-8, "{spec} (turn {turn}): {work} J");
            if dissipative {
                assert!(work < -1e-6, "{spec} (turn {turn}) takes work: {work} J");
            }
        }
    }
}
