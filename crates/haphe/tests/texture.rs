//! Textures as felt through the servo: sliding over a sine texture is felt at the speed
//! over the wavelength (a spectrum's peak), the force's change per tick stays within what
//! the texture's slope and curvature allow, and the texture never gives back more work
//! than it took over a closed path (passivity).

mod feel;

use haphe::DVec3;
use haphe::scene::Texture;

use feel::{Run, peak_near, slab_scene, spectrum, work_around};

const STIFFNESS: f64 = 500.0;

fn sine() -> Texture {
    "sine:0.0002:0.002".parse().expect("a valid texture")
}

/// The path: down onto the slab's top (z = 0) 1 mm deep, then along x at `speed`.
fn slide(speed: f64, seconds: f64) -> Vec<(f64, DVec3)> {
    let start = DVec3::new(-0.06, 0.0, 0.003);
    let down = DVec3::new(-0.06, 0.0, -0.001);
    let mut keys = vec![(0.0, start), (0.2, down)];
    let steps = 200;
    for i in 1..=steps {
        let t = seconds * i as f64 / steps as f64;
        keys.push((0.2 + t, down + DVec3::X * (speed * t)));
    }
    keys
}

/// Acceptance 1: sliding at 50 mm/s over `sine:0.0002:0.002`, the force's spectrum peaks
/// at 25 Hz; without the texture it has no such peak.
#[test]
fn sliding_over_a_sine_texture_is_felt_at_speed_over_wavelength() {
    let rate = 1000.0;
    let keys = slide(0.05, 2.4);
    let textured = Run::new(slab_scene(Some(sine()), &[]), rate).keys(&keys);
    let plain = Run::new(slab_scene(None, &[]), rate).keys(&keys);
    // Two seconds of sliding, from 0.3 s.
    let window = |r: &[haphe::servo::TickRecord]| -> Vec<f64> {
        r.iter()
            .filter(|r| r.t >= 0.3)
            .take(2000)
            .map(|r| r.force.z)
            .collect()
    };
    let (tz, pz) = (window(&textured), window(&plain));
    assert_eq!(tz.len(), 2000);
    assert!(
        tz.iter().all(|&f| f > 0.0),
        "in contact all along: {:?}",
        tz.iter().copied().fold(f64::INFINITY, f64::min)
    );
    let (freqs, t_mag) = spectrum(&tz, rate);
    let (_, p_mag) = spectrum(&pz, rate);
    let (f, m) = peak_near(&freqs, &t_mag, 1.0, rate / 2.0);
    assert!((f - 25.0).abs() <= 0.5, "the peak is at {f} Hz");
    // The ridges of the sine across x have amplitude A/3: the force's, k A / 3.
    let expected = STIFFNESS * 0.0002 / 3.0;
    assert!(
        (m - expected).abs() < 0.1 * expected,
        "amplitude {m} N, expected {expected}"
    );
    let (_, plain_there) = peak_near(&freqs, &p_mag, 24.0, 26.0);
    assert!(
        plain_there < 1e-3 * m,
        "untextured: {plain_there} N at 25 Hz"
    );
}

/// The force's change from one tick to the next while sliding at 50 mm/s is within
/// `k v dt (A ω (1 + A ω) + (d + A) A ω²)`: the texture's height and slope change no
/// faster than its slope and curvature times the speed (ω = 2π / L), at 1 and 10 kHz.
#[test]
fn the_force_changes_per_tick_within_the_textures_slope_and_curvature() {
    let (a, l, v, depth) = (0.0002, 0.002, 0.05, 0.001);
    let w = std::f64::consts::TAU / l;
    for rate in [1000.0, 10_000.0] {
        let keys = slide(v, 1.0);
        let records = Run::new(slab_scene(Some(sine()), &[]), rate).keys(&keys);
        let sliding: Vec<_> = records.iter().filter(|r| r.t >= 0.3).collect();
        let largest = sliding
            .windows(2)
            .map(|p| p[1].force.distance(p[0].force))
            .fold(0.0, f64::max);
        let dt = 1.0 / rate;
        let bound = STIFFNESS * v * dt * (a * w * (1.0 + a * w) + (depth + a) * a * w * w);
        assert!(
            largest <= bound,
            "{rate} Hz: {largest} N per tick, bound {bound}"
        );
        assert!(
            largest > 0.1 * bound,
            "{rate} Hz: the texture is felt ({largest} N)"
        );
    }
}

/// Acceptance 3 (textures): around closed paths that go in and out of contact, and that
/// stay in contact at changing depth, the work the force does on the hand is at most 0
/// (1e-8 J: the discretisation of a turn at 10 kHz, measured without a texture, is
/// below 1e-9 J), both ways round, for the sine and the noise textures.
/// The same path with the force's part across the normal left out (a texture rendered as
/// a height only) does positive work one way round: the check can fail.
#[test]
fn a_texture_gives_back_no_more_work_than_it_took() {
    let textures = [
        sine(),
        "noise:0.0001:0.0015".parse().expect("a valid texture"),
    ];
    for texture in textures {
        for (centre, radius) in [
            // Half in contact.
            (DVec3::new(0.0, 0.0, 0.0), 0.002),
            // Always in contact, at depths from 0.5 to 2.5 mm.
            (DVec3::new(0.0, 0.0, -0.0015), 0.001),
        ] {
            let mut normal_only = Vec::new();
            for turn in [1.0, -1.0] {
                let scene = slab_scene(Some(texture.clone()), &[]);
                let (work, records) = work_around(scene, centre, radius, turn);
                assert!(
                    work <= 1e-8,
                    "{texture:?} around {centre} (r {radius}, turn {turn}): {work} J"
                );
                let heights: Vec<DVec3> = records.iter().map(|r| DVec3::Z * r.force.z).collect();
                normal_only.push(feel::work_of(&records, &heights));
            }
            let most = normal_only.iter().copied().fold(f64::MIN, f64::max);
            assert!(most > 1e-6, "{texture:?}: the height alone does {most} J");
        }
    }
}
