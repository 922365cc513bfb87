//! Scripted paths over a scene (press, slide, circle, explore, strike) and the kinematic
//! device that follows one exactly.

use std::fmt;
use std::str::FromStr;

use glam::DVec3;

use super::behaviour::Simulated;
use super::spec::simulated_spec;
use super::trajectory::{Trajectory, TrajectoryError};
use crate::rng::SplitMix64;
use crate::scene::Scene;
use crate::servo::device::{DeviceFault, DeviceSpec};

/// How far below the surface a pressing target goes, metres: with the simulated hand's
/// default spring (300 N/m) against a 500 N/m surface it settles about 2.3 mm deep, a
/// light press of about 1.1 N.
const PRESS_DEPTH_M: f64 = 0.006;
/// Height of the hovering start point above the highest object, metres.
const HOVER_M: f64 = 0.03;
/// Speed of a strike, m/s: a fast tap.
const STRIKE_SPEED: f64 = 1.5;
/// Speed of a slide along a surface, m/s.
const SLIDE_SPEED: f64 = 0.05;
/// [`PathKind::Explore`] strokes over random objects of a scene of at most this many
/// objects; a larger scene is explored on its first object only, hovering just above it (a
/// user exploring one object of many, at the speeds of a hand).
pub const EXPLORE_ANY_MAX_OBJECTS: usize = 16;

/// A scripted motion over a scene. The paths are built in the world frame with `+z` up,
/// over the top of the scene's objects (found by probing downward with the collision
/// queries), so they suit any object placed on a table.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum PathKind {
    /// Come down onto the top of the first object (its highest point near the middle),
    /// press 6 mm into it, hold, lift.
    Press,
    /// Press into the top of the first object and slide across it along `x` at
    /// 5 cm/s, following its height, then lift.
    Slide,
    /// Press into the top of the first object and draw circles on it.
    Circle,
    /// Random strokes on the tops of all objects, one a second: move over the scene to
    /// the next stroke, come down, slide, lift (deterministic for a seed).
    Explore,
    /// Hit the top of the first object at 1.5 m/s aiming 4 cm below its surface,
    /// hold, lift.
    Strike,
}

impl PathKind {
    /// Every kind, in declaration order.
    pub const ALL: [PathKind; 5] = [
        PathKind::Press,
        PathKind::Slide,
        PathKind::Circle,
        PathKind::Explore,
        PathKind::Strike,
    ];

    /// The name used on the command line.
    pub fn name(self) -> &'static str {
        match self {
            PathKind::Press => "press",
            PathKind::Slide => "slide",
            PathKind::Circle => "circle",
            PathKind::Explore => "explore",
            PathKind::Strike => "strike",
        }
    }
}

impl fmt::Display for PathKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for PathKind {
    type Err = String;
    fn from_str(s: &str) -> Result<PathKind, String> {
        PathKind::ALL
            .into_iter()
            .find(|k| k.name() == s)
            .ok_or_else(|| {
                format!("unknown path {s:?}: expected press, slide, circle, explore or strike")
            })
    }
}

/// The world bounding box of a scene (from the objects' bounding spheres), metres.
pub fn scene_bounds(scene: &Scene) -> Option<(DVec3, DVec3)> {
    scene.objects().iter().fold(None, |acc, o| {
        let c = o.pose.to_world(o.shape.bound_centre());
        let r = DVec3::splat(o.shape.bound_radius());
        let (lo, hi) = (c - r, c + r);
        Some(match acc {
            None => (lo, hi),
            Some((a, b)) => (a.min(lo), b.max(hi)),
        })
    })
}

/// The highest surface point of the scene under `(x, y)`, metres, world frame: the first
/// crossing of a vertical segment from above every object down to below them.
fn surface_below(scene: &Scene, x: f64, y: f64) -> Option<DVec3> {
    let (lo, hi) = scene_bounds(scene)?;
    let top = DVec3::new(x, y, hi.z + 1.0);
    let bottom = DVec3::new(x, y, lo.z - 1.0);
    (0..scene.objects().len())
        .filter_map(|i| scene.first_hit(i, top, bottom, 0.0))
        .min_by(|a, b| a.t.total_cmp(&b.t))
        .map(|h| h.point)
}

/// Probes per side of the grid that looks for the top of an object.
const TOP_PROBES: i32 = 9;

/// The highest surface point under a grid of vertical probes over the middle of the disc
/// of radius `r` around `c` (metres, world frame): the top of the object there, even when
/// its centre is a hole (a torus).
fn highest_point(scene: &Scene, c: DVec3, r: f64) -> Option<DVec3> {
    let half = TOP_PROBES / 2;
    let step = 0.7 * r / f64::from(half.max(1));
    let mut best: Option<DVec3> = None;
    // Nearest the centre first, so that among equal heights the central point wins.
    let mut offsets: Vec<(i32, i32)> = (-half..=half)
        .flat_map(|i| (-half..=half).map(move |j| (i, j)))
        .collect();
    offsets.sort_by_key(|&(i, j)| i * i + j * j);
    for (i, j) in offsets {
        let x = c.x + f64::from(i) * step;
        let y = c.y + f64::from(j) * step;
        if let Some(p) = surface_below(scene, x, y)
            && best.is_none_or(|b| p.z > b.z + 1e-9)
        {
            best = Some(p);
        }
    }
    best
}

