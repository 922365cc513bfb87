//! Whether a triangle lies behind another's plane and meets that plane only outside the
//! other's interior, decided exactly: the test behind [`ClearZone::below`](super::ClearZone::below).
//!
//! Two cases. When triangle `T` lies in an axis plane (its three corners share one
//! coordinate, as on boxes, plates and most machined parts), every sign is exact: a
//! corner's side of the plane is the sign of a coordinate difference, and where a triangle
//! touches the plane, Shewchuk's `orient2d` in the two other coordinates tells whether it
//! reaches into `T`. Otherwise the plane is tilted and its heights carry rounding: a
//! triangle counts as behind when every corner it does not share with `T` lies lower than
//! that rounding can explain, so it meets the plane only at the shared corners, on `T`'s
//! boundary.

use glam::DVec3;
use robust::{Coord, orient2d};

use super::frame_error::FRAME_DIRECTION_ERROR;
use crate::mesh::TriFrame;

/// The plane of a triangle whose corners share the coordinate `axis`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct AxisPlane {
    axis: usize,
    at: f64,
    /// `+1` when the triangle's normal points toward `+axis`, else `-1`.
    up: f64,
    /// The triangle's corners in the two other coordinates.
    corners: [Coord<f64>; 3],
    /// The sign of their orientation (never 0).
    turn: f64,
    /// Their bounding box in those coordinates, low and high corners.
    low: Coord<f64>,
    high: Coord<f64>,
}

impl AxisPlane {
    /// The axis plane of the triangle with `corners` and unit `normal`, if it lies in one.
    pub(crate) fn of(corners: [DVec3; 3], normal: DVec3) -> Option<AxisPlane> {
        let axis =
            (0..3).find(|&k| corners[0][k] == corners[1][k] && corners[1][k] == corners[2][k])?;
        let up = if normal[axis] > 0.0 {
            1.0
        } else if normal[axis] < 0.0 {
            -1.0
        } else {
            return None;
        };
        let flat = corners.map(|p| project(p, axis));
        let turn = orient2d(flat[0], flat[1], flat[2]);
        let (xs, ys) = (flat.map(|c| c.x), flat.map(|c| c.y));
        (turn != 0.0).then_some(AxisPlane {
            axis,
            at: corners[0][axis],
            up,
            corners: flat,
            turn: turn.signum(),
            low: Coord {
                x: xs[0].min(xs[1]).min(xs[2]),
                y: ys[0].min(ys[1]).min(ys[2]),
            },
            high: Coord {
                x: xs[0].max(xs[1]).max(xs[2]),
                y: ys[0].max(ys[1]).max(ys[2]),
            },
        })
    }

    /// Positive in front of the plane, zero on it, negative behind (exact; NaN stays NaN).
    fn side(&self, p: DVec3) -> f64 {
        self.up * (p[self.axis] - self.at)
    }

    /// Whether the convex hull of `points` (in the plane, at most three) misses the
    /// triangle's interior: a line through an edge of either separates them (closed on
    /// the side of the points).
    fn misses_interior(&self, points: &[Coord<f64>]) -> bool {
        // Beside the triangle's bounding box (closed): its interior lies strictly inside
        // the box, so comparisons decide most neighbours without an orientation.
        let all = |f: &dyn Fn(&Coord<f64>) -> bool| points.iter().all(f);
        if all(&|p| p.x <= self.low.x)
            || all(&|p| p.x >= self.high.x)
            || all(&|p| p.y <= self.low.y)
            || all(&|p| p.y >= self.high.y)
        {
            return true;
        }
        let t = &self.corners;
        let by_an_edge_of_t = (0..3).any(|i| {
            let (a, b) = (t[i], t[(i + 1) % 3]);
            points.iter().all(|&p| self.turn * orient2d(a, b, p) <= 0.0)
        });
        if by_an_edge_of_t {
            return true;
        }
        match *points {
            [p, q] if p != q => {
                let sides = t.map(|c| orient2d(p, q, c));
                sides.iter().all(|&s| s >= 0.0) || sides.iter().all(|&s| s <= 0.0)
            }
            [p, q, r] => {
                let turn = orient2d(p, q, r);
                turn != 0.0
                    && [(p, q), (q, r), (r, p)]
                        .iter()
                        .any(|&(a, b)| t.iter().all(|&c| turn * orient2d(a, b, c) <= 0.0))
            }
            _ => false,
        }
    }
}

/// The point `p` in the two coordinates other than `axis`.
fn project(p: DVec3, axis: usize) -> Coord<f64> {
    Coord {
        x: p[(axis + 1) % 3],
        y: p[(axis + 2) % 3],
    }
}

