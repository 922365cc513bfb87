//! Deep strikes: the hand driven in a straight line into an object, to any depth up to
//! passing through it and out the other side, and what the proxy's force does meanwhile.
//!
//! A solid never pulls the hand on into itself: from the tick a strike first goes deeper
//! than the saturation depth until the hand stops, the force must have no component along
//! the strike direction, and the proxy must stay on the side of entry: never on the far
//! side, a surface facing along the strike behind the plane the strike entered through
//! (where the hand leaves; see [`StrikeEntry::far_side`]). Before that tick the
//! hand is within the saturation depth, the physical range, where the proxy is the
//! god-object: a grazing strike slides over the surface, and past a crest a frictionless
//! surface's normal leans along the strike and pushes the hand on, as a rigid surface
//! does. Those ticks are counted apart.
//!
//! Which ticks are deep is decided from the device's path alone, never from the proxy
//! under test: the entry is the first crossing of the strike line by brute force (every
//! triangle), and a tick is deep from the first one where the hand lies inside the solid
//! (by winding number) farther than the saturation depth from every triangle. At that
//! depth the hand is deeper than the saturation depth behind any contact plane the
//! god-object could have reached (its closest feasible point lies on the surface, at least
//! that far away), so the rule of `docs/deep-penetration.md` has the proxy holding. A proxy
//! that slid round the object instead (the old bug) therefore lands in the deep class,
//! where its pushes are counted as failures, whatever penetration it reports. (In a
//! concave crease or corner the god-object rests against two or three planes and tests
//! the depth behind the last one it met, which the hand may lie in front of: there it
//! holds from a later tick, or not at all, pinned in the corner. The check asserts what
//! the hand feels, not the hold: in contact, no push on, not on the far side.)

use glam::DVec3;
use serde::Serialize;

use super::hold::saturation_depth_of;
use super::limits::KEPT_FAILURES;
use super::oracle::{BruteCrossing, WindingOracle, distance_to_surface};
use crate::proxy::{Proxy, ProxyOptions};
use crate::rng::SplitMix64;
use crate::scene::{Scene, SceneObject};

/// Largest force along the strike direction a check accepts, newtons (rounding).
pub const STRIKE_FORCE_TOLERANCE_N: f64 = 1e-6;

/// Largest strike angle from the surface's inward normal, degrees.
pub const MAX_STRIKE_ANGLE_DEG: f64 = 70.0;

/// Strike speeds, m/s (drawn log-uniformly).
pub const STRIKE_SPEEDS: (f64, f64) = (0.5, 10.0);

/// The least share of a family's strikes that must go deeper than the saturation depth
/// (by the hand's path, [`hand_goes_deep`]) for the family to pass. The deep ticks are the
/// only ones the check asserts anything of: a family whose strikes stay in the physical
/// range would pass whatever the hold does, and the strikes drawn here (depths up to
/// 0.25 m on a 0.2 m model) go that deep in 79–96 % of draws on the models of
/// `docs/deep-penetration.md`. A drawing that stopped reaching that depth (depths or
/// speeds scaled down, entries all skipped) falls below half. A large family needs no
/// more than [`ENOUGH_DEEP_STRIKES`].
pub const MIN_DEEP_STRIKE_SHARE: f64 = 0.5;

/// Deep strikes enough for any family, however many strikes it runs: a thin model (a
/// plate a few millimetres thick, whose points lie within the saturation depth of its
/// surface but near its holes and rims) has few points that deep, so a few percent of its
/// strikes go deep; fifty of them check the hold as well as half of a small family does.
pub const ENOUGH_DEEP_STRIKES: usize = 50;

