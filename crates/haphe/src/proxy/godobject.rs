//! The god-object proxy (Zilles & Salisbury): a point that never enters an object, moved
//! each tick toward the device point and stopped and slid by the surfaces it meets.

use glam::DVec3;

use super::constraints::{Constraints, Plane, advance_to_plane};
use super::deep::{Hold, is_deep, saturation_depth};
use super::force::{contact_force, friction_target};
use super::meet::{carry, first_hit_all, hit_plane, move_checked, touching_any};
use super::near::NearCache;
use super::output::{Contact, TickOutput, TickStatus};
use super::rest::{Rest, rest_hit};
use crate::mesh::TriId;
use crate::scene::{Hit, Material, Scene, others_box};

/// How far a probe reaches beyond the ends of a move, as a fraction of the skin: far
/// above the rounding of coordinates (about 1e-16 m per metre), well inside the skin, so a
/// stop at the skin never lands within the reach of the next probe.
pub(crate) const PROBE_REACH_OF_SKIN: f64 = 0.25;

/// Most constraint steps in one tick (each is one segment crossing query). Three planes
/// need at most four; the rest is headroom for re-targeting.
pub const MAX_PROXY_STEPS: usize = 8;

/// Default skin, metres: how far the proxy stays off a touched surface against rounding.
/// A micrometre: far above the rounding of `f64` coordinates of a workspace of a few metres
/// (about 1e-15 m), far below what a hand can feel.
pub const DEFAULT_SKIN: f64 = 1e-6;

/// Settings of a [`Proxy`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProxyOptions {
    /// Distance kept from a touched surface, metres (see [`DEFAULT_SKIN`]).
    pub skin: f64,
    /// Largest force rendered, newtons (the device's maximum continuous force); below
    /// [`MIN_MAX_FORCE`](super::MIN_MAX_FORCE) no force is rendered.
    pub max_force: f64,
    /// Device points farther than this from the world origin are pulled back to it,
    /// metres (at most [`MAX_WORKSPACE_RADIUS`]; a negative or NaN radius pulls every point
    /// to the origin): keeps every product in range whatever the input.
    pub workspace_radius: f64,
}

impl Default for ProxyOptions {
    /// A micrometre of skin, [`DEFAULT_MAX_FORCE_N`](crate::scene::DEFAULT_MAX_FORCE_N)
    /// (a common desktop device), a 1 km workspace.
    fn default() -> ProxyOptions {
        ProxyOptions {
            skin: DEFAULT_SKIN,
            max_force: crate::scene::DEFAULT_MAX_FORCE_N,
            workspace_radius: 1e3,
        }
    }
}

impl ProxyOptions {
    /// Tolerance of the constraint planes, metres: a thousandth of the skin.
    pub fn plane_tolerance(&self) -> f64 {
        self.skin * 1e-3
    }

    /// How far crossing tests reach beyond a move, metres (a quarter of
    /// the skin; see [`Probe`](crate::query::Probe)).
    pub fn probe_reach(&self) -> f64 {
        self.skin * PROBE_REACH_OF_SKIN
    }
}

/// What the proxy remembers from its last contact (coherence: the next walk starts here).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct LastContact {
    pub(super) object: usize,
    pub(super) triangle: TriId,
}

