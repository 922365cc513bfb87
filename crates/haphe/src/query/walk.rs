//! The surface walk: from a start triangle to the locally nearest surface point of a
//! target, stepping over the mesh with barycentric coordinates (König & Strothotte).
//!
//! Each step finds the closest point of the current triangle to the target. Its
//! barycentric region names where to look next — the paper's six regions: inside the
//! face, we are done; on an edge, the one triangle across it; at a corner, the triangles
//! around that vertex. The walk moves only to a strictly closer point, so it cannot cycle,
//! and it stops where no neighbouring face, edge or vertex is closer: a local minimum of
//! distance on the surface. On a concave crease the answer stays on the crease edge; in a
//! concave corner, on the vertex; at the boundary of an open mesh, on the boundary.

use glam::DVec3;

use super::frame_error::FRAME_DIRECTION_ERROR;
use super::{ClosestPoint, Feature, closest_point_triangle};
use crate::mesh::{NONE, Surface, TriFrame, TriId, VertId};

/// Most steps a walk takes before it returns its best point with [`WalkStatus::BoundHit`].
/// A coherent haptic tick needs zero or one; a walk across a whole object needs about the
/// number of triangles on the way.
pub const MAX_WALK_STEPS: usize = 256;

/// Most triangles examined around one vertex (fans are usually 4–8 triangles; a cone apex
/// of a scanned mesh can have hundreds). A larger fan is searched only this far, and the
/// walk reports [`WalkStatus::BoundHit`] if it stops there.
pub const MAX_FAN_SCAN: usize = 512;

/// Smallest barycentric weight of a target's projection for [`walk_to_nearest`] to take it
/// as the nearest point without the closest-point kernel: far above the rounding of the
/// weights, so the kernel would find the same face.
const FACE_WEIGHT_MARGIN: f64 = 1e-9;

/// The projection of `target` (at height `h` over the plane of `frame`) when it falls
/// well inside the triangle, every weight above [`FACE_WEIGHT_MARGIN`]: then it is the
/// triangle's nearest point to `target`, on the face, found without the closest-point
/// kernel.
#[inline]
fn projection_inside(frame: &TriFrame, target: DVec3, h: f64) -> Option<ClosestPoint> {
    let weights = frame.barycentric(target);
    weights
        .iter()
        .all(|&w| w > FACE_WEIGHT_MARGIN)
        .then(|| ClosestPoint {
            point: target - h * frame.normal,
            weights,
            feature: Feature::Face,
        })
}

/// A point on the surface with what a haptic renderer needs there (object frame).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfacePoint {
    /// The triangle holding the point.
    pub triangle: TriId,
    /// Barycentric weights of `point` for the triangle's corners (each in `[0, 1]`).
    pub weights: [f64; 3],
    /// The point, metres.
    pub point: DVec3,
    /// Which part of the triangle the point lies on: a face, an edge (a crease or a
    /// boundary when the walk stopped there) or a corner.
    pub feature: Feature,
    /// Unit face normal of the triangle.
    pub face_normal: DVec3,
    /// Unit shading normal interpolated from the corner normals (force shading).
    pub shading_normal: DVec3,
    /// Distance from the target to `point`, metres.
    pub distance: f64,
}

/// How a walk ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WalkStatus {
    /// The point is a local minimum of distance.
    Converged,
    /// A cap ([`MAX_WALK_STEPS`], [`MAX_FAN_SCAN`]) was reached; the point is the best so far.
    BoundHit,
}

