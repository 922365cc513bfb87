//! Deep strikes: the hand driven in a straight line into an object, to any depth up to
//! passing through it and out the other side, and what the proxy's force does meanwhile.
//!
//! A solid never pulls the hand on into itself: from the tick a strike first goes deeper
//! than the saturation depth until the hand stops, the force must have no component along
//! the strike direction, and the proxy must stay on the side of entry (never on a surface
//! that faces along the strike, the side the hand leaves through). Before that tick the
//! hand is within the saturation depth, the physical range, where the proxy is the
//! god-object: a grazing strike slides over the surface, and past a crest a frictionless
//! surface's normal leans along the strike and pushes the hand on, as a rigid surface
//! does. Those ticks are counted apart.

use glam::DVec3;
use serde::Serialize;

use crate::proxy::{Proxy, ProxyOptions, saturation_depth};
use crate::query::{Side, classify_point};
use crate::rng::SplitMix64;
use crate::scene::{Scene, SceneObject};

/// Largest force along the strike direction a check accepts, newtons (rounding).
pub const STRIKE_FORCE_TOLERANCE_N: f64 = 1e-6;

/// Largest strike angle from the surface's inward normal, degrees.
pub const MAX_STRIKE_ANGLE_DEG: f64 = 70.0;

/// Strike speeds, m/s (drawn log-uniformly).
pub const STRIKE_SPEEDS: (f64, f64) = (0.5, 10.0);

/// How far outside the surface a strike starts, metres.
const RUN_UP_M: f64 = 0.01;

/// Ticks the hand stays still at the end of a strike.
const STILL_TICKS: usize = 20;

/// One straight strike at `rate_hz`: the device points from `start` along the unit `dir`
/// at `speed` m/s for `length` metres, then `STILL_TICKS` (20) ticks at rest. Returns the
/// points and the index of the last one where the hand still moves forward.
pub fn strike_path(
    start: DVec3,
    dir: DVec3,
    speed: f64,
    length: f64,
    rate_hz: f64,
) -> (Vec<DVec3>, usize) {
    let step = speed / rate_hz;
    let moving = ((length / step).ceil() as usize).clamp(1, 1_000_000);
    let mut out = Vec::with_capacity(moving + 1 + STILL_TICKS);
    out.push(start);
    for k in 1..=moving {
        out.push(start + dir * (k as f64 * step).min(length));
    }
    let last = out.len() - 1;
    let end = out[last];
    out.extend(std::iter::repeat_n(end, STILL_TICKS));
    (out, last)
}

/// The edges of the speed classes a [`StrikeCheck`] counts apart, m/s.
pub const STRIKE_SPEED_CLASSES: [f64; 5] = [0.5, 1.0, 2.0, 4.0, 10.0];

/// What the ticks of some strikes did: ticks checked, and of those the ticks whose force
/// pushes the hand on along the strike or whose contact plane faces along it.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct StrikeTicks {
    /// Strikes.
    pub strikes: usize,
    /// Ticks checked (from the first touch until the hand stops).
    pub ticks: usize,
    /// Checked ticks with a force along the strike above [`STRIKE_FORCE_TOLERANCE_N`].
    pub pushes_on: usize,
    /// Checked ticks where the proxy's contact plane faces along the strike (the far
    /// side).
    pub far_side: usize,
    /// Largest force along the strike, newtons (0 when there is none).
    pub max_push_n: f64,
}

impl StrikeTicks {
    fn add(&mut self, other: &StrikeTicks) {
        self.strikes += other.strikes;
        self.ticks += other.ticks;
        self.pushes_on += other.pushes_on;
        self.far_side += other.far_side;
        self.max_push_n = self.max_push_n.max(other.max_push_n);
    }

    /// Whether no tick pushed the hand on or faced the far side.
    pub fn clean(&self) -> bool {
        self.pushes_on == 0 && self.far_side == 0
    }
}

