//! Surfaces that deform under the proxy (see [`Scene::deform`]): the proxy rides the
//! surface it touched, and a surface that moved over it pushes it out.
//!
//! The rule, applied at the start of a tick to the objects deformed since the proxy's
//! previous tick, after the carry of moving objects and before the constraint steps:
//!
//! 0. **Forget.** An object whose shape was replaced by one with other triangles
//!    ([`Shape::replacing`]: material cut away) has none of the triangles the proxy
//!    touched: the proxy forgets them (it does not ride) and stays where it is.
//! 1. **Ride.** A proxy that touched a deformed object at the end of its previous tick
//!    keeps its barycentric point on the surface: the point of the surface before the
//!    deformation nearest to the proxy (the lowest triangle among equally near ones) goes
//!    to the same weights of its triangle's new corners, and the proxy to the same
//!    distance from it as before, along the new normal there (see [`ride_on`]), on the
//!    side it was on.
//! 2. **Push out.** A point proxy then inside a deformed closed solid (felt from the front
//!    only), or a tool whose centre lies closer than its radius to a deformed object's
//!    surface, goes to the nearest surface point, moved out by the skin (plus the radius),
//!    away from the material: outward from a solid, toward the centre's side otherwise.
//!
//! A hold beyond the saturation depth on the ridden object moves its entry with the
//! proxy. The brute-force oracle (`verify/proxy.rs`) follows the same rule.

use glam::DVec3;

use super::godobject::Proxy;
use crate::mesh::{Surface, TriId, VertId};
use crate::query::{NearTriangle, Side, classify_point, nearest_within};
use crate::scene::{Pose, Scene, SceneObject, Shape, Sides, SurfaceRef};

/// The point of a surface nearest to the proxy before a deformation: the triangle, the
/// barycentric weights of the point there, and the point (world frame).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Ride {
    pub on: SurfaceRef,
    pub weights: [f64; 3],
    pub point: DVec3,
}

impl Proxy {
    /// Steps 1 and 2 of the rule above for the proxy at `p` (after the carry): where it
    /// goes. Only when the scene deformed an object since the previous tick.
    ///
    /// # Real-time
    /// No allocation, no lock, no panic; for the ride one nearest-triangle search on the
    /// shape before the deformation, then one broad-phase query, and for each deformed
    /// object near the proxy one inside test and, where it pushes, one nearest-triangle
    /// search.
    #[cold]
    pub(super) fn follow_deformations(&mut self, scene: &Scene, p: DVec3) -> DVec3 {
        let seen = std::mem::replace(&mut self.deformations_seen, scene.deformations());
        self.forget_remeshed(scene, seen);
        let mut p = p;
        if let Some(under) = self.under
            && let Some(o) = scene.objects().get(under.object)
            && o.deformed_at > seen
            && let Some(old) = o.previous_shape.as_deref()
        {
            let q = o.previous_pose.to_object(self.position);
            let close = self.options.tool_radius + 8.0 * self.options.skin;
            if let Some(near) = nearest(old, q, close) {
                let ride = Ride::of(under.object, &o.previous_pose, &near);
                let before = p;
                p = ride_on((&o.shape, &o.pose), &ride, self.position);
                if let Some(hold) = self.hold.as_mut()
                    && hold.on.object == under.object
                {
                    hold.entry_object += o.pose.vector_to_object(p - before);
                }
            }
        }
        let reach = self.options.tool_radius + self.options.skin;
        let m = DVec3::splat(reach);
        let near = scene.near(p - m, p + m);
        for i in near.indices(scene.objects().len()) {
            let o = &scene.objects()[i];
            if o.deformed_at > seen {
                p = push_out(o, p, self.options.tool_radius, self.options.skin);
            }
        }
        p
    }

    /// Forgets the triangles of objects whose shape was replaced by one with other
    /// triangles since the tick that saw `seen` deformations: the one under the proxy, the
    /// one it rested on and a hold on it.
    fn forget_remeshed(&mut self, scene: &Scene, seen: u64) {
        let remeshed = |s: &SurfaceRef| {
            scene
                .objects()
                .get(s.object)
                .is_some_and(|o| o.remeshed_at > seen)
        };
        if self.under.as_ref().is_some_and(remeshed) {
            self.under = None;
        }
        if self.rest.as_ref().is_some_and(remeshed) {
            self.rest = None;
        }
        if self.hold.as_ref().is_some_and(|h| remeshed(&h.on)) {
            self.hold = None;
        }
    }
}

