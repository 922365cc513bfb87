//! What a tool with a size meets on a scene's objects: the first place a sphere swept
//! along a move touches an object, and the surface it touches where it stands (the sphere
//! proxy's counterparts of [`Scene::first_hit`] and [`Scene::touching`]).

use glam::DVec3;

use super::hit::Hit;
use super::object::{BOUND_SLACK, Sides};
use super::world::Scene;
use crate::mesh::TriId;
use crate::query::{ToolNear, distance_to_segment, first_sphere_contact, nearest_to_tool};

impl Scene {
    /// The first place where a sphere of `radius` metres, its centre moving `from → to`
    /// (world frame), touches object `i` at its current pose, the move reaching `reach`
    /// metres past `to` (and a start within `reach` of the object's offset counting as a
    /// contact at `t = 0` when it moves closer). The hit's point is the triangle's point
    /// nearest to the centre there, its normal the unit normal from that point toward the
    /// centre. `None` when it does not, or when `i` is out of range.
    ///
    /// `near` keeps the triangles near the tool from one call to the next: when they hold
    /// every triangle the move could touch, only they are tested; otherwise, for the
    /// object the tool touches (its triangle `hint`, tested first) or whose triangles are
    /// kept, they are gathered again around the move. Neither changes the answer.
    ///
    /// # Real-time
    /// A bounding-sphere test, then the kept triangles or [`first_sphere_contact`] in the
    /// object frame.
    pub(crate) fn first_tool_hit(
        &self,
        i: usize,
        (from, to): (DVec3, DVec3),
        (radius, reach): (f64, f64),
        (hint, near): (Option<TriId>, &mut ToolNear),
    ) -> Option<Hit> {
        let o = self.objects.get(i)?;
        let shape = &*o.shape;
        let length = from.distance(to);
        let (to_probe, scale) = if length > 0.0 && length.is_finite() {
            (
                to + (to - from) * (reach / length),
                (length + reach) / length,
            )
        } else {
            (to, 1.0)
        };
        let centre = o.pose.to_world(shape.bound_centre());
        if distance_to_segment(centre, [from, to_probe])
            > shape.bound_radius() * BOUND_SLACK + radius + reach
        {
            return None;
        }
        let one_sided = o.sides == Sides::Front;
        let (a, b) = (o.pose.to_object(from), o.pose.to_object(to_probe));
        let sphere = (radius, reach, one_sided);
        let surface = shape.surface();
        let kept = near.is_of(surface);
        let mut answer = kept
            .then(|| near.first_contact(surface, (a, b), sphere))
            .flatten();
        if answer.is_none()
            && (kept || hint.is_some())
            && near.worth_gathering(surface, a.midpoint(b), radius)
        {
            // Around the move, half as far again as the tool's radius.
            let distance = 1.5 * radius + reach + a.distance(b) / 2.0;
            near.gather(surface, shape.map(), a.midpoint(b), distance);
            answer = near.first_contact(surface, (a, b), sphere);
        }
        let c = match answer {
            Some(answer) => answer?,
            None => first_sphere_contact(surface, shape.map(), (a, b), sphere, hint)?,
        };
        Some(Hit {
            t: c.t * scale,
            object: i,
            triangle: c.triangle,
            point: o.pose.to_world(c.point),
            normal: o.pose.vector_to_world(c.normal),
            one_sided,
        })
    }

    /// The triangle of object `i` nearest to the centre `p` (world frame) of a sphere of
    /// `radius` metres, when it lies within `radius + reach` of it (in front of it, for a
    /// one-sided surface), as a [`Hit`] at the end of a move (`t = 1`) with the nearest
    /// point and the unit normal from it toward the centre: how the tool notices a surface
    /// it came to rest on. `None` when there is none, or when `i` is out of range.
    ///
    /// # Real-time
    /// A bounding-sphere test, then the triangles kept in `near` when they hold every
    /// triangle that near, else `nearest_to_tool` in the object frame (its cells within
    /// `radius + reach` of the centre).
    pub(crate) fn tool_touching(
        &self,
        i: usize,
        p: DVec3,
        (radius, reach): (f64, f64),
        near: &ToolNear,
    ) -> Option<Hit> {
        let o = self.objects.get(i)?;
        let shape = &*o.shape;
        let grow = radius + reach;
        let centre = o.pose.to_world(shape.bound_centre());
        if p.distance(centre) > shape.bound_radius() * BOUND_SLACK + grow {
            return None;
        }
        let p_object = o.pose.to_object(p);
        let kept = near
            .is_of(shape.surface())
            .then(|| near.nearest(shape.surface(), p_object, grow))
            .flatten();
        let near = match kept {
            Some(answer) => answer?,
            None => nearest_to_tool(shape.surface(), shape.map(), p_object, grow)?,
        };
        let face = shape.surface().frame(near.triangle).normal;
        let normal = (p_object - near.closest.point)
            .try_normalize()
            .unwrap_or(face);
        let one_sided = o.sides == Sides::Front;
        if one_sided && normal.dot(face) <= 0.0 {
            return None;
        }
        Some(Hit {
            t: 1.0,
            object: i,
            triangle: near.triangle,
            point: o.pose.to_world(near.closest.point),
            normal: o.pose.vector_to_world(normal),
            one_sided,
        })
    }
}