/// The haptic proxy of one point device.
///
/// Each [`tick`](Proxy::tick): objects that moved carry the proxy with them; the proxy then
/// moves toward the device point (the HIP); a path that meets a surface stops a skin's
/// width before it, the surface's plane becomes a constraint, and the proxy slides toward
/// the point closest to the HIP on the free side of up to three planes (face, concave edge,
/// concave corner), testing each leg for crossings; friction may hold it back; the force
/// pulls the device toward it.
///
/// The proxy never crosses a triangle in either direction, so it never passes through a
/// wall however thin or however fast the device moves, and it stays on the side it came
/// from (no direction problem). Crossings are found with the voxel map
/// ([`first_crossing`](crate::query::first_crossing)); the contact point and its shading
/// normal by walking the surface from the last triangle touched.
#[derive(Debug, Clone)]
pub struct Proxy {
    pub(super) position: DVec3,
    pub(super) options: ProxyOptions,
    pub(super) last: Option<LastContact>,
    /// The last constraint of the previous tick (see [`Rest`]).
    pub(super) rest: Option<Rest>,
    pub(super) sticking: bool,
    /// Placed (by [`Proxy::new`] or [`Proxy::reset`]) and not ticked yet.
    pub(super) placed: bool,
    /// The contact held beyond the saturation depth (see [`super::deep`]).
    pub(super) hold: Option<Hold>,
    /// The objects near the proxy, kept from tick to tick (see [`NearCache`]).
    pub(super) near: NearCache,
    /// The device point of the previous tick (the direction a hold starts in).
    pub(super) previous_hip: Option<DVec3>,
    /// The scene and its count of removals when the indices above were kept (see
    /// [`Proxy::follow_removals`]).
    pub(super) removals_seen: Option<(u64, u64)>,
}

impl Proxy {
    /// A proxy at `position` (metres, world frame), normally the device point at start-up.
    /// A proxy that starts inside an object stays inside it (see the servo loop's safe
    /// start).
    pub fn new(position: DVec3, options: ProxyOptions) -> Proxy {
        Proxy {
            position: if position.is_finite() {
                position
            } else {
                DVec3::ZERO
            },
            options,
            last: None,
            rest: None,
            sticking: false,
            placed: true,
            hold: None,
            near: NearCache::new(),
            previous_hip: None,
            removals_seen: None,
        }
    }

    /// The same proxy testing every object of the scene in each search instead of asking
    /// the scene's broad phase: the linear path, the oracle the broad phase is checked
    /// against (same answers, slower for scenes of many objects).
    #[cfg(any(test, feature = "testing"))]
    pub fn with_linear_scan(mut self) -> Proxy {
        self.near = NearCache::linear();
        self
    }

    /// The proxy position, metres, world frame.
    pub fn position(&self) -> DVec3 {
        self.position
    }

    /// The last constraint of the previous tick, which the next tick keeps while the
    /// device point stays behind it (for the oracles).
    #[cfg(any(test, feature = "testing"))]
    pub(crate) fn rest(&self) -> Option<Rest> {
        self.rest
    }

    /// The contact held beyond the saturation depth, if any.
    #[cfg(any(test, feature = "testing"))]
    pub(crate) fn hold(&self) -> Option<Hold> {
        self.hold
    }

    /// The device point of the previous tick (for the oracles).
    #[cfg(any(test, feature = "testing"))]
    pub(crate) fn previous_hip(&self) -> Option<DVec3> {
        self.previous_hip
    }

    /// The settings.
    pub fn options(&self) -> &ProxyOptions {
        &self.options
    }

    /// Puts the proxy at `position` with no contact (for a device that was re-homed).
    pub fn reset(&mut self, position: DVec3) {
        let near = self.near;
        *self = Proxy::new(position, self.options);
        self.near = near;
    }