/// The fewest deep strikes a family of `strikes` strikes must have:
/// [`MIN_DEEP_STRIKE_SHARE`] of them, at most [`ENOUGH_DEEP_STRIKES`], at least one.
pub fn required_deep_strikes(strikes: usize) -> usize {
    ((strikes as f64 * MIN_DEEP_STRIKE_SHARE).ceil() as usize).clamp(1, ENOUGH_DEEP_STRIKES)
}

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
    /// Checked ticks where the proxy is on the far side: its contact plane faces along
    /// the strike and lies behind the plane the strike entered through
    /// ([`StrikeEntry::far_side`]).
    pub far_side: usize,
    /// Checked ticks where the proxy touched nothing (a proxy that fell through renders no
    /// force, which would otherwise look clean).
    pub no_contact: usize,
    /// Largest force along the strike, newtons (0 when there is none).
    pub max_push_n: f64,
}

impl StrikeTicks {
    fn add(&mut self, other: &StrikeTicks) {
        self.strikes += other.strikes;
        self.ticks += other.ticks;
        self.pushes_on += other.pushes_on;
        self.far_side += other.far_side;
        self.no_contact += other.no_contact;
        self.max_push_n = self.max_push_n.max(other.max_push_n);
    }

    /// Whether no tick pushed the hand on or faced the far side.
    pub fn clean(&self) -> bool {
        self.pushes_on == 0 && self.far_side == 0
    }

    /// Whether every tick was in contact and [`StrikeTicks::clean`]: what a deep tick
    /// must be.
    pub fn held_back(&self) -> bool {
        self.clean() && self.no_contact == 0
    }
}

/// The force along the strike and the side of the proxy over strikes on one object: the
/// ticks from the hand passing the entry until it stops, split where the hand first lies
/// deeper than the saturation depth inside the solid (by the path, [`hand_goes_deep`]).
/// The *deep* ticks (from that tick on, the proxy holding) must all be in contact and
/// clean, and at least [`required_deep_strikes`] of the strikes must have some. The
/// *shallow* ticks before it are the physical range, where the proxy is the god-object: a
/// grazing strike slides over the surface, and past a crest a frictionless surface pushes
/// the hand on along its normal, as a rigid one does.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StrikeCheck {
    /// Strikes run.
    pub strikes: usize,
    /// Drawn strikes not run: their start was not outside, or the line did not enter the
    /// object first at the drawn point (both by brute force).
    pub skipped: usize,
    /// Ticks run.
    pub ticks: usize,
    /// Ticks where the proxy held (beyond the saturation depth).
    pub held_ticks: usize,
    /// The ticks from the one where the hand first lies deeper than the saturation depth
    /// inside the solid until the hand stops (`strikes`: the strikes that went that deep):
    /// every one must be in contact and clean.
    pub deep: StrikeTicks,
    /// The ticks from the hand passing the entry until then (`strikes`: the strikes with
    /// such ticks): the physical range.
    pub shallow: StrikeTicks,
    /// The deep ticks by the strike's speed class ([`STRIKE_SPEED_CLASSES`]).
    pub deep_by_speed: [StrikeTicks; 4],
    /// The shallow ticks by the strike's speed class.
    pub shallow_by_speed: [StrikeTicks; 4],
    /// The fewest deep strikes the check accepts ([`required_deep_strikes`] of the
    /// strikes run).
    pub min_deep_strikes: usize,
    /// Strikes (index, angle in degrees, speed m/s, depth m) with a deep tick that is not
    /// in contact or not clean, a few.
    pub failures: Vec<(usize, f64, f64, f64)>,
    /// Strikes (the same) with a shallow tick pushing on or on the far side, a few.
    pub shallow_pushing: Vec<(usize, f64, f64, f64)>,
}

impl StrikeCheck {
    /// Whether enough strikes went deep ([`StrikeCheck::min_deep_strikes`]) and every
    /// deep tick held the hand back ([`StrikeTicks::held_back`]).
    pub fn passed(&self) -> bool {
        self.deep.strikes >= self.min_deep_strikes && self.deep.held_back()
    }
}

