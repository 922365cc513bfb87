//! The proxy against a brute-force god-object on haptic trajectories.
//!
//! [`BruteProxy`] runs the semantics documented in [`crate::proxy`] with no voxel map and
//! no surface walk: every crossing is found by testing every triangle of every object (each
//! after a slab test against its bounding box, which never changes the answer). The
//! fast [`Proxy`] must stay within [`PROXY_TOLERANCE_M`] of it at every tick.
//!
//! Its deep-penetration hold and its friction are written from the rules' text
//! ([`super::hold`], [`super::friction`]), apart from the proxy's own code; it shares with
//! the proxy the god-object's constraint geometry ([`Constraints`], [`Plane`],
//! [`advance_to_plane`]) and the resting rule.

use glam::DVec3;
use serde::Serialize;

use std::sync::Arc;

use super::friction::friction_step;
use super::hold::{HeldContact, hand_deeper_than, saturation_depth_of};
use super::limits::KEPT_FAILURES;
use super::oracle::TriangleBounds;
use super::oracle::{WindingOracle, distance_to_surface};
use crate::mesh::TriId;
use crate::proxy::{
    Constraints, MAX_PROXY_STEPS, Plane, Proxy, ProxyOptions, Ride, TickOutput, advance_to_plane,
    clamp_to_radius, pushed_from, rests_on, ride_on,
};
use crate::query::{Probe, Side, classify_point, nearest_within_brute_force};
use crate::scene::{Material, Pose, Scene, Shape, Sides, SurfaceRef};

/// Largest distance between the fast proxy and the brute-force one, metres.
pub const PROXY_TOLERANCE_M: f64 = 1e-9;

/// One object as the oracle sees it.
struct BruteObject {
    shape: Arc<Shape>,
    /// Every triangle's box, to skip most triangles of each crossing query.
    boxes: TriangleBounds,
    pose: Pose,
    previous_pose: Pose,
    material: Material,
    one_sided: bool,
    /// The shape before the deformation the last [`BruteProxy::sync`] found, if any.
    before: Option<Arc<Shape>>,
}

/// The god-object by brute force: the oracle for [`Proxy`].
pub struct BruteProxy {
    objects: Vec<BruteObject>,
    options: ProxyOptions,
    position: DVec3,
    in_contact: bool,
    sticking: bool,
    /// Placed and not ticked yet (see [`Proxy::new`]).
    placed: bool,
    /// The last constraint of the previous tick.
    rest: Option<SurfaceRef>,
    /// The contact held beyond the saturation depth.
    hold: Option<HeldContact>,
    /// The device point of the previous tick.
    previous_hip: Option<DVec3>,
    /// The object touched at the end of the previous tick.
    touched: Option<usize>,
}

/// The state of the constraint steps of one tick.
struct Steps {
    position: DVec3,
    planes: Constraints,
    /// Where the proxy first stopped at a surface.
    touch_down: Option<DVec3>,
    /// The surface and plane met first.
    first: Option<(SurfaceRef, Plane)>,
    /// The object and plane met last.
    object: usize,
    plane: Option<Plane>,
    rest: Option<SurfaceRef>,
}

impl Steps {
    /// No plane yet, at `position`.
    fn from(position: DVec3) -> Steps {
        Steps {
            position,
            planes: Constraints::NONE,
            touch_down: None,
            first: None,
            object: 0,
            plane: None,
            rest: None,
        }
    }

    /// Met `h` on `plane` at `p`: the touch-down and the surface met first (if the
    /// first), the object, plane and triangle met last.
    fn met(&mut self, p: DVec3, h: &BruteHit, plane: Plane) {
        let surface = SurfaceRef {
            object: h.object,
            triangle: h.triangle,
        };
        self.touch_down.get_or_insert(p);
        self.first.get_or_insert((surface, plane));
        self.object = h.object;
        self.plane = Some(plane);
        self.rest = Some(surface);
    }
}

/// A crossing found by brute force, world frame.
#[derive(Clone, Copy)]
struct BruteHit {
    t: f64,
    object: usize,
    triangle: TriId,
    point: DVec3,
    normal: DVec3,
    one_sided: bool,
}