impl Ride {
    /// The ride on object `object` at `pose` from its triangle `near` (object frame).
    pub(crate) fn of(object: usize, pose: &Pose, near: &NearTriangle) -> Ride {
        Ride {
            on: SurfaceRef {
                object,
                triangle: near.triangle,
            },
            weights: near.closest.weights,
            point: pose.to_world(near.closest.point),
        }
    }
}

/// The triangle of `shape` nearest to `q` (object frame), the lowest among equally near
/// ones: searched within `close` metres first, where the proxy usually is and where a
/// few triangles pass the plane test, then as far as the shape reaches.
fn nearest(shape: &Shape, q: DVec3, close: f64) -> Option<NearTriangle> {
    let (surface, map) = (shape.surface(), shape.map());
    nearest_within(surface, map, q, close).or_else(|| {
        let all = 4.0 * shape.bound_radius() + q.distance(shape.bound_centre());
        nearest_within(surface, map, q, all)
    })
}

/// Where a proxy at `position` that touched `ride` at the end of the last tick goes when
/// the surface of `shape` at `pose` deforms (step 1).
pub(crate) fn ride_on((shape, pose): (&Shape, &Pose), ride: &Ride, position: DVec3) -> DVec3 {
    let surface = shape.surface();
    let Some(corners) = (ride.on.triangle.index() < surface.triangle_count())
        .then(|| surface.corners(ride.on.triangle))
    else {
        return position;
    };
    let [w0, w1, w2] = ride.weights;
    let point = pose.to_world(w0 * corners[0] + w1 * corners[1] + w2 * corners[2]);
    let n = pose.vector_to_world(ride_normal(surface, ride.on.triangle, ride.weights));
    let offset = position - ride.point;
    let side = if offset.dot(n) >= 0.0 { 1.0 } else { -1.0 };
    let out = point + side * offset.length() * n;
    if out.is_finite() { out } else { position }
}

/// The direction a ride keeps the proxy's distance along, at the point of weights `w` of
/// triangle `t`: its face normal inside it; on an edge (a weight exactly 0) the mean of
/// the two faces' normals; at a corner (a weight exactly 1) the mean of the normals of
/// the faces around it. So the direction does not hang on which of the triangles at an
/// edge or corner the touching point was found in.
fn ride_normal(surface: &Surface, t: TriId, w: [f64; 3]) -> DVec3 {
    let n_t = surface.frame(t).normal;
    if let Some(i) = w.iter().position(|&x| x == 1.0) {
        let v = VertId(surface.triangle(t)[i]);
        let sum: DVec3 = surface
            .fan(v)
            .iter()
            .map(|&s| surface.frame(TriId(s)).normal)
            .sum();
        return sum.try_normalize().unwrap_or(n_t);
    }
    match w
        .iter()
        .position(|&x| x == 0.0)
        .map(|i| surface.neighbour(t, i))
    {
        Some(Some(across)) => (n_t + surface.frame(across).normal)
            .try_normalize()
            .unwrap_or(n_t),
        _ => n_t,
    }
}

/// Where the proxy at `p` goes when `o`'s surface has moved over it (step 2): `p` itself
/// when it has not.
pub(crate) fn push_out(o: &SceneObject, p: DVec3, tool_radius: f64, skin: f64) -> DVec3 {
    let shape = &o.shape;
    let (surface, map) = (shape.surface(), shape.map());
    let q = o.pose.to_object(p);
    let inside = shape.is_solid()
        && o.sides == Sides::Front
        && classify_point(surface, map, q).0 == Side::Inside;
    if !inside && tool_radius <= 0.0 {
        return p;
    }
    let near = if inside {
        nearest(shape, q, tool_radius + 8.0 * skin)
    } else {
        nearest_within(surface, map, q, tool_radius)
    };
    let Some(near) = near else {
        return p;
    };
    if !inside && near.distance >= tool_radius {
        return p;
    }
    let pushed = o
        .pose
        .to_world(pushed_from(surface, q, &near, inside, tool_radius + skin));
    if pushed.is_finite() { pushed } else { p }
}

/// Where a push from `q` (object frame) to its nearest surface point `near` leaves the
/// proxy: `lift` metres from that point, away from the material (outward when `q` is
/// `inside` a solid, toward `q` otherwise; along the triangle's normal when `q` is on it).
pub(crate) fn pushed_from(
    surface: &Surface,
    q: DVec3,
    near: &NearTriangle,
    inside: bool,
    lift: f64,
) -> DVec3 {
    let at = near.closest.point;
    let away = if inside { at - q } else { q - at };
    let out = away
        .try_normalize()
        .unwrap_or_else(|| surface.frame(near.triangle).normal);
    at + lift * out
}
