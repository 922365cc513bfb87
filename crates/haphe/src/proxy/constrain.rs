//! Step 2 of a tick, the god-object's constraint steps: aim at the point closest to the
//! device point on the free side of the active planes, move toward it, and on meeting a
//! surface stop at its plane (moved out by the skin) and add that plane.

use glam::DVec3;

use super::constraints::{Constraints, Plane, advance_to_plane};
use super::meet::{first_hit_all, hit_plane, touching_any};
use super::near::NearCache;
use super::options::ProxyOptions;
use super::output::TickStatus;
use super::rest::rest_hit;
use crate::scene::{Hit, Scene, SurfaceRef, others_box};

/// Most constraint steps in one tick (each is one segment crossing query). Three planes
/// need at most four; the rest is headroom for re-targeting.
pub const MAX_PROXY_STEPS: usize = 8;

/// What a tick's constraint steps start from, besides the proxy and the device point.
#[derive(Debug, Clone, Copy)]
pub(super) struct Start {
    /// The proxy was just placed ([`Proxy::new`](super::Proxy::new),
    /// [`Proxy::reset`](super::Proxy::reset)): it touches a surface within a probe's reach
    /// when the device point lies behind it.
    pub(super) placed: bool,
    /// The surface the proxy rests on: the last constraint of the previous tick.
    pub(super) rest: Option<SurfaceRef>,
    /// The contact triangle of the previous tick, under the proxy.
    pub(super) under: Option<SurfaceRef>,
}

/// The result of the constraint steps of one tick.
pub(super) struct Sweep {
    pub(super) position: DVec3,
    /// Where the proxy first stopped at a surface this tick.
    pub(super) touch_down: DVec3,
    pub(super) planes: Constraints,
    /// The first surface met this tick; its plane is the first of `planes`.
    pub(super) first_hit: Option<SurfaceRef>,
    /// The last surface met, and its plane.
    pub(super) last_hit: Option<(Hit, Plane)>,
}

impl Sweep {
    /// No surface met yet, the proxy at `p`.
    pub(super) fn at(p: DVec3) -> Sweep {
        Sweep {
            position: p,
            touch_down: p,
            planes: Constraints::NONE,
            first_hit: None,
            last_hit: None,
        }
    }

    /// Met `hit` on `plane`, the proxy now at `position`; `false` when the plane is one
    /// too many.
    fn met(&mut self, hit: Hit, plane: Plane, position: DVec3) -> bool {
        self.position = position;
        if self.last_hit.is_none() {
            self.touch_down = position;
            self.first_hit = Some(hit.surface());
        }
        self.last_hit = Some((hit, plane));
        self.planes.push(plane)
    }
}

/// What one leg of the constraint steps came to.
enum Leg {
    /// The move stands and meets nothing (shown by a clear zone or by the searches): the
    /// proxy reached its target.
    Free {
        /// Shown by the clear zone of the surface last met, without the searches.
        cleared: bool,
    },
    /// The move met (or ended touching) a surface: the sweep took it ([`Sweep::met`]), the
    /// proxy stopped where it met it. `full` when its plane was one too many.
    Met { full: bool },
}

/// The god-object's steps of one tick over `scene` (the objects near the proxy kept in
/// `near`), from the sweep's position (no surface met yet: [`Sweep::at`]) toward `hip`: at
/// most [`MAX_PROXY_STEPS`] legs, each toward the point closest to `hip` on the free side of
/// the planes met so far.
///
/// The caller owns the sweep (the planes and the last hit, a few hundred bytes): filled in
/// place, it is never copied out.
pub(super) fn constrain(
    (scene, near): (&Scene, &mut NearCache),
    sweep: &mut Sweep,
    hip: DVec3,
    start: Start,
    options: &ProxyOptions,
    status: &mut TickStatus,
) {
    if start.placed {
        touch_where_placed(scene, near, sweep, hip, options);
    }
    for _ in 0..MAX_PROXY_STEPS {
        let Some(target) = sweep
            .planes
            .closest_feasible(hip, options.plane_tolerance())
        else {
            status.wedged = true;
            return;
        };
        if target == sweep.position {
            return;
        }
        match leg((scene, &mut *near), sweep, target, start, options) {
            Leg::Free { cleared } => {
                status.cleared |= cleared;
                sweep.position = target;
                return;
            }
            Leg::Met { full: true } => {
                status.step_cap_hit = true;
                return;
            }
            Leg::Met { full: false } => {}
        }
    }
    status.step_cap_hit = true;
}