/// Walks from `start` to the locally nearest point of the surface to `target` (metres,
/// object frame).
///
/// A degenerate start triangle is replaced by its nearest usable neighbour around its
/// first corner; a surface always has one (see [`Surface::new`]).
///
/// # Real-time
/// No allocation, no lock, no panic for any input (a non-finite target returns the start
/// triangle's first corner with `BoundHit`). At most [`MAX_WALK_STEPS`] steps of at most
/// [`MAX_FAN_SCAN`] closest-point tests each.
pub fn walk_to_nearest(
    surface: &Surface,
    start: TriId,
    target: DVec3,
) -> (SurfacePoint, WalkStatus) {
    let start = if start.index() < surface.triangle_count() {
        start
    } else {
        TriId(0)
    };
    let start = usable_near(surface, start);
    // The coherent case: the target lies over the start triangle, well inside its edges,
    // so its projection on the plane is the nearest point of the triangle, on the face,
    // and a local minimum (no neighbour can be closer than the face under the target).
    let frame = surface.frame(start);
    if target.is_finite()
        && let Some(closest) = projection_inside(frame, target, frame.height(target))
    {
        return (
            surface_point(surface, (start, closest), target),
            WalkStatus::Converged,
        );
    }
    let mut current = (
        start,
        closest_point_triangle(target, surface.corners(start)),
    );
    if !target.is_finite() {
        return (
            surface_point(surface, current, target),
            WalkStatus::BoundHit,
        );
    }
    let mut d2 = current.1.point.distance_squared(target);
    for _ in 0..MAX_WALK_STEPS {
        let (t, closest) = current;
        let tri = surface.triangle(t);
        let mut best: Option<(TriId, ClosestPoint, f64)> = None;
        let mut consider = |s: u32| {
            if s == NONE || s == t.0 {
                return;
            }
            let frame = surface.frame(TriId(s));
            if frame.is_degenerate() {
                return;
            }
            // No point of `s` is nearer than its plane: one whose plane is farther than
            // the best point so far cannot win, and one under which the target lies,
            // well inside its edges, has its nearest point there (as at the start). The
            // slack covers the error of the frame's normal (large on slivers), so a
            // triangle is skipped only when its nearest point is certainly farther.
            let offset = target - frame.origin;
            let h = frame.normal.dot(offset);
            let bound = best.map_or(d2, |(_, _, b2)| b2);
            let slack = FRAME_DIRECTION_ERROR * offset.abs().max_element();
            if h.abs() > slack && (h.abs() - slack) * (h.abs() - slack) > bound {
                return;
            }
            let c = projection_inside(frame, target, h)
                .unwrap_or_else(|| closest_point_triangle(target, surface.corners(TriId(s))));
            let e2 = c.point.distance_squared(target);
            let better = match best {
                None => e2 < d2,
                Some((b, _, b2)) => e2 < b2 || (e2 == b2 && s < b.0),
            };
            if better {
                best = Some((TriId(s), c, e2));
            }
        };
        let mut truncated = false;
        match closest.feature {
            Feature::Face => {
                return (
                    surface_point(surface, current, target),
                    WalkStatus::Converged,
                );
            }
            Feature::Edge(i) => consider(surface.neighbours(t)[i as usize]),
            Feature::Vertex(i) => {
                let fan = surface.fan(VertId(tri[i as usize]));
                truncated = fan.len() > MAX_FAN_SCAN;
                fan.iter().take(MAX_FAN_SCAN).for_each(|&s| consider(s));
            }
        }
        match best {
            Some((s, c, e2)) => {
                current = (s, c);
                d2 = e2;
            }
            None => {
                let status = if truncated {
                    WalkStatus::BoundHit
                } else {
                    WalkStatus::Converged
                };
                return (surface_point(surface, current, target), status);
            }
        }
    }
    (
        surface_point(surface, current, target),
        WalkStatus::BoundHit,
    )
}

/// `t` itself when it has area, else the first triangle with area around its corners.
fn usable_near(surface: &Surface, t: TriId) -> TriId {
    if !surface.frame(t).is_degenerate() {
        return t;
    }
    surface
        .triangle(t)
        .iter()
        .flat_map(|&v| surface.fan(VertId(v)).iter().take(MAX_FAN_SCAN))
        .map(|&s| TriId(s))
        .find(|&s| !surface.frame(s).is_degenerate())
        .unwrap_or(t)
}

fn surface_point(surface: &Surface, (t, c): (TriId, ClosestPoint), target: DVec3) -> SurfacePoint {
    SurfacePoint {
        triangle: t,
        weights: c.weights,
        point: c.point,
        feature: c.feature,
        face_normal: surface.frame(t).normal,
        shading_normal: surface.shading_normal(t, c.weights),
        distance: c.point.distance(target),
    }
}

/// The nearest point of the whole surface to `target`, by testing every triangle: the
/// oracle for [`walk_to_nearest`] on convex meshes. Ties go to the lowest triangle index.
///
/// # Performance
/// `O(n)` in the number of triangles: for tests and verification, never for a tick.
pub fn nearest_point_brute_force(surface: &Surface, target: DVec3) -> SurfacePoint {
    let mut best: Option<(TriId, ClosestPoint, f64)> = None;
    for t in 0..surface.triangle_count() as u32 {
        let t = TriId(t);
        if surface.frame(t).is_degenerate() {
            continue;
        }
        let c = closest_point_triangle(target, surface.corners(t));
        let d2 = c.point.distance_squared(target);
        if best.is_none_or(|(_, _, b2)| d2 < b2) {
            best = Some((t, c, d2));
        }
    }
    let (t, c, _) = best.unwrap_or_else(|| {
        (
            TriId(0),
            closest_point_triangle(target, surface.corners(TriId(0))),
            0.0,
        )
    });
    surface_point(surface, (t, c), target)
}
