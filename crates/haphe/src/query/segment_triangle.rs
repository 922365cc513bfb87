//! Watertight segment–triangle intersection, after Woop, Benthin & Wald, *Watertight
//! Ray/Triangle Intersection* (JCGT 2013), with a tie-break that hands every edge and vertex
//! to exactly one triangle.
//!
//! The method, the tie-break and its limits are documented on
//! [`intersect_segment_triangle`].

use glam::DVec3;

/// A coordinate axis, used as an index that is known to be in range.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u8)]
enum Axis {
    X = 0,
    Y = 1,
    Z = 2,
}

impl Axis {
    /// The component of `v` along this axis.
    #[inline(always)]
    fn of(self, v: DVec3) -> f64 {
        // A select, not an array index: no store and reload of the vector.
        match self {
            Axis::X => v.x,
            Axis::Y => v.y,
            Axis::Z => v.z,
        }
    }

    /// The next axis in the cycle x → y → z → x.
    fn next(self) -> Axis {
        match self {
            Axis::X => Axis::Y,
            Axis::Y => Axis::Z,
            Axis::Z => Axis::X,
        }
    }
}

/// A segment from `p0` to `p1` (metres, in the frame of the triangles it is tested against,
/// usually the object frame), prepared for watertight tests against many triangles.
///
/// Build it with [`Segment::new`]: besides the end points it holds the axis permutation and
/// the shear of the segment's direction, computed once and reused for every triangle.
/// The end points are public for reading; changing them afterwards (other than translating
/// both by the same vector) leaves the shear describing the old direction.
///
/// A segment of zero length, or with a non-finite end point or direction, never hits
/// anything ([`Segment::is_degenerate`]).
///
/// # Real-time
/// `Copy`, no heap.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Segment {
    /// Start point, metres.
    p0: DVec3,
    /// End point, metres.
    p1: DVec3,
    /// The axis of the largest component of `p1 − p0`.
    kz: Axis,
    /// The first of the two other axes (swapped with `ky` when `(p1 − p0)[kz] < 0`).
    kx: Axis,
    /// The second of the two other axes.
    ky: Axis,
    /// `d[kx] / d[kz]`, dimensionless.
    shear_x: f64,
    /// `d[ky] / d[kz]`, dimensionless.
    shear_y: f64,
    /// `1 / d[kz]`, 1/metres: scales heights along `kz` to the segment parameter.
    shear_z: f64,
    /// False for a zero-length or non-finite segment, which hits nothing.
    usable: bool,
}

impl Segment {
    /// The start point, metres.
    #[inline]
    pub fn p0(&self) -> DVec3 {
        self.p0
    }

    /// The end point, metres.
    #[inline]
    pub fn p1(&self) -> DVec3 {
        self.p1
    }

    /// Prepares the segment from `p0` to `p1` (metres): the axis permutation and shear
    /// constants of its direction `d = p1 − p0`.
    ///
    /// # Real-time
    /// Allocation-free, constant time (three divisions).
    ///
    /// # Examples
    /// ```
    /// use haphe::DVec3;
    /// use haphe::query::{Segment, intersect_segment_triangle};
    /// let down = Segment::new(DVec3::new(0.2, 0.2, 1.0), DVec3::new(0.2, 0.2, -1.0));
    /// let floor = [DVec3::ZERO, DVec3::X, DVec3::Y]; // normal +z
    /// let hit = intersect_segment_triangle(&down, floor).expect("crosses the floor");
    /// assert_eq!(hit.t, 0.5);
    /// assert!(hit.entering);
    /// assert!((hit.weights[0] - 0.6).abs() < 1e-15);
    /// ```
    #[inline]
    pub fn new(p0: DVec3, p1: DVec3) -> Segment {
        let d = p1 - p0;
        let m = d.abs();
        let kz = if m.x >= m.y && m.x >= m.z {
            Axis::X
        } else if m.y >= m.z {
            Axis::Y
        } else {
            Axis::Z
        };
        let dz = kz.of(d);
        let (mut kx, mut ky) = (kz.next(), kz.next().next());
        if dz < 0.0 {
            std::mem::swap(&mut kx, &mut ky);
        }
        let shear_x = kx.of(d) / dz;
        let shear_y = ky.of(d) / dz;
        let shear_z = 1.0 / dz;
        let usable = p0.is_finite()
            && p1.is_finite()
            && dz != 0.0
            && shear_x.is_finite()
            && shear_y.is_finite()
            && shear_z.is_finite();
        Segment {
            p0,
            p1,
            kz,
            kx,
            ky,
            shear_x,
            shear_y,
            shear_z,
            usable,
        }
    }

