//! What the texture and effect tests share: a slab to touch, a servo run along a path, a
//! spectrum, and the work a force does on the hand.

#![allow(dead_code, reason = "each test file uses a part")]

use std::sync::Arc;

use haphe::DVec3;
use haphe::map::MapOptions;
use haphe::mesh::{Mesh, Surface, SurfaceOptions};
use haphe::scene::{Effect, Material, ObjectId, Pose, Scene, SceneObject, Shape, Texture};
use haphe::servo::{ScriptedDevice, Servo, ServoOptions, TickRecord, Trajectory};
use rustfft::FftPlanner;
use rustfft::num_complex::Complex;

/// A box 20 cm wide and 5 cm deep whose top face is the plane z = 0.
pub fn slab() -> Arc<Shape> {
    let (lo, hi) = (DVec3::new(-0.1, -0.1, -0.05), DVec3::new(0.1, 0.1, 0.0));
    let vertices: Vec<DVec3> = (0..8)
        .map(|i| {
            DVec3::new(
                if i & 1 == 0 { lo.x } else { hi.x },
                if i & 2 == 0 { lo.y } else { hi.y },
                if i & 4 == 0 { lo.z } else { hi.z },
            )
        })
        .collect();
    // Counter-clockwise seen from outside.
    let triangles = vec![
        [0, 2, 1],
        [1, 2, 3],
        [4, 5, 6],
        [5, 7, 6],
        [0, 1, 4],
        [1, 5, 4],
        [2, 6, 3],
        [3, 6, 7],
        [0, 4, 2],
        [2, 4, 6],
        [1, 3, 5],
        [3, 7, 5],
    ];
    let surface = Surface::new(
        Mesh {
            vertices,
            triangles,
        },
        &SurfaceOptions::default(),
    )
    .expect("a closed box");
    assert!(surface.is_solid());
    Arc::new(Shape::build(surface, &MapOptions::default()).expect("a map"))
}

/// The slab as object 1 (default material), with `texture`, and `effects`.
pub fn slab_scene(texture: Option<Texture>, effects: &[Effect]) -> Scene {
    let mut scene = Scene::local(2);
    let mut o = SceneObject::new(ObjectId(1), slab(), Pose::IDENTITY, Material::default());
    o.texture = texture;
    scene.insert(o).map_err(|(e, _)| e).expect("room");
    for e in effects {
        scene.add_effect(*e).expect("room for the effect");
    }
    scene
}

/// A servo at `rate` Hz over a scene, driven along paths by a scripted device (no ramp).
pub struct Run {
    scene: Scene,
    rate: f64,
}

impl Run {
    pub fn new(scene: Scene, rate: f64) -> Run {
        Run { scene, rate }
    }

    /// The records of a run along the path through `keys` (seconds, metres), to its end.
    pub fn keys(self, keys: &[(f64, DVec3)]) -> Vec<TickRecord> {
        let path = Trajectory::from_keys(keys).expect("a valid path");
        // Through the tick at the end time.
        let ticks = (path.end_time() * self.rate + 1e-6).floor() as u64 + 1;
        let options = ServoOptions::new(self.rate)
            .and_then(|o| o.with_ramp_seconds(0.0))
            .expect("valid options");
        let mut servo =
            Servo::new(ScriptedDevice::new(path), self.scene, options).expect("a servo");
        let mut records = Vec::with_capacity(ticks as usize);
        servo.run_simulated(ticks, |r| records.push(*r));
        records
    }
}

/// The amplitude spectrum of `x` sampled at `rate` Hz (its mean removed): frequencies and
/// amplitudes (the amplitude of a sine that falls on a bin is its own).
pub fn spectrum(x: &[f64], rate: f64) -> (Vec<f64>, Vec<f64>) {
    let n = x.len();
    let mean = x.iter().sum::<f64>() / n as f64;
    let mut buffer: Vec<Complex<f64>> = x.iter().map(|&v| Complex::new(v - mean, 0.0)).collect();
    FftPlanner::new().plan_fft_forward(n).process(&mut buffer);
    let half = n / 2;
    let freqs = (0..half).map(|k| k as f64 * rate / n as f64).collect();
    let mags = buffer[..half]
        .iter()
        .map(|c| 2.0 * c.norm() / n as f64)
        .collect();
    (freqs, mags)
}

/// The frequency and amplitude of the largest bin from `lo` to `hi` Hz.
pub fn peak_near(freqs: &[f64], mags: &[f64], lo: f64, hi: f64) -> (f64, f64) {
    freqs
        .iter()
        .zip(mags)
        .filter(|(f, _)| (lo..=hi).contains(*f))
        .map(|(&f, &m)| (f, m))
        .fold((0.0, f64::MIN), |a, b| if b.1 > a.1 { b } else { a })
}

/// The work (joules) the forces `forces[k]` do on the hand moving through the records'
/// device points, by the trapezoid rule.
pub fn work_of(records: &[TickRecord], forces: &[DVec3]) -> f64 {
    records
        .windows(2)
        .zip(forces.windows(2))
        .map(|(r, f)| 0.5 * (f[0] + f[1]).dot(r[1].hip - r[0].hip))
        .sum()
}

/// Runs a servo at 10 kHz on `scene` along a circle of `radius` in the xz plane around
/// `centre` (`turn` 1: from +x toward +z; −1 the other way), reached from 5 mm above its
/// start, going round twice at 20 mm/s; returns the rendered force's work on the hand over
/// the second turn, and that turn's records.
pub fn work_around(scene: Scene, centre: DVec3, radius: f64, turn: f64) -> (f64, Vec<TickRecord>) {
    let at = |a: f64| centre + radius * DVec3::new(a.cos(), 0.0, turn * a.sin());
    let start = at(0.0);
    let rate = 10_000.0;
    // Whole ticks, so that the turn measured ends where it began.
    let lap_ticks = (std::f64::consts::TAU * radius / 0.02 * rate).round() as u64;
    let approach_ticks = 3_000;
    let (lap, approach) = (lap_ticks as f64 / rate, approach_ticks as f64 / rate);
    let mut keys = vec![
        (0.0, start + DVec3::Z * (0.005 + radius)),
        (approach, start),
    ];
    let steps = 2000;
    for i in 1..=2 * steps {
        let a = std::f64::consts::TAU * i as f64 / steps as f64;
        keys.push((approach + lap * i as f64 / steps as f64, at(a)));
    }
    let records = Run::new(scene, rate).keys(&keys);
    let second: Vec<TickRecord> = records
        .into_iter()
        .filter(|r| (approach_ticks + lap_ticks..=approach_ticks + 2 * lap_ticks).contains(&r.tick))
        .collect();
    assert_eq!(second.len() as u64, lap_ticks + 1, "a whole turn");
    assert!(second[0].hip.distance(second[second.len() - 1].hip) < 1e-12);
    let forces: Vec<DVec3> = second.iter().map(|r| r.force).collect();
    (work_of(&second, &forces), second)
}