impl BruteProxy {
    /// The oracle for a proxy at `position` among the objects of `scene` (their poses and
    /// materials are read again by [`BruteProxy::sync`]).
    pub fn new(scene: &Scene, position: DVec3, options: ProxyOptions) -> BruteProxy {
        let objects = scene
            .objects()
            .iter()
            .map(|o| BruteObject {
                boxes: TriangleBounds::new(o.shape.surface()),
                shape: o.shape.clone(),
                pose: o.pose,
                previous_pose: o.previous_pose,
                material: o.material,
                one_sided: o.sides == Sides::Front,
                before: None,
            })
            .collect();
        BruteProxy {
            objects,
            options,
            position,
            in_contact: false,
            sticking: false,
            placed: true,
            rest: None,
            hold: None,
            previous_hip: None,
            touched: None,
        }
    }

    /// The proxy position, metres, world frame.
    pub fn position(&self) -> DVec3 {
        self.position
    }

    /// Puts the oracle in the state of the fast proxy (after a reported mismatch).
    pub fn resync(&mut self, proxy: &Proxy, in_contact: bool, sticking: bool) {
        self.position = proxy.position();
        self.in_contact = in_contact;
        self.sticking = sticking;
        self.placed = false;
        self.rest = proxy.rest();
        self.hold = proxy.hold().map(|h| HeldContact {
            object: h.on.object,
            normal: h.normal_object,
            entry: h.entry_object,
            hand: h.hip_object,
            direction: h.direction_object,
        });
        self.previous_hip = proxy.previous_hip();
        self.touched = proxy.touched();
    }

    /// Reads the objects' poses and materials from the scene, which must hold the same
    /// objects in the same order (call it after moving objects, before
    /// [`BruteProxy::tick`]).
    pub fn sync(&mut self, scene: &Scene) {
        // Objects given other triangles: the proxy forgets what it touched there.
        let mut forget = Vec::new();
        for (i, (o, s)) in self.objects.iter_mut().zip(scene.objects()).enumerate() {
            if !Arc::ptr_eq(&o.shape, &s.shape) {
                o.before = Some(std::mem::replace(&mut o.shape, s.shape.clone()));
                o.boxes = TriangleBounds::new(o.shape.surface());
                if s.shape.is_remesh() {
                    forget.push(i);
                }
            }
            o.pose = s.pose;
            o.previous_pose = s.previous_pose;
            o.material = s.material;
            o.one_sided = s.sides == Sides::Front;
        }
        for i in forget {
            // As the proxy forgets the triangle under it: friction starts again from
            // where it touches down.
            if self.touched == Some(i) {
                self.touched = None;
                self.in_contact = false;
            }
            if self.rest.is_some_and(|r| r.object == i) {
                self.rest = None;
            }
            if self.hold.as_ref().is_some_and(|h| h.object == i) {
                self.hold = None;
            }
        }
    }

    fn hit(&self, i: usize, from: DVec3, to: DVec3) -> Option<BruteHit> {
        if self.options.tool_radius() > 0.0 {
            return self.tool_hit(i, from, to);
        }
        let o = &self.objects[i];
        let one_sided = o.one_sided;
        let probe = Probe::new(from, to, self.options.probe_reach(), one_sided);
        let c = o.boxes.first_crossing_where(
            o.shape.surface(),
            o.pose.to_object(probe.p0),
            o.pose.to_object(probe.p1),
            |h| h.entering || !one_sided,
        )?;
        Some(BruteHit {
            t: probe.move_t(c.t),
            object: i,
            triangle: c.triangle,
            point: o.pose.to_world(c.point),
            normal: o.pose.vector_to_world(c.face_normal),
            one_sided,
        })
    }

    /// The first contact of the tool's sphere moving `from → to` with object `i`, the move
    /// reaching a probe's reach past `to`: the triangle's point nearest to the centre
    /// there, and the normal from it toward the centre.
    fn tool_hit(&self, i: usize, from: DVec3, to: DVec3) -> Option<BruteHit> {
        let o = &self.objects[i];
        let (radius, reach) = (self.options.tool_radius(), self.options.probe_reach());
        let length = from.distance(to);
        let (end, scale) = if length > 0.0 {
            (
                to + (to - from) * (reach / length),
                (length + reach) / length,
            )
        } else {
            (to, 1.0)
        };
        let c = o.boxes.first_sphere_contact(
            o.shape.surface(),
            (o.pose.to_object(from), o.pose.to_object(end)),
            (radius, reach),
            o.one_sided,
        )?;
        Some(BruteHit {
            t: c.t * scale,
            object: i,
            triangle: c.triangle,
            point: o.pose.to_world(c.point),
            normal: o.pose.vector_to_world(c.normal),
            one_sided: o.one_sided,
        })
    }

