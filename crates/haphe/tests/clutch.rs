//! The clutch with the simulated hand: while its button is held the tool stays where it
//! was and the mapping's offset follows the hand, so that at the release the offset has
//! moved by minus the hand's travel and the tool continues from where it stayed; the
//! force fades out after the press and back in after the release, never jumping.

use haphe::DVec3;
use haphe::scene::Material;
use haphe::servo::{
    Buttons, HandOptions, PathKind, Servo, ServoOptions, SimulatedHand, TickRecord, scripted_path,
};
use haphe::verify::sphere_scene;

const TICKS: u64 = 3_000;

/// The records of the simulated hand pressing into a sphere for `TICKS` ticks at 1 kHz,
/// button 0 held over `held` (seconds) when given, with the clutch on button 0; and the
/// final mapping offset.
fn run(held: Option<(f64, f64)>) -> (Vec<TickRecord>, DVec3) {
    let scene = sphere_scene(2_000, Material::default()).expect("the sphere");
    let path = scripted_path(PathKind::Press, &scene, TICKS as f64 / 1000.0, 1).expect("a path");
    let mut hand = SimulatedHand::new(path, HandOptions::default());
    if let Some((from, until)) = held {
        hand = hand.press(0, from, until).expect("a valid press");
    }
    let options = ServoOptions::default().with_clutch_button(Some(0));
    let mut servo = Servo::new(hand, scene, options).expect("servo");
    let mut records = Vec::new();
    servo.run_simulated(TICKS, |r| records.push(*r));
    (records, servo.mapping().offset())
}

/// The ticks `[from, until)` of a press given in seconds at 1 kHz.
fn ticks(from: f64, until: f64) -> std::ops::Range<usize> {
    (from * 1000.0).round() as usize..(until * 1000.0).round() as usize
}

/// Acceptance: held in free space on the way down, the tool stays; the hand's positions
/// are those of the run without a press until the release (no force acts on it in
/// either), so its travel is known from that run; the offset moved by minus that travel,
/// and from the release the tool is the hand moved by it.
#[test]
fn held_the_tool_stays_and_the_offset_moves_by_the_hands_travel() {
    let (free, no_offset) = run(None);
    assert_eq!(no_offset, DVec3::ZERO, "never held: the mapping stays");
    let first_force = free
        .iter()
        .position(|r| r.force != DVec3::ZERO)
        .expect("the press touches");
    // Held over the middle half of the approach.
    let (from, until) = (
        first_force as f64 / 4000.0,
        3.0 * first_force as f64 / 4000.0,
    );
    let held = ticks(from, until);
    let (clutched, offset) = run(Some((from, until)));
    let before = free[held.start - 1].hip;
    let travel = free[held.end - 1].hip - before;
    // Guards the premise: the hand moves while the clutch is held.
    assert!(travel.length() > 5e-3, "the hand travels {travel}");
    for k in 0..=held.end {
        let (r, f) = (&clutched[k], &free[k]);
        let is_held = held.contains(&k);
        assert_eq!(
            (r.buttons, r.clutch),
            (Buttons(u32::from(is_held)), is_held)
        );
        let tool = if k < held.start {
            f.hip
        } else if is_held {
            before
        } else {
            f.hip - travel
        };
        assert!(
            r.hip.distance(tool) < 1e-12,
            "tick {k}: {} vs {tool}",
            r.hip
        );
        if is_held {
            assert_eq!(r.velocity, DVec3::ZERO, "held, the tool is at rest");
        }
    }
    assert!((offset + travel).length() < 1e-12, "{offset} vs {travel}");
    // The tool now stops short of where the hand pressed: the press is shallower.
    let deepest = |rs: &[TickRecord]| rs.iter().map(|r| r.penetration).fold(0.0, f64::max);
    assert!(deepest(&clutched) < deepest(&free));
}

/// Held while pressing hard: the force fades to zero over the ramp's 50 ms and comes back
/// over 50 ms after the release; every step between ticks stays within the largest step
/// of the run without a clutch plus one fade step of the maximum force.
#[test]
fn held_in_contact_the_force_fades_and_returns_without_a_jolt() {
    let (free, _) = run(None);
    let strongest = (0..free.len())
        .max_by(|&a, &b| free[a].force.length().total_cmp(&free[b].force.length()))
        .expect("ticks");
    let max_force = ServoOptions::default().proxy().max_force();
    assert!(free[strongest].force.length() > 0.5, "a real press");
    let from = strongest as f64 / 1000.0;
    let (clutched, _) = run(Some((from, from + 0.4)));
    let held = ticks(from, from + 0.4);
    let steps = |rs: &[TickRecord]| {
        rs.windows(2)
            .map(|w| w[1].force.distance(w[0].force))
            .fold(0.0, f64::max)
    };
    let fade_step = max_force * 1e-3 / ServoOptions::default().ramp_seconds();
    assert!(
        steps(&clutched) <= steps(&free) + fade_step + 1e-12,
        "{} vs {} + {fade_step}",
        steps(&clutched),
        steps(&free)
    );
    for (k, r) in clutched.iter().enumerate() {
        assert!(
            r.force.is_finite() && r.force.length() <= max_force + 1e-12,
            "tick {k}"
        );
    }
    // Faded out 50 ms after the press, until the release.
    for (k, r) in clutched
        .iter()
        .enumerate()
        .take(held.end)
        .skip(held.start + 50)
    {
        assert_eq!(r.force, DVec3::ZERO, "tick {k}");
    }
    assert!(clutched[held.start].force.length() > 0.5 * free[strongest].force.length());
}