/// A scripted path of `kind` over `scene`, lasting `seconds` (at least one second), in
/// the world frame. `seed` drives [`PathKind::Explore`].
///
/// # Errors
/// [`TrajectoryError::EmptyScene`] when the scene has no object.
pub fn scripted_path(
    kind: PathKind,
    scene: &Scene,
    seconds: f64,
    seed: u64,
) -> Result<Trajectory, TrajectoryError> {
    let seconds = if seconds.is_finite() {
        seconds.max(1.0)
    } else {
        1.0
    };
    let (_, hi) = scene_bounds(scene).ok_or(TrajectoryError::EmptyScene)?;
    let first = &scene.objects()[0];
    let c = first.pose.to_world(first.shape.bound_centre());
    let r = first.shape.bound_radius();
    let layout = Layout {
        scene,
        c,
        r,
        top: highest_point(scene, c, r).unwrap_or(DVec3::new(c.x, c.y, c.z)),
        hover_z: hi.z + HOVER_M,
        t: seconds,
    };
    let keys = match kind {
        PathKind::Press => layout.press(),
        PathKind::Slide => layout.slide(),
        PathKind::Circle => layout.circle(),
        PathKind::Explore => layout.explore(seed),
        PathKind::Strike => layout.strike(),
    };
    Trajectory::from_keys(&keys)
}

/// What a scripted path is laid out over: the scene, the centre `c` and radius `r` of its
/// first object's bounding sphere, the `top` of that object, the height the hand hovers
/// at (`hover_z`) and the path's duration `t`, seconds. Each path is a list of key
/// points (time, world point).
struct Layout<'a> {
    scene: &'a Scene,
    c: DVec3,
    r: f64,
    top: DVec3,
    hover_z: f64,
    t: f64,
}

/// `p` moved down by `depth` metres.
fn under(p: DVec3, depth: f64) -> DVec3 {
    p - DVec3::Z * depth
}