    /// The surface within a probe's reach of `p` (of the tool's surface, with a tool
    /// radius), lowest object index first.
    fn touching(&self, p: DVec3) -> Option<BruteHit> {
        let radius = self.options.tool_radius();
        self.objects.iter().enumerate().find_map(|(i, o)| {
            let q = o.pose.to_object(p);
            let near = nearest_within_brute_force(
                o.shape.surface(),
                q,
                radius + self.options.probe_reach(),
            )?;
            let face = o.shape.surface().frame(near.triangle).normal;
            let normal = if radius > 0.0 {
                let n = (q - near.closest.point).try_normalize().unwrap_or(face);
                if o.one_sided && n.dot(face) <= 0.0 {
                    return None;
                }
                n
            } else {
                face
            };
            Some(BruteHit {
                t: 1.0,
                object: i,
                triangle: near.triangle,
                point: o.pose.to_world(near.closest.point),
                normal: o.pose.vector_to_world(normal),
                one_sided: o.one_sided,
            })
        })
    }

    /// The surface the proxy rests on (see [`Proxy`]'s resting rule).
    fn resting(&self, rest: SurfaceRef, p: DVec3, target: DVec3) -> Option<BruteHit> {
        // A tool with a size has no resting rule: its legs are all searched.
        if self.options.tool_radius() > 0.0 {
            return None;
        }
        let o = self.objects.get(rest.object)?;
        let (point, normal) = rests_on(
            o.shape.surface(),
            &o.pose,
            o.one_sided,
            rest.triangle,
            p,
            target,
            self.options.skin,
        )?;
        Some(BruteHit {
            t: 0.0,
            object: rest.object,
            triangle: rest.triangle,
            point,
            normal,
            one_sided: o.one_sided,
        })
    }

    /// The constraint plane of a hit: the triangle's plane, or with a tool radius the
    /// plane tangent to its offset where the tool touched it, moved out by the skin.
    fn plane(&self, h: &BruteHit, from: DVec3, to: DVec3) -> Plane {
        let (radius, skin) = (self.options.tool_radius(), self.options.skin());
        if radius > 0.0 {
            return Plane {
                normal: h.normal,
                offset: h.normal.dot(h.point) + radius + skin,
            };
        }
        Plane::of_hit(h.normal, h.point, h.one_sided, from, to, skin)
    }

    fn first_hit(&self, p0: DVec3, p1: DVec3) -> Option<BruteHit> {
        let mut best: Option<BruteHit> = None;
        for i in 0..self.objects.len() {
            if let Some(h) = self.hit(i, p0, p1)
                && best.is_none_or(|b| h.t < b.t)
            {
                best = Some(h);
            }
        }
        best
    }

    /// The constraint steps toward `goal` from `from.position` with the planes (and the
    /// surface met last) of `from`.
    fn steps(&self, mut p: DVec3, goal: DVec3, mut from: Steps) -> Steps {
        let hip = goal;
        for _ in 0..MAX_PROXY_STEPS {
            let Some(target) = from
                .planes
                .closest_feasible(hip, self.options.plane_tolerance())
            else {
                break;
            };
            if target == p {
                break;
            }
            let resting = match self.rest {
                Some(r) if from.planes.is_empty() => self.resting(r, p, target),
                _ => None,
            };
            let (h, plane) = match resting.or_else(|| self.first_hit(p, target)) {
                Some(h) => {
                    let plane = self.plane(&h, p, target);
                    p = advance_to_plane(p, target, &plane);
                    (h, plane)
                }
                None => match self.touching(target) {
                    Some(h) => {
                        let plane = self.plane(&h, p, target);
                        p = target;
                        (h, plane)
                    }
                    None => {
                        p = target;
                        break;
                    }
                },
            };
            from.met(p, &h, plane);
            if !from.planes.push(plane) {
                break;
            }
        }
        from.position = p;
        from
    }