    /// Whether the segment can hit nothing: zero length, a non-finite end point, or a
    /// direction whose shear does not fit in `f64` (shorter than about `1e-308` m).
    #[inline]
    pub fn is_degenerate(&self) -> bool {
        !self.usable
    }

    /// Corner `p` translated by `−p0` and sheared: `(x, y)` in the plane `⊥ d` and the
    /// unscaled height `p[kz] − p0[kz]`, metres.
    ///
    /// The same corner gives the same bits in every triangle: this is what makes the edge
    /// functions of a shared edge exact negations of each other.
    #[inline(always)]
    fn shear(&self, p: DVec3) -> (f64, f64, f64) {
        let q = p - self.p0;
        let z = self.kz.of(q);
        (
            self.kx.of(q) - self.shear_x * z,
            self.ky.of(q) - self.shear_y * z,
            z,
        )
    }
}

/// Where a segment crosses a triangle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SegmentHit {
    /// Parameter along the segment, `p0 + t (p1 − p0)`, in `[0, 1]` (dimensionless).
    pub t: f64,
    /// Barycentric weights of the crossing point for corners `a, b, c`: each in `[0, 1]`,
    /// summing to 1 up to rounding.
    pub weights: [f64; 3],
    /// The segment goes from the front (the side the normal `(b − a) × (c − a)` points to)
    /// to the back: from outside to inside of a solid.
    pub entering: bool,
}

/// Whether an edge whose 2D edge function is exactly 0 counts as inside a triangle whose
/// determinant has sign `positive`: the sign of the edge function for the query point moved
/// by `(−ε, −ε²)` is `−sign(e.y)`, or `sign(e.x)` when `e.y = 0`, and the edge is inside when
/// that sign is the triangle's. `e = (ex, ey)` is the sheared edge `Q − P` of `E(P → Q)`.
#[inline]
fn owns_zero_edge(ex: f64, ey: f64, positive: bool) -> bool {
    let perturbed_positive = ey < 0.0 || (ey == 0.0 && ex > 0.0);
    let perturbed_negative = ey > 0.0 || (ey == 0.0 && ex < 0.0);
    if positive {
        perturbed_positive
    } else {
        perturbed_negative
    }
}