/// The force along the strike and the side of the proxy over strikes on one object: the
/// ticks from the first touch until the hand stops, split where the strike first goes
/// deeper than the saturation depth. The *deep* ticks (from that tick on, the proxy holding
/// or about to) must all be clean. The *shallow* ticks before it are the physical range,
/// where the proxy is the god-object: a grazing strike slides over the surface, and past a
/// crest a frictionless surface pushes the hand on along its normal, as a rigid one does.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StrikeCheck {
    /// Strikes run.
    pub strikes: usize,
    /// Drawn strikes not run: their start was not outside, or the line did not enter the
    /// object first at the drawn point.
    pub skipped: usize,
    /// Ticks run.
    pub ticks: usize,
    /// Ticks where the proxy held (beyond the saturation depth).
    pub held_ticks: usize,
    /// The ticks from the one a strike first goes deeper than the saturation depth until
    /// the hand stops (`strikes`: the strikes that went that deep): every one must be
    /// clean.
    pub deep: StrikeTicks,
    /// The ticks from the first touch until then (`strikes`: the strikes with such
    /// ticks): the physical range.
    pub shallow: StrikeTicks,
    /// The deep ticks by the strike's speed class ([`STRIKE_SPEED_CLASSES`]).
    pub deep_by_speed: [StrikeTicks; 4],
    /// The shallow ticks by the strike's speed class.
    pub shallow_by_speed: [StrikeTicks; 4],
    /// Strikes (index, angle in degrees, speed m/s, depth m) with a deep tick that is not
    /// clean, a few.
    pub failures: Vec<(usize, f64, f64, f64)>,
    /// Strikes (the same) with a shallow tick pushing on or facing along the strike, a
    /// few.
    pub shallow_pushing: Vec<(usize, f64, f64, f64)>,
}

/// Runs `count` deep strikes drawn with `seed` on object 0 of `scene` (a solid at rest):
/// each enters at a random point of the surface at an angle up to
/// [`MAX_STRIKE_ANGLE_DEG`] from the inward normal, at a speed in [`STRIKE_SPEEDS`], at
/// `rate_hz`, and goes on in a straight line to a depth drawn up to `max_depth` metres past
/// the entry (beyond the far side for a depth above the object's size).
pub fn check_strikes(
    scene: &Scene,
    options: ProxyOptions,
    count: usize,
    max_depth: f64,
    rate_hz: f64,
    seed: u64,
) -> StrikeCheck {
    let mut random = SplitMix64::new(seed);
    let mut check = StrikeCheck {
        strikes: 0,
        skipped: 0,
        ticks: 0,
        held_ticks: 0,
        deep: StrikeTicks::default(),
        shallow: StrikeTicks::default(),
        deep_by_speed: [StrikeTicks::default(); 4],
        shallow_by_speed: [StrikeTicks::default(); 4],
        failures: Vec::new(),
        shallow_pushing: Vec::new(),
    };
    let Some(o) = scene.objects().first() else {
        return check;
    };
    let surface = o.shape.surface();
    let saturation = saturation_depth(&o.material, options.max_force);
    for index in 0..count {
        let strike = Strike::draw(&mut random, o, max_depth);
        let start = strike.start();
        let enters_here = scene
            .first_hit(0, start, strike.entry + 1e-4 * strike.dir, 0.0)
            .is_some_and(|h| h.point.distance(strike.entry) < 1e-7);
        let outside =
            classify_point(surface, o.shape.map(), o.pose.to_object(start)).0 == Side::Outside;
        if !(enters_here && outside && strike.tangent != DVec3::ZERO) {
            check.skipped += 1;
            continue;
        }
        check.strikes += 1;
        let [shallow, deep] = run_strike(scene, options, &strike, rate_hz, saturation, &mut check);
        let class = STRIKE_SPEED_CLASSES[1..4]
            .iter()
            .take_while(|&&edge| strike.speed >= edge)
            .count();
        check.shallow.add(&shallow);
        check.shallow_by_speed[class].add(&shallow);
        check.deep.add(&deep);
        check.deep_by_speed[class].add(&deep);
        let drawn = (index, strike.angle, strike.speed, strike.depth);
        if !deep.clean() && check.failures.len() < super::KEPT_FAILURES {
            check.failures.push(drawn);
        }
        if !shallow.clean() && check.shallow_pushing.len() < super::KEPT_FAILURES {
            check.shallow_pushing.push(drawn);
        }
    }
    check
}

