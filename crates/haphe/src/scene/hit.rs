//! What a path met on a scene's objects: a triangle of an object, and the hit with its
//! point and normal.

use glam::DVec3;

use super::pose::Pose;
use crate::mesh::TriId;
use crate::query::{Crossing, Probe};

/// A triangle of one of a scene's objects: the object's index in [`Scene::objects`] and
/// the triangle. What the proxy keeps from tick to tick (the surface it rests on, the
/// contact under it, the contact it holds) and what a hit met.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct SurfaceRef {
    /// Index of the object in the scene.
    pub object: usize,
    /// The triangle, in the object's surface.
    pub triangle: TriId,
}

/// Where a path first meets an object's surface, world frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Hit {
    /// Parameter along the move, `≥ 0`: a crossing within a probe's reach behind the start
    /// counts as 0, one within reach past the end exceeds 1 (see [`Probe`]).
    pub t: f64,
    /// Index of the object in the scene ([`Scene::objects`]).
    pub object: usize,
    /// The triangle met.
    pub triangle: TriId,
    /// The point met, metres, world frame.
    pub point: DVec3,
    /// Unit face normal of the triangle, world frame (out of a solid).
    pub normal: DVec3,
    /// Only the front of the surface is touched (its normal's side is the free side).
    pub one_sided: bool,
}

impl Hit {
    /// The triangle met.
    #[inline]
    pub(crate) fn surface(&self) -> SurfaceRef {
        SurfaceRef {
            object: self.object,
            triangle: self.triangle,
        }
    }

    /// The hit of object `i` at `pose` for `crossing`, found by the probe `probe` (object
    /// frame crossing, world frame hit).
    pub(super) fn of_crossing(i: usize, pose: &Pose, probe: &Probe, crossing: &Crossing) -> Hit {
        Hit {
            t: probe.move_t(crossing.t),
            object: i,
            triangle: crossing.triangle,
            point: pose.to_world(crossing.point),
            normal: pose.vector_to_world(crossing.face_normal),
            one_sided: probe.entering_only,
        }
    }
}
