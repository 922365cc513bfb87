//! The god-object proxy (Zilles & Salisbury): a point that never enters an object, moved
//! each tick toward the device point and stopped and slid by the surfaces it meets.

use glam::DVec3;

use super::constrain::{Start, Sweep, constrain};
use super::force::{contact_force, friction_target};
use super::hold::{Hold, is_deep, saturation_depth};
use super::meet::{carry, move_checked};
use super::near::NearCache;
use super::options::ProxyOptions;
use super::output::{Contact, TickOutput, TickStatus};
use crate::scene::{Hit, Material, Param, Relief, Scene, SceneObject, SurfaceRef, others_box};

/// The device on one tick: its point (metres, world frame, pulled into the workspace), its
/// velocity (m/s) and its point on the previous tick.
#[derive(Debug, Clone, Copy)]
pub(super) struct Hand {
    pub(super) hip: DVec3,
    pub(super) velocity: DVec3,
    pub(super) previous: Option<DVec3>,
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
    /// The contact triangle of the previous tick, under the proxy (the next walk starts
    /// there).
    pub(super) under: Option<SurfaceRef>,
    /// The last constraint of the previous tick: the surface the proxy rests on (see
    /// `rest.rs`).
    pub(super) rest: Option<SurfaceRef>,
    pub(super) sticking: bool,
    /// Placed (by [`Proxy::new`] or [`Proxy::reset`]) and not ticked yet.
    pub(super) placed: bool,
    /// The contact held beyond the saturation depth (see [`super::hold`]).
    pub(super) hold: Option<Hold>,
    /// The objects near the proxy, kept from tick to tick (see [`NearCache`]).
    pub(super) near: NearCache,
    /// The device point of the previous tick (the direction a hold starts in).
    pub(super) previous_hip: Option<DVec3>,
    /// The scene and its count of removals when the indices above were kept (see
    /// [`Proxy::follow_removals`]).
    pub(super) removals_seen: Option<(u64, u64)>,
    /// The scene's count of deformations at the previous tick.
    pub(super) deformations_seen: u64,
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
            under: None,
            rest: None,
            sticking: false,
            placed: true,
            hold: None,
            near: NearCache::new(),
            previous_hip: None,
            removals_seen: None,
            deformations_seen: 0,
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
    pub(crate) fn rest(&self) -> Option<SurfaceRef> {
        self.rest
    }

    /// The contact held beyond the saturation depth, if any.
    #[cfg(any(test, feature = "testing"))]
    pub(crate) fn hold(&self) -> Option<Hold> {
        self.hold
    }