/// The index of the first of `path`'s points (world frame, consecutive points at most
/// `step` metres apart) where the hand lies inside object 0 of `scene` farther than
/// `depth` metres from its surface, by brute force: the winding number and the distance
/// to every triangle. The signed depth (positive inside) changes by at most `step` per
/// point, so points that cannot have reached `depth` yet are passed over without a query.
pub fn hand_goes_deep(
    scene: &Scene,
    winding: &WindingOracle,
    path: &[DVec3],
    step: f64,
    depth: f64,
) -> Option<usize> {
    let o = scene.objects().first()?;
    let surface = o.shape.surface();
    let mut k = 0;
    while k < path.len() {
        let p = o.pose.to_object(path[k]);
        let distance = distance_to_surface(surface, p);
        let signed = if winding.winding(p) != 0 {
            distance
        } else {
            -distance
        };
        if signed > depth {
            return Some(k);
        }
        // Points before `k + jump` are less than `depth - signed` from this one.
        let jump = if step > 0.0 {
            ((depth - signed) / step).floor()
        } else {
            f64::INFINITY
        };
        k = k.saturating_add((jump.min(1e9) as usize).max(1));
    }
    None
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
        min_deep_strikes: 1,
        failures: Vec::new(),
        shallow_pushing: Vec::new(),
    };
    let Some(o) = scene.objects().first() else {
        return check;
    };
    let surface = o.shape.surface();
    let crossing = BruteCrossing::new(surface);
    let winding = WindingOracle::new(surface);
    let saturation = saturation_depth_of(&o.material, options.max_force);
    for index in 0..count {
        let strike = Strike::draw(&mut random, o, max_depth);
        if !strike.enters(o, &crossing, &winding) {
            check.skipped += 1;
            continue;
        }
        check.strikes += 1;
        let (path, last_moving) = strike_path(
            strike.start(),
            strike.dir,
            strike.speed,
            RUN_UP_M + strike.depth,
            rate_hz,
        );
        // The hand passes the entry after the run-up; it is deep from `deep_from` on.
        let step = strike.speed / rate_hz;
        let deep_from = saturation
            .and_then(|d| hand_goes_deep(scene, &winding, &path[..=last_moving], step, d))
            .unwrap_or(usize::MAX);
        let window = ((RUN_UP_M / step).floor() as usize, last_moving, deep_from);
        let [shallow, deep] =
            run_strike(scene, options, &strike, &path, window, rate_hz, &mut check);
        let class = STRIKE_SPEED_CLASSES[1..4]
            .iter()
            .take_while(|&&edge| strike.speed >= edge)
            .count();
        check.shallow.add(&shallow);
        check.shallow_by_speed[class].add(&shallow);
        check.deep.add(&deep);
        check.deep_by_speed[class].add(&deep);
        let kept = (index, strike.angle, strike.speed, strike.depth);
        if !deep.held_back() && check.failures.len() < KEPT_FAILURES {
            check.failures.push(kept);
        }
        if !shallow.clean() && check.shallow_pushing.len() < KEPT_FAILURES {
            check.shallow_pushing.push(kept);
        }
    }
    check.min_deep_strikes = required_deep_strikes(check.strikes);
    check
}

/// Where a strike enters a solid: the point, the outward normal of the triangle it enters
/// through and the direction it goes on in, world frame. It says which contacts are on the
/// object's far side for this strike.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StrikeEntry {
    /// The entry point: the strike line's first crossing of the surface.
    pub point: DVec3,
    /// The unit outward normal of the triangle the strike enters through.
    pub normal: DVec3,
    /// The strike's unit direction (into the solid: `dir · normal < 0`).
    pub dir: DVec3,
}

impl StrikeEntry {
    /// Whether a contact at `point` whose contact plane has the unit `normal` is on the
    /// far side: the plane faces along the strike (`normal · dir > 0`) and the point lies
    /// behind the entry plane (the plane through the entry point with the entry
    /// triangle's normal) by more than `skin` metres (the proxy's skin, its distance off a
    /// surface it rests on).
    ///
    /// The strike line past the entry lies wholly behind the entry plane (it goes in at
    /// most [`MAX_STRIKE_ANGLE_DEG`] from the inward normal), so every surface it leaves
    /// the object through lies behind it: those surfaces, and any other facing along the
    /// strike back there, are the far side, where a proxy that crawled round the object
    /// ends up. A surface facing along the strike on or in front of the entry plane is on
    /// the side of entry: a wall of a notch or an overhang beside the entry (the raised
    /// letters of `20mm-xyz-cube.stl` meet the cube's face in 57° notches, whose
    /// downward-facing wall lies 89° from a strike into the upward-facing one). A
    /// god-object whose path toward the hand is blocked there rests against that wall,
    /// with the force still back along the strike. On a convex solid every surface point
    /// off the entry plane lies behind it, so there this is the plane facing along the
    /// strike alone.
    #[inline]
    pub fn far_side(&self, point: DVec3, normal: DVec3, skin: f64) -> bool {
        normal.dot(self.dir) > 0.0 && (self.point - point).dot(self.normal) > skin
    }
}