    /// A tick of a holding proxy at `p` (after the carry): while the device point stays
    /// deeper than the saturation depth behind the held plane, constraint steps toward the
    /// hold's goal, without friction, the held plane becoming the one they meet last on
    /// the held object; `None` (and no change) once it is back within that depth.
    fn hold_step(&mut self, mut p: DVec3, hip: DVec3, mut hold: HeldContact) -> Option<DVec3> {
        let o = self.objects.get(hold.object)?;
        let depth =
            saturation_depth_of(o.shape.hold_material(&o.material), self.options.max_force)?;
        if !hand_deeper_than(p, hip, hold.normal_at(&o.pose), Some(depth)) {
            return None;
        }
        if let Some(aim) = hold.aim(&o.pose, p, hip, depth, self.options.skin) {
            let step = self.steps(p, aim, Steps::from(p));
            p = step.position;
            self.rest = step.rest;
            if let (Some(plane), Some(_)) = (step.plane, step.rest)
                && step.object == hold.object
            {
                hold.normal = self.objects[hold.object]
                    .pose
                    .vector_to_object(plane.normal);
            }
        }
        self.hold = Some(hold);
        self.position = p;
        self.in_contact = true;
        self.touched = Some(hold.object);
        Some(p)
    }

    /// One tick; returns the proxy and whether it touches an object.
    pub fn tick(&mut self, hip: DVec3) -> (DVec3, bool) {
        if !hip.is_finite() {
            self.in_contact = false;
            self.touched = None;
            self.sticking = false;
            self.rest = None;
            self.hold = None;
            self.previous_hip = None;
            return (self.position, false);
        }
        let (hip, _) = clamp_to_radius(hip, self.options.workspace_radius);
        let previous_hip = self.previous_hip.replace(hip);
        let p = self.carried(self.position);
        let p = self.deformed(p);
        // Beyond the saturation depth of the held plane, the proxy moves by constraint
        // steps toward the hold's goal, without friction.
        if let Some(hold) = self.hold.take()
            && let Some(p) = self.hold_step(p, hip, hold)
        {
            return (p, true);
        }
        let held = p;
        let step = self.constrained(p, hip);
        let mut p = step.position;
        self.rest = step.rest;
        let Some(touch_down) = step.touch_down else {
            self.position = p;
            self.in_contact = false;
            self.touched = None;
            self.sticking = false;
            return (p, false);
        };
        // Friction, with the material of the surface met last; the hold's depth from the
        // object's softest.
        let o = &self.objects[step.object];
        let material = step
            .rest
            .filter(|r| r.object == step.object)
            .map_or(o.material, |r| {
                *o.shape.material_on(r.triangle, &o.material)
            });
        let softest = *o.shape.hold_material(&o.material);
        p = self.with_friction(
            p,
            hip,
            &material,
            if self.in_contact { held } else { touch_down },
        );
        if let Some(p) = self.hold_if_deep(p, hip, previous_hip, &step, &softest) {
            return (p, true);
        }
        self.position = p;
        self.in_contact = true;
        self.touched = Some(step.object);
        (p, true)
    }

    /// `p` carried by the objects that moved since the previous tick.
    fn carried(&self, mut p: DVec3) -> DVec3 {
        for (i, o) in self.objects.iter().enumerate() {
            if o.pose == o.previous_pose {
                continue;
            }
            let from = o.pose.to_world(o.previous_pose.to_object(p));
            if let Some(h) = self.hit(i, from, p) {
                p = advance_to_plane(from, p, &self.plane(&h, from, p));
            }
        }
        p
    }

    /// `p` after the objects deformed since the previous tick moved under it (see
    /// `proxy/deform.rs` for the rule): riding the object touched, on the nearest point of
    /// its surface before the deformation (every triangle tested), then pushed out of
    /// every deformed object it lies inside (winding number) or, with a tool radius,
    /// closer than the radius to (every triangle tested).
    fn deformed(&mut self, mut p: DVec3) -> DVec3 {
        let placed = self.placed;
        let before: Vec<Option<Arc<Shape>>> =
            self.objects.iter_mut().map(|o| o.before.take()).collect();
        if placed || before.iter().all(Option::is_none) {
            return p;
        }
        if let Some(i) = self.touched
            && let Some(old) = &before[i]
        {
            let o = &self.objects[i];
            let q = o.previous_pose.to_object(self.position);
            if let Some(near) = nearest_within_brute_force(old.surface(), q, f64::MAX) {
                let ride = Ride::of(i, &o.previous_pose, &near);
                let ridden = ride_on((&o.shape, &o.pose), &ride, self.position);
                if let Some(hold) = self.hold.as_mut()
                    && hold.object == i
                {
                    hold.entry += o.pose.vector_to_object(ridden - p);
                }
                p = ridden;
            }
        }
        let (radius, skin) = (self.options.tool_radius(), self.options.skin());
        for (o, old) in self.objects.iter().zip(&before) {
            if old.is_none() {
                continue;
            }
            let surface = o.shape.surface();
            let q = o.pose.to_object(p);
            let inside =
                o.shape.is_solid() && o.one_sided && WindingOracle::new(surface).winding(q) != 0;
            if !inside && radius <= 0.0 {
                continue;
            }
            let Some(near) = nearest_within_brute_force(surface, q, f64::MAX) else {
                continue;
            };
            if inside || near.distance < radius {
                p = o
                    .pose
                    .to_world(pushed_from(surface, q, &near, inside, radius + skin));
            }
        }
        p
    }