    /// The object the proxy touched at the end of the previous tick (for the oracles).
    #[cfg(any(test, feature = "testing"))]
    pub(crate) fn touched(&self) -> Option<usize> {
        self.under.map(|u| u.object)
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
    /// object, one resting test (one triangle), `MAX_PROXY_STEPS` crossing queries and as
    /// many touching searches (plus one on the first tick after [`Proxy::new`] or
    /// [`Proxy::reset`]), one friction query and one walk; before each crossing query one
    /// clear-zone test (and before the first, one triangle test under the proxy that can
    /// stand for the query where the zone shows the surface convex), whose zone is
    /// computed on the triangle's first contact unless
    /// [`Shape::prepare_clear_zones`](crate::scene::Shape::prepare_clear_zones) ran.
    /// A non-finite input leaves the proxy where it was and gives zero force.
    pub fn tick(&mut self, scene: &Scene, hip: DVec3, velocity: DVec3) -> TickOutput {
        let mut status = TickStatus::default();
        let Some(hand) = self.accept(hip, velocity, &mut status) else {
            return self.output(self.position, DVec3::ZERO, None, status);
        };
        self.follow_removals(scene);
        // 1. Carry: objects that moved push the proxy; surfaces that deformed carry it
        // or push it out.
        let mut carried = carry(scene, &mut self.near, self.position, &self.options);
        if scene.deformations() != self.deformations_seen {
            if self.placed {
                // Just placed: a proxy that starts inside an object stays there.
                self.deformations_seen = scene.deformations();
            } else {
                carried = self.follow_deformations(scene, carried);
            }
        }
        // 5. Deep penetration, begun on an earlier tick: while the hand stays that deep,
        // the hold stands for steps 2 to 4.
        let held = self
            .hold
            .take()
            .and_then(|hold| self.hold_tick(scene, carried, &hand, hold, status));
        if let Some(out) = held {
            return out;
        }
        // 2. Constrain: the god-object's steps toward the device point.
        let start = Start {
            placed: std::mem::take(&mut self.placed),
            rest: self.rest,
            under: self.under,
        };
        let mut sweep = Sweep::at(carried);
        constrain(
            (scene, &mut self.near),
            &mut sweep,
            hand.hip,
            start,
            &self.options,
            &mut status,
        );
        self.rest = sweep.last_hit.map(|(hit, _)| hit.surface());
        let Some((hit, plane)) = sweep.last_hit else {
            self.under = None;
            self.sticking = false;
            return self.output(sweep.position, DVec3::ZERO, None, status);
        };
        let object = &scene.objects()[hit.object];
        let (material, held) = (object.material_on(hit.triangle), object.hold_material());
        // 3. Friction.
        let p = self.friction(
            scene,
            (&hit, material),
            (carried, &sweep),
            hand.hip,
            &mut status,
        );
        // 4. Contact and force.
        let on = (hit.surface(), plane.normal, sweep.planes.len() as u8);
        let felt = (object, material);
        let (contact, force) = self.contact_and_force(scene, on, p, &hand, felt, &mut status);
        // 5. Deep penetration: the hold begins. Tested before the output is built, so that
        // the common case builds it once, in place.
        let depth = saturation_depth(held, self.options.max_force);
        if !is_deep(p, hand.hip, plane.normal, depth) {
            return self.output(p, force, contact, status);
        }
        let out = self.output(p, force, contact, status);
        self.hold_if_deep(scene, &sweep, (&hit, plane.normal, held), &hand, out)
    }

    /// The device point pulled into the workspace, with the tick's velocity and the
    /// previous device point; `None` (and the proxy's contact forgotten) for a non-finite
    /// input.
    #[inline]
    fn accept(&mut self, hip: DVec3, velocity: DVec3, status: &mut TickStatus) -> Option<Hand> {
        if !hip.is_finite() || !velocity.is_finite() {
            status.input_rejected = true;
            self.under = None;
            self.rest = None;
            self.sticking = false;
            self.hold = None;
            self.previous_hip = None;
            return None;
        }
        let (hip, clamped) = clamp_to_radius(hip, self.options.workspace_radius);
        status.input_clamped = clamped;
        let previous = self.previous_hip.replace(hip);
        Some(Hand {
            hip,
            velocity,
            previous,
        })
    }

    /// The tick's output with the proxy at `p` (where it stays).
    #[inline]
    pub(super) fn output(
        &mut self,
        p: DVec3,
        force: DVec3,
        contact: Option<Contact>,
        status: TickStatus,
    ) -> TickOutput {
        self.position = p;
        TickOutput {
            proxy: p,
            force,
            contact,
            status,
        }
    }

    /// Step 3: with friction on the material of `hit`, the proxy at `p` stays where it
    /// rested (`held`, after the carry) or touched down this tick while the tangential
    /// force is inside the static cone, else slips to the edge of the dynamic cone (a move
    /// tested for crossings too).
    #[inline]
    fn friction(
        &mut self,
        scene: &Scene,
        (hit, material): (&Hit, &Material),
        (held, sweep): (DVec3, &Sweep),
        hip: DVec3,
        status: &mut TickStatus,
    ) -> DVec3 {
        let mut p = sweep.position;
        if material.static_friction > 0.0 {
            let (anchor, was_sticking) = match self.under {
                Some(_) => (held, self.sticking),
                None => (sweep.touch_down, true),
            };
            let (target, sticking) = friction_target(anchor, p, hip, material, was_sticking);
            let reach = self.options.probe_reach();
            let near = self.near.get(scene, || others_box(p, target, reach));
            let point = self.options.tool_radius == 0.0;
            p = if point && scene.clear_move(near, hit.surface(), p, target, reach) {
                status.cleared = true;
                target
            } else {
                let hint = Some(hit.surface());
                move_checked(scene, &mut self.near, (p, target), &self.options, hint)
            };
            self.sticking = sticking;
        } else {
            self.sticking = false;
        }
        status.sticking = self.sticking;
        status.in_contact = true;
        p
    }

    /// Step 4: the contact of the proxy at `p` on the surface `on` of `object` (with the
    /// contact plane's unit normal and the number of active planes), found by walking from
    /// there, and the force toward the proxy of `material` (the surface's), shaded,
    /// textured and clamped.
    #[inline]
    fn contact_and_force(
        &mut self,
        scene: &Scene,
        on: (SurfaceRef, DVec3, u8),
        p: DVec3,
        hand: &Hand,
        (object, material): (&SceneObject, &Material),
        status: &mut TickStatus,
    ) -> (Option<Contact>, DVec3) {
        let (surface, normal, planes) = on;
        let contact = contact_at(scene, surface, p, hand.hip, (normal, planes), status);
        // The texture under the contact, if the object has one.
        let relief = match (&object.texture, &contact) {
            (Some(_), Some(c)) => object.relief((c.triangle, c.weights), c.point, c.normal),
            _ => Relief::FLAT,
        };
        let (force, force_clamped) = contact_force(
            p,
            hand.hip,
            hand.velocity,
            contact.map(|c| (c.normal, c.shading_normal, c.constraints)),
            (material, &relief),
            self.options.max_force,
        );
        status.force_clamped = force_clamped;
        self.under = contact.map(|c| c.surface());
        (contact, force)
    }

    /// Step 5: beyond the saturation depth the proxy holds: from where it first met the
    /// surface this tick (this tick is then the hold's first, replacing `out`), or, where
    /// the hand is not that deep behind that surface, from here on the next tick.
    #[inline]
    fn hold_if_deep(
        &mut self,
        scene: &Scene,
        sweep: &Sweep,
        (hit, normal, material): (&Hit, DVec3, &Material),
        hand: &Hand,
        out: TickOutput,
    ) -> TickOutput {
        let depth = saturation_depth(material, self.options.max_force);
        if !is_deep(out.proxy, hand.hip, normal, depth) {
            return out;
        }
        let clamped = out.status.input_clamped;
        if let Some(held) = self.hold_from_touch_down(scene, sweep, hand, clamped) {
            return held;
        }
        let on = SurfaceRef {
            object: hit.object,
            triangle: out.contact.map_or(hit.triangle, |c| c.triangle),
        };
        let pose = &scene.objects()[hit.object].pose;
        let planes = sweep.planes.len() as u8;
        let motion = (hand.previous, hand.hip);
        self.hold = Some(Hold::begin(
            pose,
            (on, planes),
            (out.proxy, normal),
            hand.hip,
            motion,
        ));
        out
    }
}

/// The contact of a proxy at `p` on `object`, found by walking its surface from
/// `triangle`, with the contact plane's unit `normal` (toward the proxy) and the number of
/// active planes; `None` where the walk finds no triangle. Always inlined, so that the
/// contact is built in the tick's output rather than copied into it.
#[inline(always)]
pub(super) fn contact_at(
    scene: &Scene,
    on: SurfaceRef,
    p: DVec3,
    hip: DVec3,
    (normal, constraints): (DVec3, u8),
    status: &mut TickStatus,
) -> Option<Contact> {
    let object = on.object;
    let (id, version) = {
        let o = &scene.objects()[object];
        (o.id, o.shape.version())
    };
    scene.surface_point(on, p).map(|(s, walk)| {
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
            version,
        }
    })
}