/// One strike drawn at random: where it enters (world frame), its unit direction and the
/// tangent it leans toward, its angle from the inward normal (degrees), speed (m/s) and
/// depth past the entry (metres).
struct Strike {
    entry: DVec3,
    dir: DVec3,
    tangent: DVec3,
    angle: f64,
    speed: f64,
    depth: f64,
}

impl Strike {
    /// A strike on object `o`, drawn with `random`, at most `max_depth` deep.
    fn draw(random: &mut SplitMix64, o: &SceneObject, max_depth: f64) -> Strike {
        let surface = o.shape.surface();
        let t = crate::mesh::TriId(random.index(surface.triangle_count()) as u32);
        let [a, b, c] = surface.corners(t);
        let (u, v) = (random.range(0.05, 0.9), random.range(0.05, 0.9));
        let (u, v) = if u + v > 0.95 {
            (0.95 - u, 0.95 - v)
        } else {
            (u, v)
        };
        let entry = o.pose.to_world(a + u * (b - a) + v * (c - a));
        let n = o.pose.vector_to_world(surface.frame(t).normal);
        let angle = random.range(0.0, MAX_STRIKE_ANGLE_DEG);
        let side = random.unit_vector();
        let tangent = (side - side.dot(n) * n).normalize_or_zero();
        let (s, co) = angle.to_radians().sin_cos();
        let dir = (-co * n + s * tangent).normalize();
        let speed = (STRIKE_SPEEDS.0.ln()
            + random.next_unit() * (STRIKE_SPEEDS.1 / STRIKE_SPEEDS.0).ln())
        .exp();
        let depth = random.range(0.0, max_depth);
        Strike {
            entry,
            dir,
            tangent,
            angle,
            speed,
            depth,
        }
    }

    /// Where the hand starts, a run-up before the entry.
    fn start(&self) -> DVec3 {
        self.entry - RUN_UP_M * self.dir
    }
}

/// Runs one strike at `rate_hz` with a new proxy, counting its ticks in `check`; returns
/// its moving ticks in contact before and after it went deeper than `saturation`.
fn run_strike(
    scene: &Scene,
    options: ProxyOptions,
    strike: &Strike,
    rate_hz: f64,
    saturation: Option<f64>,
    check: &mut StrikeCheck,
) -> [StrikeTicks; 2] {
    let (start, dir) = (strike.start(), strike.dir);
    let (path, last_moving) =
        strike_path(start, dir, strike.speed, RUN_UP_M + strike.depth, rate_hz);
    let mut proxy = Proxy::new(start, options);
    let mut touched = false;
    let mut deep = false;
    let mut ticks = [StrikeTicks::default(); 2];
    let mut previous = start;
    for (k, &hip) in path.iter().enumerate() {
        let out = proxy.tick(scene, hip, (hip - previous) * rate_hz);
        previous = hip;
        check.ticks += 1;
        check.held_ticks += usize::from(out.status.deep_hold);
        deep |= out.status.deep_hold
            || out
                .contact
                .is_some_and(|c| saturation.is_some_and(|d| c.penetration > d));
        touched |= out.contact.is_some();
        if !touched || k > last_moving {
            continue;
        }
        let t = &mut ticks[usize::from(deep)];
        t.strikes = 1;
        t.ticks += 1;
        let push = out.force.dot(dir);
        t.max_push_n = t.max_push_n.max(push);
        t.pushes_on += usize::from(push > STRIKE_FORCE_TOLERANCE_N);
        t.far_side += usize::from(out.contact.is_some_and(|c| c.normal.dot(dir) > 0.0));
    }
    ticks
}