    /// The constraint steps from `p` toward `hip`, starting on the surface touched when
    /// the proxy was just placed there.
    fn constrained(&mut self, p: DVec3, hip: DVec3) -> Steps {
        let mut from = Steps::from(p);
        if std::mem::take(&mut self.placed)
            && let Some(h) = self.touching(p)
        {
            let plane = self.plane(&h, p, hip);
            if plane.height(hip) < 0.0 {
                from.planes.push(plane);
                from.met(p, &h, plane);
            }
        }
        self.steps(p, hip, from)
    }

    /// `p` after the friction step of `material` from `anchor` (where the proxy was held,
    /// or touched down this tick), stopped at the first surface on the way.
    fn with_friction(&mut self, p: DVec3, hip: DVec3, material: &Material, anchor: DVec3) -> DVec3 {
        if material.static_friction <= 0.0 {
            self.sticking = false;
            return p;
        }
        let was = !self.in_contact || self.sticking;
        let (target, sticking) = friction_step(anchor, p, hip, material, was);
        self.sticking = sticking;
        if target == p {
            return p;
        }
        match self.first_hit(p, target) {
            None => target,
            Some(h) => advance_to_plane(p, target, &self.plane(&h, p, target)),
        }
    }

    /// Beyond the saturation depth the proxy holds: from where it first met a surface
    /// this tick when the hand is that deep behind that surface too (the proxy of that
    /// hold step is returned), else from here on the next tick.
    fn hold_if_deep(
        &mut self,
        p: DVec3,
        hip: DVec3,
        previous_hip: Option<DVec3>,
        step: &Steps,
        material: &Material,
    ) -> Option<DVec3> {
        let (Some(plane), Some(_)) = (step.plane, step.rest) else {
            return None;
        };
        let depth = saturation_depth_of(material, self.options.max_force);
        if !hand_deeper_than(p, hip, plane.normal, depth) {
            return None;
        }
        let motion = previous_hip.map(|q| hip - q);
        if let (Some((at, first_plane)), Some(touch_down)) = (step.first, step.touch_down) {
            let hold = HeldContact::new(
                &self.objects[at.object].pose,
                at.object,
                (touch_down, first_plane.normal),
                previous_hip.unwrap_or(hip),
                motion,
            );
            let rest = self.rest.replace(at);
            if let Some(p) = self.hold_step(touch_down, hip, hold) {
                return Some(p);
            }
            self.rest = rest;
        }
        self.hold = Some(HeldContact::new(
            &self.objects[step.object].pose,
            step.object,
            (p, plane.normal),
            hip,
            motion,
        ));
        None
    }
}

/// The proxy against [`BruteProxy`] along a path.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ProxyCheck {
    /// Ticks run.
    pub ticks: usize,
    /// Ticks in contact (fast proxy).
    pub contact_ticks: usize,
    /// Ticks where the fast and brute-force proxies differ by more than
    /// [`PROXY_TOLERANCE_M`] or disagree on contact (the oracle is then reset to the fast
    /// proxy's state).
    pub mismatches: usize,
    /// Largest distance between the two, metres.
    pub max_deviation_m: f64,
    /// Ticks where the proxy is inside a solid object deeper than its skin (inside by the
    /// voxel map, depth by brute force): a break-through.
    pub inside: usize,
    /// Ticks where a force was non-finite or above the maximum.
    pub bad_forces: usize,
    /// Some failing ticks: `(tick, fast proxy, brute-force proxy)`.
    pub failures: Vec<(usize, [f64; 3], [f64; 3])>,
}