    /// One servo tick: `hip` is the device point (metres, world frame), `velocity` its
    /// velocity (m/s). Call [`Scene::begin_tick`] once before, so that objects moved since
    /// the previous tick push the proxy.
    ///
    /// # Real-time
    /// No allocation, no lock, no panic for any input; at most one carry query per moved
    /// object, one resting test (one triangle), [`MAX_PROXY_STEPS`] crossing queries and as
    /// many touching searches (plus one on the first tick after [`Proxy::new`] or
    /// [`Proxy::reset`]), one friction query and one walk; before each crossing query one
    /// clear-zone test (and before the first, one triangle test under the proxy that can
    /// stand for the query where the zone shows the surface convex), whose zone is
    /// computed on the triangle's first contact unless
    /// [`Shape::prepare_clear_zones`](crate::scene::Shape::prepare_clear_zones) ran.
    /// A non-finite input leaves the proxy where it was and gives zero force.
    pub fn tick(&mut self, scene: &Scene, hip: DVec3, velocity: DVec3) -> TickOutput {
        let mut status = TickStatus::default();
        if !hip.is_finite() || !velocity.is_finite() {
            status.input_rejected = true;
            self.last = None;
            self.rest = None;
            self.sticking = false;
            self.hold = None;
            self.previous_hip = None;
            return TickOutput {
                proxy: self.position,
                force: DVec3::ZERO,
                contact: None,
                status,
            };
        }
        let (hip, clamped) = clamp_to_radius(hip, self.options.workspace_radius);
        status.input_clamped = clamped;
        let previous_hip = self.previous_hip.replace(hip);
        self.follow_removals(scene);

        let mut p = carry(scene, &mut self.near, self.position, &self.options);
        if let Some(hold) = self.hold.take()
            && let Some(out) = self.hold_tick(scene, p, hip, velocity, hold, status)
        {
            return out;
        }
        let held = p;
        let placed = std::mem::take(&mut self.placed);
        let under = self.last.map(|l| (l.object, l.triangle));
        let sweep = constrain(
            (scene, &mut self.near),
            p,
            hip,
            placed,
            (self.rest, under),
            &self.options,
            &mut status,
        );
        p = sweep.position;
        self.rest = sweep.last_hit.map(|(hit, _)| Rest {
            object: hit.object,
            triangle: hit.triangle,
        });

        let Some((hit, plane)) = sweep.last_hit else {
            self.position = p;
            self.last = None;
            self.sticking = false;
            return TickOutput {
                proxy: p,
                force: DVec3::ZERO,
                contact: None,
                status,
            };
        };
        let object = &scene.objects()[hit.object];
        let material: Material = object.material;

        // Friction: against where the proxy rested, or where it touched down this tick.
        if material.static_friction > 0.0 {
            let (anchor, was_sticking) = match self.last {
                Some(_) => (held, self.sticking),
                None => (sweep.touch_down, true),
            };
            let (target, sticking) = friction_target(anchor, p, hip, &material, was_sticking);
            let (lo, hi) = others_box(p, target, self.options.probe_reach());
            p = if scene.clear_move_among(
                self.near.get(scene, lo, hi),
                hit.object,
                hit.triangle,
                p,
                target,
                self.options.probe_reach(),
            ) {
                status.cleared = true;
                target
            } else {
                move_checked(scene, &mut self.near, p, target, &self.options)
            };
            self.sticking = sticking;
        } else {
            self.sticking = false;
        }
        status.sticking = self.sticking;
        status.in_contact = true;

        let contact = contact_at(
            scene,
            (hit.object, hit.triangle),
            p,
            hip,
            (plane.normal, sweep.planes.len() as u8),
            &mut status,
        );
        let (force, force_clamped) = contact_force(
            p,
            hip,
            velocity,
            contact.map(|c| (c.normal, c.shading_normal, c.constraints)),
            &material,
            self.options.max_force,
        );
        status.force_clamped = force_clamped;
        self.position = p;
        self.last = contact.map(|c| LastContact {
            object: c.object,
            triangle: c.triangle,
        });
        // Beyond the saturation depth the proxy holds: from where it first met the surface
        // this tick, or (where the hand is not that deep behind that surface) from here,
        // on the next tick.
        if is_deep(
            p,
            hip,
            plane.normal,
            saturation_depth(&material, self.options.max_force),
        ) {
            let clamped = status.input_clamped;
            if let Some(out) =
                self.hold_from_touch_down(scene, &sweep, (hip, velocity), previous_hip, clamped)
            {
                return out;
            }
            self.hold = Some(Hold::begin(
                &object.pose,
                (
                    hit.object,
                    contact.map_or(hit.triangle, |c| c.triangle),
                    sweep.planes.len() as u8,
                ),
                (p, plane.normal),
                hip,
                (previous_hip, hip),
            ));
        }
        TickOutput {
            proxy: p,
            force,
            contact,
            status,
        }
    }
}