/// Watertight test of a segment against triangle `[a, b, c]` (metres, the segment's frame,
/// counter-clockwise seen from the front).
///
/// Returns the crossing when the segment's line passes through the triangle (with the
/// tie-break below on edges and vertices) at a parameter `0 ≤ t ≤ 1`. No hit when:
///
/// - the segment is parallel to the triangle's plane (`det = 0`), including a segment lying
///   in the plane;
/// - the segment has zero length or a non-finite end point ([`Segment::is_degenerate`]);
/// - a corner is not finite, or the products overflow, or the triangle seen along the
///   segment is so small that `1 / det` overflows (area below about `1e-308` m²).
///
/// # Method
///
/// [`Segment::new`] picks the axis `kz` of the largest component of `d = p1 − p0` and the two
/// others `kx, ky` (swapped when `d[kz] < 0`, so the winding seen along `d` is kept), and a
/// shear that maps `d` onto the `kz` axis. Per triangle, each corner is translated by `−p0`
/// and sheared into a 2D point `(x, y)` in the plane `⊥ d`; the segment's line is then the
/// origin `O` of that plane. The three 2D edge functions
///
/// ```text
/// E(P → Q) = Q.x·P.y − Q.y·P.x        U = E(b → c),  V = E(c → a),  W = E(a → b)
/// ```
///
/// are the doubled signed areas of the sub-triangles `O, P, Q`, so `U, V, W` are the
/// unnormalised barycentric weights of `O` for the corners `a, b, c`. The line passes
/// through the triangle when they share one sign; their sum is the determinant
/// `det = U + V + W`, positive when the segment runs against the face normal `(b−a)×(c−a)`
/// (it *enters* a solid). The crossing parameter is `t = (U·a_z + V·b_z + W·c_z) / det`
/// with the sheared heights `·_z`.
///
/// # Why it is watertight
///
/// A sheared corner depends only on the corner and the segment, never on the triangle, so
/// two triangles that share an edge see the same two 2D points. `E(Q → P)` is computed as
/// `P.x·Q.y − P.y·Q.x`, which in IEEE arithmetic (round to nearest, no fused multiply–add) is
/// exactly `−E(P → Q)`: the triangles on the two sides of an edge always agree on which side
/// of it the line passes. No epsilon is added anywhere — an epsilon would open gaps or
/// overlaps between neighbours.
///
/// # Tie-break: who owns an edge or vertex
///
/// When the line passes exactly through an edge (an edge function is exactly `0`), Woop's
/// test accepts it for both triangles. Here such an edge counts as *inside* only for the
/// triangle on one designated side of it, chosen by a fixed rule in the sheared 2D frame:
/// **the query point is treated as if moved by an infinitesimal `(−ε, −ε²)`**, i.e. toward
/// `−x`, and toward `−y` when that does not decide (symbolic perturbation, "simulation of
/// simplicity"). For an edge `P → Q` with direction `e = Q − P` whose function is exactly 0,
/// the perturbed function is `E + ε·(−e.y) + ε²·e.x`, whose sign is `−sign(e.y)`, or
/// `sign(e.x)` when `e.y = 0`. Equivalently: with the triangle normalised to run
/// counter-clockwise in the sheared `(x, y)` plane, an edge through the query point is inside
/// when its normalised direction `n` has `n.y > 0 || (n.y == 0 && n.x < 0)` (the top-left
/// rule of rasterisers, mirrored): a point on an edge belongs to the triangle on the edge's
/// `−x` side, and a point on an edge parallel to `x` to the triangle below it.
///
/// Because the perturbed sign is a property of the edge (it flips exactly with `e`, as the
/// edge function does), every triangle classifies the same perturbed point, which lies on
/// no edge. So:
///
/// - an edge shared by two triangles on opposite sides of it (seen along `d`) is owned by
///   exactly one of them;
/// - a vertex surrounded by its fan (seen along `d`) is owned by exactly one triangle of the
///   fan: the one whose corner wedge contains the direction `(−1, −0)`;
/// - where the surface folds over seen along `d` (a segment grazing a ridge, a silhouette
///   edge or vertex), the perturbed point lies either in two overlapping triangles of
///   opposite facing, one `entering` and one leaving, or in none: **0 or 2 hits**, never 1.
///   The signed count (entering − leaving) stays exact, so parity and inside/outside
///   counting stay right.
///
/// A triangle seen edge-on (`det = 0`, the segment parallel to its plane, including segments
/// lying in the plane) has zero area in the projection and is never hit; its neighbours
/// cover the line between them.
///
/// # Limits
///
/// - The edge functions are `f64` products without the higher-precision fallback of the
///   paper, so a line passing within rounding of a vertex may be put in a wedge next to the
///   true one. The signs stay consistent between triangles (they are computed once per
///   edge, antisymmetrically), so a transversal crossing is still reported exactly once.
/// - The test `0 ≤ t ≤ 1` uses each triangle's own plane and rounds. When an end point lies
///   on the surface or within rounding of it, the crossing there may be reported for the
///   segment ending at that point, for the next segment starting there, for both, or for
///   neither. Callers chaining segments (one HIP to the next) must treat one end as open
///   and handle a HIP resting on the surface explicitly.
///
/// # Real-time
/// Allocation-free, constant time: about 30 multiplications, one division (only for a
/// hit), no loop. Never panics.
#[inline]
pub fn intersect_segment_triangle(segment: &Segment, [a, b, c]: [DVec3; 3]) -> Option<SegmentHit> {
    if !segment.usable {
        return None;
    }
    let (ax, ay, az) = segment.shear(a);
    let (bx, by, bz) = segment.shear(b);
    let (cx, cy, cz) = segment.shear(c);

    // E(P → Q) = Q.x·P.y − Q.y·P.x, the same expression for every edge.
    let u = cx * by - cy * bx;
    let v = ax * cy - ay * cx;
    let w = bx * ay - by * ax;

    if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
        return None;
    }
    let det = u + v + w;
    if det == 0.0 || !det.is_finite() {
        // Also rejects NaN edge functions (non-finite input): the sum is then NaN.
        return None;
    }
    let positive = det > 0.0;
    if (u == 0.0 || v == 0.0 || w == 0.0)
        && !((u != 0.0 || owns_zero_edge(cx - bx, cy - by, positive))
            && (v != 0.0 || owns_zero_edge(ax - cx, ay - cy, positive))
            && (w != 0.0 || owns_zero_edge(bx - ax, by - ay, positive)))
    {
        return None;
    }

    // Heights along d, scaled so that the segment runs from 0 to 1.
    let t_scaled = segment.shear_z * (u * az + v * bz + w * cz);
    let (t_num, det_abs) = if positive {
        (t_scaled, det)
    } else {
        (-t_scaled, -det)
    };
    if !(t_num >= 0.0 && t_num <= det_abs) {
        return None;
    }
    let inverse = 1.0 / det;
    if !inverse.is_finite() {
        return None;
    }
    let unit = |x: f64| x.clamp(0.0, 1.0);
    Some(SegmentHit {
        t: unit(t_scaled * inverse),
        weights: [unit(u * inverse), unit(v * inverse), unit(w * inverse)],
        entering: positive,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    const A: DVec3 = DVec3::new(0.0, 0.0, 0.0);
    const B: DVec3 = DVec3::new(1.0, 0.0, 0.0);
    const C: DVec3 = DVec3::new(0.0, 1.0, 0.0);

    fn hit(p0: DVec3, p1: DVec3, tri: [DVec3; 3]) -> Option<SegmentHit> {
        intersect_segment_triangle(&Segment::new(p0, p1), tri)
    }

    #[test]
    fn front_hit_enters_with_weights_and_parameter() {
        let h = hit(
            DVec3::new(0.25, 0.5, 2.0),
            DVec3::new(0.25, 0.5, -2.0),
            [A, B, C],
        )
        .expect("hit");
        assert_eq!(h.t, 0.5);
        assert!(h.entering);
        assert_eq!(h.weights, [0.25, 0.25, 0.5]);
    }

    #[test]
    fn back_hit_leaves() {
        let h = hit(
            DVec3::new(0.25, 0.5, -1.0),
            DVec3::new(0.25, 0.5, 3.0),
            [A, B, C],
        )
        .expect("hit");
        assert_eq!(h.t, 0.25);
        assert!(!h.entering);
        assert_eq!(h.weights, [0.25, 0.25, 0.5]);
    }

    #[test]
    fn every_dominant_axis_and_sign_agrees() {
        // The same crossing, the triangle and segment rotated through the axes and
        // mirrored, must give the same answer with every permutation of the shear.
        let tri = [
            DVec3::new(0.1, -0.3, 0.2),
            DVec3::new(0.9, 0.1, -0.1),
            DVec3::new(-0.2, 0.8, 0.3),
        ];
        let (p0, p1) = (DVec3::new(0.2, 0.2, 1.5), DVec3::new(0.3, 0.1, -1.0));
        let reference = hit(p0, p1, tri).expect("hit");
        let rotate = |v: DVec3, k: usize| match k {
            0 => v,
            1 => DVec3::new(v.z, v.x, v.y),
            _ => DVec3::new(v.y, v.z, v.x),
        };
        for k in 0..3 {
            let t = tri.map(|v| rotate(v, k));
            let h = hit(rotate(p0, k), rotate(p1, k), t).expect("rotated hit");
            assert!((h.t - reference.t).abs() < 1e-14);
            assert_eq!(h.entering, reference.entering);
            let back = hit(rotate(p1, k), rotate(p0, k), t).expect("reversed hit");
            assert!((back.t - (1.0 - reference.t)).abs() < 1e-14);
            assert_eq!(back.entering, !reference.entering);
            for i in 0..3 {
                assert!((h.weights[i] - reference.weights[i]).abs() < 1e-14);
                assert!((back.weights[i] - reference.weights[i]).abs() < 1e-14);
            }
        }
    }

    #[test]
    fn end_points_on_the_plane_give_t_zero_and_one() {
        let start = hit(
            DVec3::new(0.2, 0.2, 0.0),
            DVec3::new(0.2, 0.2, -1.0),
            [A, B, C],
        );
        assert_eq!(start.map(|h| h.t), Some(0.0));
        let end = hit(
            DVec3::new(0.2, 0.2, 1.0),
            DVec3::new(0.2, 0.2, 0.0),
            [A, B, C],
        );
        assert_eq!(end.map(|h| h.t), Some(1.0));
    }

    #[test]
    fn misses_short_segments_and_points_beside_the_triangle() {
        // Stops short of the plane, starts past it, passes beside the triangle.
        assert!(
            hit(
                DVec3::new(0.2, 0.2, 2.0),
                DVec3::new(0.2, 0.2, 0.5),
                [A, B, C]
            )
            .is_none()
        );
        assert!(
            hit(
                DVec3::new(0.2, 0.2, -0.5),
                DVec3::new(0.2, 0.2, -2.0),
                [A, B, C]
            )
            .is_none()
        );
        assert!(
            hit(
                DVec3::new(0.6, 0.6, 1.0),
                DVec3::new(0.6, 0.6, -1.0),
                [A, B, C]
            )
            .is_none()
        );
        assert!(
            hit(
                DVec3::new(-0.1, 0.2, 1.0),
                DVec3::new(-0.1, 0.2, -1.0),
                [A, B, C]
            )
            .is_none()
        );
    }

    #[test]
    fn parallel_and_in_plane_segments_never_hit() {
        assert!(
            hit(
                DVec3::new(-1.0, 0.2, 0.5),
                DVec3::new(2.0, 0.2, 0.5),
                [A, B, C]
            )
            .is_none()
        );
        assert!(
            hit(
                DVec3::new(-1.0, 0.2, 0.0),
                DVec3::new(2.0, 0.2, 0.0),
                [A, B, C]
            )
            .is_none()
        );
        assert!(
            hit(
                DVec3::new(0.1, 0.1, 0.0),
                DVec3::new(0.2, 0.3, 0.0),
                [A, B, C]
            )
            .is_none()
        );
    }

    #[test]
    fn degenerate_and_non_finite_input_never_hits_nor_panics() {
        let p = DVec3::new(0.2, 0.2, 0.0);
        assert!(Segment::new(p, p).is_degenerate());
        assert!(hit(p, p, [A, B, C]).is_none());
        let nan = DVec3::new(f64::NAN, 0.0, 0.0);
        let inf = DVec3::new(0.0, f64::INFINITY, 0.0);
        for bad in [nan, inf, -inf] {
            assert!(hit(bad, DVec3::new(0.2, 0.2, -1.0), [A, B, C]).is_none());
            assert!(hit(DVec3::new(0.2, 0.2, 1.0), bad, [A, B, C]).is_none());
            let down = (DVec3::new(0.2, 0.2, 1.0), DVec3::new(0.2, 0.2, -1.0));
            assert!(hit(down.0, down.1, [bad, B, C]).is_none());
            assert!(hit(down.0, down.1, [A, bad, C]).is_none());
            assert!(hit(down.0, down.1, [A, B, bad]).is_none());
        }
        let huge = 1e300;
        let big = [A * huge, B * huge, C * huge];
        assert!(
            hit(
                DVec3::new(0.2, 0.2, 1.0) * huge,
                DVec3::new(0.2, 0.2, -1.0) * huge,
                big
            )
            .is_none_or(|h| h.t.is_finite() && h.weights.iter().all(|w| w.is_finite()))
        );
        // A degenerate triangle is seen edge-on from every direction: no hit.
        let line = [A, B, 2.0 * B];
        assert!(hit(DVec3::new(0.5, 0.0, 1.0), DVec3::new(0.5, 0.0, -1.0), line).is_none());
    }

    #[test]
    fn a_shared_edge_is_reported_once() {
        // Two triangles of the unit square sharing the diagonal B–C, the segment straight
        // down through its midpoint, and through its end points.
        let d = DVec3::new(1.0, 1.0, 0.0);
        let (first, second) = ([A, B, C], [B, d, C]);
        for x in [DVec3::new(0.5, 0.5, 0.0), B, C] {
            let (p0, p1) = (x + DVec3::Z, x - DVec3::Z);
            let count = [first, second]
                .into_iter()
                .filter(|&t| hit(p0, p1, t).is_some())
                .count();
            assert!(count <= 1, "{x}: {count}");
        }
        let mid = DVec3::new(0.5, 0.5, 0.0);
        let hits = [first, second].map(|t| hit(mid + DVec3::Z, mid - DVec3::Z, t).is_some());
        assert_eq!(hits.iter().filter(|&&h| h).count(), 1);
    }

    #[test]
    fn ties_go_where_the_documented_perturbation_puts_the_point() {
        // Dyadic corners, points and directions whose other components are power-of-two
        // fractions of the largest: every sheared coordinate is exact, so a segment through
        // a vertex or an edge point has edge functions exactly 0 and only the tie-break
        // decides. The owner must be the triangle hit by the same segment moved by
        // (−δ, −δ²) in the sheared frame (a move with no kz component keeps the shear).
        let ring = [
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(0.5, 1.0, 0.25),
            DVec3::new(-0.5, 1.0, 0.0),
            DVec3::new(-1.0, 0.0, -0.25),
            DVec3::new(-0.5, -1.0, 0.125),
            DVec3::new(0.5, -1.0, 0.0),
        ];
        let fan: Vec<[DVec3; 3]> = (0..6).map(|k| [A, ring[k], ring[(k + 1) % 6]]).collect();
        let delta = 1e-7;
        let mut single = 0;
        for through in [A, ring[2] * 0.5, ring[5] * 0.25, (ring[0] + ring[1]) * 0.5] {
            for (i, j, k) in [
                (1, 2, 4),
                (0, 0, 1),
                (-1, 0, 2),
                (0, -2, 1),
                (1, 1, -4),
                (2, -1, -1),
                (4, 1, -2),
                (-1, -1, -1),
                (0, 1, 0),
            ] {
                let d = DVec3::new(f64::from(i), f64::from(j), f64::from(k)) / 8.0;
                let segment = Segment::new(through + d, through - d);
                let mut shift = [0.0; 3];
                shift[segment.kx as usize] = -delta;
                shift[segment.ky as usize] = -delta * delta;
                let shift = DVec3::from_array(shift);
                let moved = Segment::new(segment.p0 + shift, segment.p1 + shift);
                let hits = |s: &Segment| -> Vec<usize> {
                    (0..6)
                        .filter(|&t| intersect_segment_triangle(s, fan[t]).is_some())
                        .collect()
                };
                assert_eq!(hits(&segment), hits(&moved), "through {through} along {d}");
                single += usize::from(hits(&segment).len() == 1);
            }
        }
        assert!(single >= 24, "{single}");
    }

    #[test]
    fn a_vertex_in_a_flat_fan_is_reported_once() {
        // Six triangles around the origin, every segment direction through it.
        let ring: Vec<DVec3> = (0..6)
            .map(|k| {
                let (s, c) = (f64::from(k) * std::f64::consts::FRAC_PI_3).sin_cos();
                DVec3::new(c, s, 0.0)
            })
            .collect();
        let fan: Vec<[DVec3; 3]> = (0..6).map(|k| [A, ring[k], ring[(k + 1) % 6]]).collect();
        for dir in [
            DVec3::Z,
            DVec3::new(0.5, 0.0, 1.0),
            DVec3::new(0.0, -0.25, 1.0),
            DVec3::new(0.3, 0.7, 0.2),
            DVec3::new(-1.0, -1.0, 1.0),
        ] {
            for sign in [1.0, -1.0] {
                let (p0, p1) = (A + sign * dir, A - sign * dir);
                let hits: Vec<SegmentHit> = fan.iter().filter_map(|&t| hit(p0, p1, t)).collect();
                assert_eq!(hits.len(), 1, "{dir} {sign}");
                assert_eq!(hits[0].entering, sign > 0.0);
            }
        }
    }
}