/// Largest workspace radius honoured, metres: a larger (or non-finite)
/// [`ProxyOptions::workspace_radius`] counts as this, so that squared coordinates never
/// overflow.
pub const MAX_WORKSPACE_RADIUS: f64 = Param::WorkspaceRadius.domain().high;

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
    // Twice the largest component is more than the length computed below (at most √3
    // times it, rounding included): well inside, no division and no square root. Tested
    // first: false for a largest component that is not finite.
    if 2.0 * largest <= radius || !largest.is_finite() || largest == 0.0 {
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

impl Proxy {
    /// Follows the objects the proxy keeps by index (its last contact, the surface it
    /// rests on, the contact it holds) across the removals since the previous tick: an
    /// index that moved (the last object takes a removed one's place) is updated, and what
    /// was kept of a removed object is forgotten, so that it never stands for another
    /// object. A proxy moved to another scene forgets them all.
    ///
    /// # Real-time
    /// No allocation; at most `REMOVALS_KEPT` (`scene/removals.rs`) steps per
    /// index (a proxy that missed more forgets them).
    pub(super) fn follow_removals(&mut self, scene: &Scene) {
        let log = scene.removals();
        let now = (scene.broad_epoch().0, log.count());
        if self.removals_seen == Some(now) {
            // No removal since the previous tick (the common case): nothing to write.
            return;
        }
        let Some(seen) = self.removals_seen.replace(now) else {
            return;
        };
        if seen == now {
            return;
        }
        let follow = |i: usize| (seen.0 == now.0).then(|| log.follow(seen.1, i)).flatten();
        let follow_ref = |s: SurfaceRef| {
            follow(s.object).map(|object| SurfaceRef {
                object,
                triangle: s.triangle,
            })
        };
        self.under = self.under.and_then(follow_ref);
        self.rest = self.rest.and_then(follow_ref);
        self.hold = self.hold.and_then(|mut h| {
            h.on = follow_ref(h.on)?;
            Some(h)
        });
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