impl ProxyCheck {
    /// A check of no ticks.
    pub fn empty() -> ProxyCheck {
        ProxyCheck {
            ticks: 0,
            contact_ticks: 0,
            mismatches: 0,
            max_deviation_m: 0.0,
            inside: 0,
            bad_forces: 0,
            failures: Vec::new(),
        }
    }

    /// The sum of two checks (failures kept up to [`KEPT_FAILURES`], ticks of `other`
    /// numbered after those of `self`).
    pub fn merged(mut self, other: ProxyCheck) -> ProxyCheck {
        let offset = self.ticks;
        self.ticks += other.ticks;
        self.contact_ticks += other.contact_ticks;
        self.mismatches += other.mismatches;
        self.max_deviation_m = self.max_deviation_m.max(other.max_deviation_m);
        self.inside += other.inside;
        self.bad_forces += other.bad_forces;
        for (t, a, b) in other.failures {
            if self.failures.len() < KEPT_FAILURES {
                self.failures.push((t + offset, a, b));
            }
        }
        self
    }
}

/// Runs the fast proxy and the brute-force one along `path` in `scene` (at rest).
pub fn check_proxy(scene: &Scene, path: &[DVec3], options: ProxyOptions) -> ProxyCheck {
    let start = path.first().copied().unwrap_or(DVec3::ZERO);
    let mut pair = ProxyPair::new(scene, start, options);
    let mut check = ProxyCheck {
        ticks: path.len(),
        ..ProxyCheck::empty()
    };
    for (tick, &hip) in path.iter().enumerate() {
        pair.tick(scene, tick, hip, &mut check);
    }
    check
}

/// The fast proxy and its brute-force oracle, ticked side by side.
pub(crate) struct ProxyPair {
    fast: Proxy,
    brute: BruteProxy,
    previous: DVec3,
}

impl ProxyPair {
    /// Both proxies at `start` in `scene`.
    pub(crate) fn new(scene: &Scene, start: DVec3, options: ProxyOptions) -> ProxyPair {
        ProxyPair {
            fast: Proxy::new(start, options),
            brute: BruteProxy::new(scene, start, options),
            previous: start,
        }
    }

    /// One tick of both toward `hip` (tick number `tick`), counted in `check`: a
    /// mismatch resets the oracle to the fast proxy's state.
    pub(crate) fn tick(
        &mut self,
        scene: &Scene,
        tick: usize,
        hip: DVec3,
        check: &mut ProxyCheck,
    ) -> TickOutput {
        let options = *self.fast.options();
        let velocity = (hip - self.previous) * 1e3;
        self.previous = hip;
        let out = self.fast.tick(scene, hip, velocity);
        let (b, b_contact) = self.brute.tick(hip);
        let deviation = out.proxy.distance(b);
        check.max_deviation_m = check.max_deviation_m.max(deviation);
        check.contact_ticks += usize::from(out.contact.is_some());
        if deviation > PROXY_TOLERANCE_M || b_contact != out.contact.is_some() {
            check.mismatches += 1;
            if check.failures.len() < KEPT_FAILURES {
                check
                    .failures
                    .push((tick, out.proxy.to_array(), b.to_array()));
            }
            self.brute
                .resync(&self.fast, out.contact.is_some(), out.status.sticking);
        }
        if !out.force.is_finite() || out.force.length() > options.max_force * (1.0 + 1e-12) {
            check.bad_forces += 1;
        }
        check.inside += breaks_in(scene, out.proxy, &options);
        out
    }

    /// The oracle, to read the scene's objects again ([`BruteProxy::sync`]).
    pub(crate) fn brute(&mut self) -> &mut BruteProxy {
        &mut self.brute
    }
}

/// The objects the proxy at `p` has broken into: a solid it lies inside deeper than its
/// skin (inside by the voxel map, depth by brute force) and, with a tool radius, any
/// object one of whose triangles lies closer than the radius less the skin.
pub(crate) fn breaks_in(scene: &Scene, p: DVec3, options: &ProxyOptions) -> usize {
    let radius = options.tool_radius();
    scene
        .objects()
        .iter()
        .filter(|o| {
            let q = o.pose.to_object(p);
            let surface = o.shape.surface();
            let inside =
                o.shape.is_solid() && classify_point(surface, o.shape.map(), q).0 == Side::Inside;
            let distance = || distance_to_surface(surface, q);
            (inside && distance() > options.skin())
                || (radius > 0.0 && distance() < radius - options.skin())
        })
        .count()
}
