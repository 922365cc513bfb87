//! The surface a proxy rests on: the triangle of the last constraint of the previous tick,
//! which the next tick takes as its first constraint when the device point is still behind
//! it — the god-object's constraint kept from one tick to the next, without a search.

use glam::DVec3;

use super::constraints::Plane;
use crate::mesh::{Surface, TriId};
use crate::scene::{Hit, Pose, Scene, Sides, SurfaceRef};

/// How far beyond its constraint plane (as a fraction of the skin) a resting proxy may
/// lie: the rounding of the projection that put it there, which can land a hair in front.
/// The first leg then moves it onto the plane.
pub(crate) const REST_TOLERANCE_OF_SKIN: f64 = 1e-3;

/// Whether the proxy at `from` (world frame) still rests on `triangle` of the object at
/// `pose` with `surface` when the device point is at `to`: `from` lies on the free side
/// of the triangle's plane (the front for a `one_sided` surface, else the side it is on),
/// no farther from it than its constraint plane (the triangle's plane moved out by `skin`
/// metres) and [`REST_TOLERANCE_OF_SKIN`] of the skin, `to` lies strictly behind the
/// triangle's plane, and the line from `from` to
/// `to` meets that plane inside the triangle. Returns that point and the unit face normal
/// (world frame).
///
/// Then the triangle's constraint plane is the first constraint of the tick, as the move
/// toward the device point would have found it, without a crossing search along that
/// move: the proxy does not move along it (it already lies on or behind the plane, or
/// within that tolerance in front, and then moves onto it), and every move it then makes
/// is tested as usual.
///
/// # Real-time
/// Constant time: one triangle's frame, no allocation, no panic (a triangle out of range,
/// a degenerate one or non-finite input gives `None`). The tick takes the plane too
/// ([`rest_plane`]); the oracle (feature `testing`) and the tests call this.
#[cfg(any(test, feature = "testing"))]
pub(crate) fn rests_on(
    surface: &Surface,
    pose: &Pose,
    one_sided: bool,
    triangle: TriId,
    from: DVec3,
    to: DVec3,
    skin: f64,
) -> Option<(DVec3, DVec3)> {
    rest_plane(surface, pose, one_sided, triangle, from, to, skin)
        .map(|(point, normal, _)| (point, normal))
}

/// [`rests_on`], with the triangle's constraint plane for the move `from → to` (the plane
/// the tick then takes as its first, built once), inlined into the tick's first leg.
#[inline(always)]
fn rest_plane(
    surface: &Surface,
    pose: &Pose,
    one_sided: bool,
    triangle: TriId,
    from: DVec3,
    to: DVec3,
    skin: f64,
) -> Option<(DVec3, DVec3, Plane)> {
    if triangle.index() >= surface.triangle_count() {
        return None;
    }
    let frame = surface.frame(triangle);
    if frame.is_degenerate() {
        return None;
    }
    let (a, b) = (pose.to_object(from), pose.to_object(to));
    let (ha, hb) = (frame.height(a), frame.height(b));
    let side = if one_sided || ha > 0.0 { 1.0 } else { -1.0 };
    let (ha, hb) = (side * ha, side * hb);
    if !(ha > 0.0 && ha <= 2.0 * skin && hb < 0.0) {
        return None;
    }
    let x = a + (ha / (ha - hb)) * (b - a);
    if !frame.barycentric(x).iter().all(|&w| w >= 0.0) {
        return None;
    }
    let (point, normal) = (pose.to_world(x), pose.vector_to_world(frame.normal));
    let plane = Plane::of_hit(normal, point, one_sided, from, to, skin);
    (plane.height(from) <= skin * REST_TOLERANCE_OF_SKIN).then_some((point, normal, plane))
}

/// The triangle `rest` as the surface the proxy at `from` still rests on with the device
/// point at `to` ([`rests_on`] in its object's frame), as a [`Hit`] at the start of the
/// move (`t = 0`), with its constraint plane for that move (the plane
/// [`hit_plane`](super::meet::hit_plane) gives a point). `None` when it is not, or when its
/// object is out of range.
pub(crate) fn rest_hit(
    scene: &Scene,
    rest: SurfaceRef,
    from: DVec3,
    to: DVec3,
    skin: f64,
) -> Option<(Hit, Plane)> {
    let SurfaceRef {
        object: i,
        triangle,
    } = rest;
    let o = scene.objects().get(i)?;
    let one_sided = o.sides == Sides::Front;
    let (point, normal, plane) = rest_plane(
        o.shape.surface(),
        &o.pose,
        one_sided,
        triangle,
        from,
        to,
        skin,
    )?;
    let hit = Hit {
        t: 0.0,
        object: i,
        triangle,
        point,
        normal,
        one_sided,
    };
    Some((hit, plane))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{SurfaceOptions, shapes};

    #[test]
    fn rests_only_on_the_triangle_under_the_line_within_a_skin() {
        // A 0.1 m cube around the origin: its top face is z = 0.05.
        let surface = Surface::new(
            shapes::cuboid(DVec3::splat(0.05), [1, 1, 1]),
            &SurfaceOptions::default(),
        )
        .unwrap();
        let pose = Pose::IDENTITY;
        let skin = 1e-6;
        let top_at = |x: f64, y: f64| {
            (0..surface.triangle_count() as u32)
                .map(TriId)
                .find(|&t| {
                    let f = surface.frame(t);
                    f.normal.z > 0.99
                        && f.barycentric(DVec3::new(x, y, 0.05))
                            .iter()
                            .all(|&w| w > 0.0)
                })
                .unwrap()
        };
        let top = top_at(0.01, 0.0);
        let p = DVec3::new(0.01, 0.0, 0.05 + 0.9 * skin);
        let below = DVec3::new(0.012, 0.001, 0.048);
        let (point, normal) = rests_on(&surface, &pose, true, top, p, below, skin).unwrap();
        assert!((point.z - 0.05).abs() < 1e-15 && normal.z > 0.999);
        // The device point above the face, the proxy too far from it, the line leaving the
        // triangle, or another triangle: no rest.
        let above = DVec3::new(0.012, 0.001, 0.0501);
        assert!(rests_on(&surface, &pose, true, top, p, above, skin).is_none());
        let high = DVec3::new(0.01, 0.0, 0.05 + 3.0 * skin);
        assert!(rests_on(&surface, &pose, true, top, high, below, skin).is_none());
        // Near the edge x = 0.05, toward a device point beyond it: the line meets the
        // top plane past the edge.
        let near_edge = DVec3::new(0.0499, 0.0, 0.05 + 0.9 * skin);
        let beyond = DVec3::new(0.2, 0.0, 0.0499);
        let edge_triangle = top_at(0.0499, 0.0);
        assert!(
            rests_on(
                &surface,
                &pose,
                true,
                edge_triangle,
                near_edge,
                beyond,
                skin
            )
            .is_none()
        );
        // The same device point straight below is behind the face: rest.
        let under = DVec3::new(0.0499, 0.0, 0.0499);
        assert!(rests_on(&surface, &pose, true, edge_triangle, near_edge, under, skin).is_some());
        let other = TriId((top.0 + 3) % surface.triangle_count() as u32);
        assert!(rests_on(&surface, &pose, true, other, p, below, skin).is_none());
        assert!(rests_on(&surface, &pose, true, TriId(1000), p, below, skin).is_none());
        assert!(rests_on(&surface, &pose, true, top, p, DVec3::NAN, skin).is_none());
    }
}