/// A proxy placed on a surface (within a probe's reach) touches it when the device point
/// lies behind its plane, as if it had come to rest there.
fn touch_where_placed(
    scene: &Scene,
    near: &mut NearCache,
    sweep: &mut Sweep,
    hip: DVec3,
    options: &ProxyOptions,
) {
    let p = sweep.position;
    if let Some(hit) = touching_any(scene, near, p, options) {
        let plane = hit_plane(&hit, p, hip, options);
        if plane.height(hip) < 0.0 {
            sweep.met(hit, plane, p);
        }
    }
}

/// One leg from the sweep's position toward `target`, found by the first of these that
/// answers: the surface the proxy rests on (first leg), the clear zone of the surface last
/// met or rested on, the convex surface under the proxy (first leg), the crossing search,
/// the touching search at `target`. A surface met goes into the sweep in place.
fn leg(
    (scene, near): (&Scene, &mut NearCache),
    sweep: &mut Sweep,
    target: DVec3,
    start: Start,
    options: &ProxyOptions,
) -> Leg {
    let (p, reach) = (sweep.position, options.probe_reach());
    let first_leg = sweep.planes.is_empty();
    // A tool with a size takes every leg through the searches: its resting rule, clear
    // zones and convex surfaces under it are the point's.
    let point = options.tool_radius == 0.0;
    // The first leg of a tick keeps the surface the proxy rests on when the device point
    // is still behind it (no search along that leg: the proxy does not move), with the
    // plane the test built.
    if let Some(r) = start.rest
        && first_leg
        && point
        && let Some((hit, plane)) = rest_hit(scene, r, p, target, options.skin)
    {
        let full = !sweep.met(hit, plane, advance_to_plane(p, target, &plane));
        return Leg::Met { full };
    }
    // A leg that stays in the clear zone of the surface last met (or rested on) meets
    // nothing and ends touching nothing: the searches would find nothing.
    let slid_on = sweep
        .last_hit
        .as_ref()
        .map(|(h, _)| h.surface())
        .or(start.rest);
    let others = || others_box(p, target, reach);
    if point
        && let Some(on) = slid_on
        && scene.clear_move(near.get(scene, others), on, p, target, reach)
    {
        return Leg::Free { cleared: true };
    }
    // A first leg into the surface under the proxy, where its neighbourhood is convex,
    // meets that triangle first: shown without the search (the same hit).
    let shown = match start.under {
        Some(under) if first_leg && point => {
            scene.first_hit_shown(near.get(scene, others), under, p, target, reach)
        }
        _ => None,
    };
    if let Some(hit) = shown {
        return stop_at(sweep, hit, target, options);
    }
    let hint = slid_on.or(start.under);
    if let Some(hit) = first_hit_all(scene, near, (p, target), options, hint) {
        return stop_at(sweep, hit, target, options);
    }
    // A free move that ends on a surface (or within a probe's reach of it, moving along
    // it) touches it: its plane becomes a constraint, so that the proxy never rests where
    // the next probe could start on the surface.
    match touching_any(scene, near, target, options) {
        Some(hit) => {
            let plane = hit_plane(&hit, p, target, options);
            Leg::Met {
                full: !sweep.met(hit, plane, target),
            }
        }
        None => Leg::Free { cleared: false },
    }
}

/// The leg toward `target` met `hit` (a crossing): the proxy stops at its plane, which the
/// sweep takes.
fn stop_at(sweep: &mut Sweep, hit: Hit, target: DVec3, options: &ProxyOptions) -> Leg {
    let p = sweep.position;
    let plane = hit_plane(&hit, p, target, options);
    let full = !sweep.met(hit, plane, advance_to_plane(p, target, &plane));
    Leg::Met { full }
}