/// Whether the triangle with vertex indices `ids`, `corners` and their `heights` over
/// `T`'s plane (as `frame.height` gives them) lies on or behind the plane of triangle `T`
/// (its `frame`, vertex indices `own`, and its axis `plane` when it has one) and meets that
/// plane only outside `T`'s interior. A copy of `T` does not.
pub(crate) fn lies_behind(
    frame: &TriFrame,
    own: [u32; 3],
    plane: Option<&AxisPlane>,
    ids: [u32; 3],
    corners: [DVec3; 3],
    heights: [f64; 3],
) -> bool {
    match plane {
        Some(plane) => {
            let mut on = [Coord { x: 0.0, y: 0.0 }; 3];
            let mut n = 0;
            for p in corners {
                let side = plane.side(p);
                // In front of the plane, or NaN: not behind.
                if side > 0.0 || side.is_nan() {
                    return false;
                }
                if side == 0.0 {
                    on[n] = project(p, plane.axis);
                    n += 1;
                }
            }
            plane.misses_interior(&on[..n])
        }
        None => {
            let shared = ids.iter().filter(|v| own.contains(v)).count();
            shared < 3
                && (0..3).all(|k| {
                    own.contains(&ids[k])
                        || heights[k]
                            < -FRAME_DIRECTION_ERROR
                                * (corners[k] - frame.origin).abs().element_sum()
                })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame_of(c: [DVec3; 3]) -> TriFrame {
        TriFrame::new(c[0], c[1], c[2])
    }

    #[test]
    fn axis_plane_neighbours_beside_below_or_over() {
        // T in the plane z = 0.5, facing +z.
        let t = [
            DVec3::new(0.0, 0.0, 0.5),
            DVec3::new(1.0, 0.0, 0.5),
            DVec3::new(0.0, 1.0, 0.5),
        ];
        let frame = frame_of(t);
        let plane = AxisPlane::of(t, frame.normal).expect("an axis plane");
        let own = [0, 1, 2];
        let behind = |ids: [u32; 3], c: [DVec3; 3]| {
            lies_behind(
                &frame,
                own,
                Some(&plane),
                ids,
                c,
                c.map(|p| frame.height(p)),
            )
        };
        let at = |x: f64, y: f64, z: f64| DVec3::new(x, y, z);
        // Coplanar across the hypotenuse, sharing it: beside.
        assert!(behind([1, 2, 3], [t[1], t[2], at(1.0, 1.0, 0.5)]));
        // Coplanar, folded over T: not.
        assert!(!behind([1, 2, 4], [t[1], t[2], at(0.2, 0.2, 0.5)]));
        // A copy of T: not.
        assert!(!behind(own, t));
        // A side wall down from an edge: behind.
        assert!(behind([0, 1, 5], [t[0], t[1], at(0.5, 0.0, 0.4)]));
        // Rising from an edge: not.
        assert!(!behind([0, 1, 6], [t[0], t[1], at(0.5, -0.1, 0.6)]));
        // Touching the plane at one point inside T from below: not; outside T: behind.
        assert!(!behind(
            [7, 8, 9],
            [at(0.2, 0.2, 0.5), at(0.0, 0.0, 0.0), at(1.0, 0.0, 0.0)]
        ));
        assert!(behind(
            [7, 8, 9],
            [at(2.0, 2.0, 0.5), at(0.0, 0.0, 0.0), at(1.0, 0.0, 0.0)]
        ));
        // A segment on the plane across T, from below: not; along an edge line: behind.
        assert!(!behind(
            [7, 8, 9],
            [at(-1.0, 0.3, 0.5), at(2.0, 0.3, 0.5), at(0.0, 0.0, 0.0)]
        ));
        assert!(behind(
            [7, 8, 9],
            [at(-1.0, 0.0, 0.5), at(-2.0, 0.0, 0.5), at(0.0, 0.0, 0.0)]
        ));
        // Far below: behind. A NaN corner: not.
        assert!(behind(
            [7, 8, 9],
            [at(0.2, 0.2, 0.1), at(0.0, 0.0, 0.0), at(1.0, 0.0, 0.0)]
        ));
        assert!(!behind(
            [7, 8, 9],
            [at(0.2, 0.2, f64::NAN), at(0.0, 0.0, 0.0), at(1.0, 0.0, 0.0)]
        ));
    }

    #[test]
    fn a_tilted_plane_needs_corners_clearly_behind() {
        let t = [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.1),
            DVec3::new(0.0, 1.0, 0.2),
        ];
        let frame = frame_of(t);
        assert!(AxisPlane::of(t, frame.normal).is_none());
        let own = [0, 1, 2];
        let behind = |ids: [u32; 3], c: [DVec3; 3]| {
            lies_behind(&frame, own, None, ids, c, c.map(|p| frame.height(p)))
        };
        let below = t[1] + t[2] - t[0] - 0.05 * frame.normal;
        let on = t[1] + t[2] - t[0];
        assert!(behind([1, 2, 3], [t[1], t[2], below]));
        // In the plane: within rounding, so not shown.
        assert!(!behind([1, 2, 3], [t[1], t[2], on]));
        assert!(!behind(own, t));
    }
}