/// The contact of a proxy at `p` on `object`, found by walking its surface from
/// `triangle`, with the contact plane's unit `normal` (toward the proxy) and the number of
/// active planes; `None` where the walk finds no triangle.
pub(super) fn contact_at(
    scene: &Scene,
    (object, triangle): (usize, TriId),
    p: DVec3,
    hip: DVec3,
    (normal, constraints): (DVec3, u8),
    status: &mut TickStatus,
) -> Option<Contact> {
    let id = scene.objects()[object].id;
    scene.surface_point(object, triangle, p).map(|(s, walk)| {
        status.walk_cap_hit = walk == crate::query::WalkStatus::BoundHit;
        let side = if s.face_normal.dot(normal) >= 0.0 {
            1.0
        } else {
            -1.0
        };
        Contact {
            object,
            id,
            triangle: s.triangle,
            weights: s.weights,
            point: s.point,
            normal,
            shading_normal: side * s.shading_normal,
            penetration: (p - hip).dot(normal).max(0.0),
            constraints,
        }
    })
}

/// Largest workspace radius honoured, metres: a larger (or non-finite)
/// [`ProxyOptions::workspace_radius`] counts as this, so that squared coordinates never
/// overflow.
pub const MAX_WORKSPACE_RADIUS: f64 = 1e9;

/// `p` pulled back onto the sphere of `radius` (metres, at most [`MAX_WORKSPACE_RADIUS`])
/// around the origin when beyond it, and whether it was. Exact for any finite `p`, however
/// large (its length is never squared beyond range); a non-finite `p` is returned as is.
pub fn clamp_to_radius(p: DVec3, radius: f64) -> (DVec3, bool) {
    let radius = if radius >= 0.0 {
        radius.min(MAX_WORKSPACE_RADIUS)
    } else {
        0.0
    };
    let largest = p.abs().max_element();
    if !largest.is_finite() || largest == 0.0 {
        return (p, false);
    }
    // The direction from p scaled to a largest component of 1: no overflow, no underflow.
    let scaled = p / largest;
    let r = scaled.length() * largest;
    if r > radius {
        (scaled.normalize() * radius, true)
    } else {
        (p, false)
    }
}

/// The result of the constraint steps of one tick.
pub(super) struct Sweep {
    pub(super) position: DVec3,
    /// Where the proxy first stopped at a surface this tick.
    pub(super) touch_down: DVec3,
    pub(super) planes: Constraints,
    /// The first surface met this tick (object, triangle); its plane is the first of
    /// `planes`.
    pub(super) first_hit: Option<(usize, TriId)>,
    /// The last surface met, and its plane.
    pub(super) last_hit: Option<(Hit, Plane)>,
}