/// One strike drawn: where it enters the object, along which direction, how fast and how
/// deep.
struct Strike {
    entry: DVec3,
    /// The unit outward normal of the entry triangle, world frame.
    normal: DVec3,
    dir: DVec3,
    /// The direction's part along the surface (zero for a strike along the normal).
    tangent: DVec3,
    angle: f64,
    speed: f64,
    depth: f64,
}

impl Strike {
    /// A strike at a random point of a random triangle of `o`, at an angle up to
    /// [`MAX_STRIKE_ANGLE_DEG`] from the inward normal, a speed in [`STRIKE_SPEEDS`]
    /// (uniform in its logarithm) and a depth up to `max_depth`.
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
            normal: n,
            dir,
            tangent,
            angle,
            speed,
            depth,
        }
    }

    /// Where it enters and in which direction.
    fn line(&self) -> StrikeEntry {
        StrikeEntry {
            point: self.entry,
            normal: self.normal,
            dir: self.dir,
        }
    }

    /// Where the hand starts: the run-up before the entry.
    fn start(&self) -> DVec3 {
        self.entry - RUN_UP_M * self.dir
    }

    /// Whether the strike starts outside `o` and first enters it at its entry point (a
    /// strike that would enter elsewhere first, or has no tangent, is skipped).
    fn enters(&self, o: &SceneObject, crossing: &BruteCrossing, winding: &WindingOracle) -> bool {
        let start_object = o.pose.to_object(self.start());
        let past_entry = o.pose.to_object(self.entry + 1e-4 * self.dir);
        let enters_here = crossing
            .first_crossing(start_object, past_entry)
            .is_some_and(|h| o.pose.to_world(h.point).distance(self.entry) < 1e-7);
        let outside = winding.winding(start_object) == 0;
        enters_here && outside && self.tangent != DVec3::ZERO
    }
}

/// Ticks a proxy along a strike's `path`, counting every tick in `check`; returns the
/// ticks of the strike's window `(entered, last_moving, deep_from)` before and from
/// `deep_from` (shallow, deep).
fn run_strike(
    scene: &Scene,
    options: ProxyOptions,
    strike: &Strike,
    path: &[DVec3],
    (entered, last_moving, deep_from): (usize, usize, usize),
    rate_hz: f64,
    check: &mut StrikeCheck,
) -> [StrikeTicks; 2] {
    let start = strike.start();
    let mut proxy = Proxy::new(start, options);
    let mut ticks = [StrikeTicks::default(); 2];
    let line = strike.line();
    let mut previous = start;
    for (k, &hip) in path.iter().enumerate() {
        let out = proxy.tick(scene, hip, (hip - previous) * rate_hz);
        previous = hip;
        check.ticks += 1;
        check.held_ticks += usize::from(out.status.deep_hold);
        if k < entered || k > last_moving {
            continue;
        }
        let t = &mut ticks[usize::from(k >= deep_from)];
        t.strikes = 1;
        t.ticks += 1;
        let push = out.force.dot(strike.dir);
        t.max_push_n = t.max_push_n.max(push);
        t.pushes_on += usize::from(push > STRIKE_FORCE_TOLERANCE_N);
        t.far_side += usize::from(
            out.contact
                .is_some_and(|c| line.far_side(c.point, c.normal, options.skin())),
        );
        t.no_contact += usize::from(out.contact.is_none());
    }
    ticks
}