impl Layout<'_> {
    /// The highest surface point under `(x, y)` (at the first object's centre height
    /// where there is none).
    fn top_at(&self, x: f64, y: f64) -> DVec3 {
        surface_below(self.scene, x, y).unwrap_or(DVec3::new(x, y, self.c.z))
    }

    /// `p` lifted to the hovering height.
    fn above(&self, p: DVec3) -> DVec3 {
        DVec3::new(p.x, p.y, self.hover_z)
    }

    fn press(&self) -> Vec<(f64, DVec3)> {
        let (top, t) = (self.top, self.t);
        vec![
            (0.0, self.above(top)),
            (0.3 * t, top + DVec3::Z * 0.002),
            (0.45 * t, under(top, PRESS_DEPTH_M)),
            (0.8 * t, under(top, PRESS_DEPTH_M)),
            (t, self.above(top)),
        ]
    }

    fn slide(&self) -> Vec<(f64, DVec3)> {
        let (c, t) = (self.c, self.t);
        let half = (0.5 * self.r).min(0.5 * SLIDE_SPEED * 0.6 * t);
        let (x0, x1) = (c.x - half, c.x + half);
        let start = self.top_at(x0, c.y);
        let mut keys = vec![
            (0.0, self.above(start)),
            (0.15 * t, start + DVec3::Z * 0.002),
            (0.2 * t, under(start, PRESS_DEPTH_M)),
        ];
        let n = 16;
        for k in 1..=n {
            let s = f64::from(k) / f64::from(n);
            let x = x0 + s * (x1 - x0);
            keys.push((
                0.2 * t + s * 0.6 * t,
                under(self.top_at(x, c.y), PRESS_DEPTH_M),
            ));
        }
        let end = keys[keys.len() - 1].1;
        keys.push((0.9 * t, end + DVec3::Z * (PRESS_DEPTH_M + 0.002)));
        keys.push((t, self.above(end)));
        keys
    }

    fn circle(&self) -> Vec<(f64, DVec3)> {
        let (c, t) = (self.c, self.t);
        let radius = 0.5 * self.r;
        let on = |a: f64| {
            let (x, y) = (c.x + radius * a.cos(), c.y + radius * a.sin());
            under(self.top_at(x, y), PRESS_DEPTH_M)
        };
        let start = on(0.0);
        let mut keys = vec![(0.0, self.above(start)), (0.1 * t, under(start, -0.002))];
        keys.push((0.15 * t, start));
        let turns = 2.0;
        let n = 64;
        for k in 1..=n {
            let s = f64::from(k) / f64::from(n);
            keys.push((
                0.15 * t + s * 0.7 * t,
                on(s * turns * std::f64::consts::TAU),
            ));
        }
        let end = keys[keys.len() - 1].1;
        keys.push((t, self.above(end)));
        keys
    }

    fn explore(&self, seed: u64) -> Vec<(f64, DVec3)> {
        let (scene, c, r, t) = (self.scene, self.c, self.r, self.t);
        let first = &scene.objects()[0];
        let mut rng = SplitMix64::new(seed);
        let strokes = (t / 1.0).round().max(1.0) as usize;
        let dt = t / strokes as f64;
        // One object of many: its own surface under the hand, hovering over its own
        // bounding sphere.
        let one = scene.objects().len() > EXPLORE_ANY_MAX_OBJECTS;
        let own_top = |x: f64, y: f64| {
            let (top, bottom) = (
                DVec3::new(x, y, c.z + r + 1.0),
                DVec3::new(x, y, c.z - r - 1.0),
            );
            scene
                .first_hit(0, top, bottom, 0.0)
                .map_or(DVec3::new(x, y, c.z), |h| h.point)
        };
        let surface = |x: f64, y: f64| {
            if one {
                own_top(x, y)
            } else {
                self.top_at(x, y)
            }
        };
        let above = |p: DVec3| {
            if one {
                DVec3::new(p.x, p.y, c.z + r + HOVER_M)
            } else {
                self.above(p)
            }
        };
        let mut keys = Vec::new();
        for s in 0..strokes {
            let o = if one {
                first
            } else {
                &scene.objects()[rng.index(scene.objects().len())]
            };
            let oc = o.pose.to_world(o.shape.bound_centre());
            let reach = 0.6 * o.shape.bound_radius();
            let mut pick = || {
                let (x, y) = (
                    oc.x + rng.range(-reach, reach),
                    oc.y + rng.range(-reach, reach),
                );
                surface(x, y)
            };
            let (a, b) = (pick(), pick());
            let depth = PRESS_DEPTH_M * rng.range(0.3, 1.5);
            let t0 = s as f64 * dt;
            // Over the top of everything to the next stroke, then straight down.
            // The path starts hovering over the first stroke.
            keys.push((if s == 0 { 0.0 } else { t0 + 0.1 * dt }, above(a)));
            keys.push((t0 + 0.25 * dt, a + DVec3::Z * 0.003));
            keys.push((t0 + 0.35 * dt, under(a, depth)));
            for k in 1..=6 {
                let f = f64::from(k) / 6.0;
                let p = a.lerp(b, f);
                keys.push((t0 + (0.35 + 0.45 * f) * dt, under(surface(p.x, p.y), depth)));
            }
            keys.push((t0 + 0.9 * dt, b + DVec3::Z * 0.01));
        }
        // End lifted off the last stroke.
        let last = keys[keys.len() - 1].1;
        keys.push((t, last + DVec3::Z * 0.02));
        keys
    }

    fn strike(&self) -> Vec<(f64, DVec3)> {
        let (top, t) = (self.top, self.t);
        // Constant speed from 4 cm above the surface to 4 cm below it.
        let start = top + DVec3::Z * 0.04;
        let end = top - DVec3::Z * 0.04;
        let t0 = 0.3 * t;
        let travel = start.distance(end) / STRIKE_SPEED;
        let mut keys = vec![(0.0, self.above(top).max(start)), (t0, start)];
        let n = 8;
        for k in 1..=n {
            let s = f64::from(k) / f64::from(n);
            keys.push((t0 + s * travel, start.lerp(end, s)));
        }
        keys.push((0.75 * t, end));
        keys.push((t, self.above(top).max(start)));
        keys
    }
}

/// A device whose end point follows a path exactly, whatever force it is given: a
/// position-controlled robot, or a perfectly stiff hand. Velocity is the path's.
///
/// It never faults; after the path ends it rests at the last point.
#[derive(Debug, Clone)]
pub struct ScriptedDevice {
    path: Trajectory,
    pub(super) spec: DeviceSpec,
    pub(super) open: bool,
    last_force: DVec3,
    pub(super) presses: super::presses::Presses,
}

impl ScriptedDevice {
    /// A device following `path` (device frame), with the simulated device specification
    /// (`simulated_spec`).
    pub fn new(path: Trajectory) -> ScriptedDevice {
        ScriptedDevice {
            path,
            spec: simulated_spec(),
            open: false,
            last_force: DVec3::ZERO,
            presses: super::presses::Presses::default(),
        }
    }

    /// The last force written, newtons, device frame.
    pub fn last_force(&self) -> DVec3 {
        self.last_force
    }
}

impl Simulated for ScriptedDevice {
    fn sample(&mut self, t: f64) -> Result<(DVec3, DVec3), DeviceFault> {
        Ok(self.path.sample(t))
    }

    fn feel(&mut self, force: DVec3) {
        self.last_force = force;
    }
}