/// The god-object's constraint steps: aim at the point closest to `hip` on the free side
/// of the active planes, move toward it, and on a crossing stop at the touched triangle's
/// plane (moved out by `skin`) and add it. `rest` is the surface the proxy rested on,
/// `under` the contact triangle of the last tick, under the proxy (object, triangle).
pub(super) fn constrain(
    (scene, near): (&Scene, &mut NearCache),
    mut p: DVec3,
    hip: DVec3,
    placed: bool,
    (rest, under): (Option<Rest>, Option<(usize, TriId)>),
    options: &ProxyOptions,
    status: &mut TickStatus,
) -> Sweep {
    let mut planes = Constraints::NONE;
    let mut last_hit = None;
    let mut touch_down = p;
    // A proxy placed on a surface (within a probe's reach) touches it when the device
    // point lies behind its plane, as if it had come to rest there.
    if placed && let Some(hit) = touching_any(scene, near, p, options.probe_reach()) {
        let plane = hit_plane(&hit, p, hip, options);
        if plane.height(hip) < 0.0 {
            planes.push(plane);
            last_hit = Some((hit, plane));
        }
    }
    let mut first_hit = last_hit.map(|(h, _): (Hit, Plane)| (h.object, h.triangle));
    let mut finished = false;
    for _ in 0..MAX_PROXY_STEPS {
        let Some(target) = planes.closest_feasible(hip, options.plane_tolerance()) else {
            status.wedged = true;
            finished = true;
            break;
        };
        if target == p {
            finished = true;
            break;
        }
        // The first leg of a tick keeps the surface the proxy rests on when the device
        // point is still behind it (no search along that leg: the proxy does not move).
        let resting = match rest {
            Some(r) if planes.is_empty() => {
                rest_hit(scene, r.object, r.triangle, p, target, options.skin)
            }
            _ => None,
        };
        // A leg that stays in the clear zone of the surface last met (or rested on)
        // meets nothing and ends touching nothing: the searches would find nothing.
        let slid_on = last_hit
            .map(|(h, _)| (h.object, h.triangle))
            .or(rest.map(|r| (r.object, r.triangle)));
        let others = others_box(p, target, options.probe_reach());
        if resting.is_none()
            && let Some((object, triangle)) = slid_on
            && scene.clear_move_among(
                near.get(scene, others.0, others.1),
                object,
                triangle,
                p,
                target,
                options.probe_reach(),
            )
        {
            status.cleared = true;
            p = target;
            finished = true;
            break;
        }
        // A first leg into the surface under the proxy, where its neighbourhood is convex,
        // meets that triangle first: shown without the search (the same hit).
        let shown = match under {
            Some((object, triangle)) if planes.is_empty() && resting.is_none() => scene
                .first_hit_shown(
                    near.get(scene, others.0, others.1),
                    object,
                    triangle,
                    p,
                    target,
                    options.probe_reach(),
                ),
            _ => None,
        };
        let (hit, plane) = match resting
            .or(shown)
            .or_else(|| first_hit_all(scene, near, p, target, options.probe_reach()))
        {
            Some(hit) => {
                let plane = hit_plane(&hit, p, target, options);
                p = advance_to_plane(p, target, &plane);
                (hit, plane)
            }
            None => match touching_any(scene, near, target, options.probe_reach()) {
                // A free move that ends on a surface (or within a probe's reach of it,
                // moving along it) touches it: its plane becomes a constraint, so that the
                // proxy never rests where the next probe could start on the surface.
                Some(hit) => {
                    let plane = hit_plane(&hit, p, target, options);
                    p = target;
                    (hit, plane)
                }
                None => {
                    p = target;
                    finished = true;
                    break;
                }
            },
        };
        if last_hit.is_none() {
            touch_down = p;
            first_hit = Some((hit.object, hit.triangle));
        }
        last_hit = Some((hit, plane));
        if !planes.push(plane) {
            finished = true;
            status.step_cap_hit = true;
            break;
        }
    }
    status.step_cap_hit |= !finished;
    Sweep {
        position: p,
        touch_down,
        planes,
        first_hit,
        last_hit,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clamp_to_radius_survives_huge_and_tiny_points() {
        let (p, clamped) = clamp_to_radius(DVec3::new(-0.1, 1e300, 0.2), 1e3);
        assert!(clamped);
        assert_eq!(p.y, 1e3);
        assert!(p.x.abs() < 1e-290 && p.z.abs() < 1e-290);
        let (p, clamped) = clamp_to_radius(DVec3::splat(f64::MAX), 2.0);
        assert!(clamped && (p.length() - 2.0).abs() < 1e-15);
        assert_eq!(
            clamp_to_radius(DVec3::splat(1e-320), 1.0),
            (DVec3::splat(1e-320), false)
        );
        assert_eq!(
            clamp_to_radius(DVec3::new(3.0, 4.0, 0.0), 5.0),
            (DVec3::new(3.0, 4.0, 0.0), false)
        );
        let (p, clamped) = clamp_to_radius(DVec3::new(3.0, 4.0, 0.0), 2.5);
        assert!(clamped && p.distance(DVec3::new(1.5, 2.0, 0.0)) < 1e-15);
        // A radius beyond the cap, or not a number, is the cap (or nothing).
        let (p, _) = clamp_to_radius(DVec3::new(1e12, 0.0, 0.0), f64::INFINITY);
        assert_eq!(p.x, MAX_WORKSPACE_RADIUS);
        assert_eq!(clamp_to_radius(DVec3::X, f64::NAN), (DVec3::ZERO, true));
        assert!(!clamp_to_radius(DVec3::NAN, 1.0).1);
    }
}
