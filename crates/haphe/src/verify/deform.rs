//! Deforming suites: a shape deformed at every tick while the proxy and its brute-force
//! oracle touch it (a breathing sphere, a travelling dent, a twisting box), checked as
//! [`check_proxy`](super::check_proxy) checks a scene at rest, against the current
//! vertices at every tick.

use std::str::FromStr;

use glam::{DQuat, DVec3};

use super::proxy::{ProxyCheck, ProxyPair};
use crate::proxy::ProxyOptions;
use crate::scene::{DeformError, Scene};

/// How a deforming suite moves a shape's vertices over time, about the centre `c` of its
/// rest bounding box, with `size` its largest half-extent.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Deformation {
    /// The shape scales about its centre by 0.85 to 1.15, at 2 Hz.
    Breathe,
    /// A dent 8 mm deep and a third of the size wide travels around the shape (about
    /// its vertical axis, a turn in 4 s, 30° above its equator), pressing vertices toward
    /// the centre.
    Dent,
    /// Both at once.
    BreatheAndDent,
    /// The shape twists about its vertical axis, the top turning up to ±0.5 rad against
    /// the bottom, at 0.5 Hz.
    Twist,
}

/// Depth of [`Deformation::Dent`], metres.
const DENT_DEPTH_M: f64 = 0.008;

impl Deformation {
    /// Every deformation, for the suites.
    pub const ALL: [Deformation; 4] = [
        Deformation::Breathe,
        Deformation::Dent,
        Deformation::BreatheAndDent,
        Deformation::Twist,
    ];

    /// Its name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Deformation::Breathe => "breathe",
            Deformation::Dent => "dent",
            Deformation::BreatheAndDent => "breathe-dent",
            Deformation::Twist => "twist",
        }
    }

    /// The vertices at time `t` (seconds) of a shape whose vertices at rest are `rest`.
    pub fn vertices_at(self, rest: &[DVec3], t: f64) -> Vec<DVec3> {
        let (lo, hi) = rest
            .iter()
            .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), &p| {
                (lo.min(p), hi.max(p))
            });
        let (c, size) = (0.5 * (lo + hi), 0.5 * (hi - lo).max_element());
        let tau = std::f64::consts::TAU;
        let scale = 1.0 + 0.15 * (tau * 2.0 * t).sin();
        let dent = |p: DVec3| {
            let along = (tau * t / 4.0).sin_cos();
            let centre = DVec3::new(along.1, along.0, 0.0) * 30f64.to_radians().cos()
                + DVec3::Z * 30f64.to_radians().sin();
            let away = (p - c).normalize_or_zero();
            let angle = away.dot(centre).clamp(-1.0, 1.0).acos();
            let width = (size / 3.0) / size.max(f64::MIN_POSITIVE);
            if angle >= width {
                return p;
            }
            let fall = (0.5 * std::f64::consts::PI * angle / width).cos().powi(2);
            p - away * (DENT_DEPTH_M * fall)
        };
        let twist = |p: DVec3| {
            let height = if hi.z > lo.z {
                (p.z - lo.z) / (hi.z - lo.z)
            } else {
                0.0
            };
            let turn = 0.5 * (tau * 0.5 * t).sin() * height;
            c + DQuat::from_rotation_z(turn) * (p - c)
        };
        rest.iter()
            .map(|&p| match self {
                Deformation::Breathe => c + scale * (p - c),
                Deformation::Dent => dent(p),
                Deformation::BreatheAndDent => c + scale * (dent(p) - c),
                Deformation::Twist => twist(p),
            })
            .collect()
    }
}

impl FromStr for Deformation {
    type Err = String;
    fn from_str(s: &str) -> Result<Deformation, String> {
        Deformation::ALL
            .into_iter()
            .find(|d| d.name() == s)
            .ok_or_else(|| {
                let names: Vec<&str> = Deformation::ALL.iter().map(|d| d.name()).collect();
                format!("unknown deformation `{s}` (one of: {})", names.join(", "))
            })
    }
}

/// Runs the fast proxy and the brute-force one along `path` (device points at `rate_hz`)
/// while the first object of `scene` deforms by `deformation` before every tick (its
/// vertices as they were when this was called are the rest shape): mismatches, ticks
/// inside the current surface and bad forces, as [`check_proxy`](super::check_proxy)
/// counts them.
///
/// # Errors
/// What [`Scene::deform`] says (a deformation beyond the largest grid).
pub fn check_deforming(
    scene: &mut Scene,
    deformation: Deformation,
    path: &[DVec3],
    options: ProxyOptions,
    rate_hz: f64,
) -> Result<ProxyCheck, DeformError> {
    let Some(first) = scene.objects().first() else {
        return Ok(ProxyCheck::empty());
    };
    let (id, rest) = (first.id, first.shape.surface().vertices().to_vec());
    let start = path.first().copied().unwrap_or(DVec3::ZERO);
    let mut pair = ProxyPair::new(scene, start, options);
    let mut check = ProxyCheck {
        ticks: path.len(),
        ..ProxyCheck::empty()
    };
    for (tick, &hip) in path.iter().enumerate() {
        let t = tick as f64 / rate_hz;
        scene.deform(id, &deformation.vertices_at(&rest, t))?;
        scene.begin_tick();
        pair.brute().sync(scene);
        pair.tick(scene, tick, hip, &mut check);
    }
    Ok(check)
}
