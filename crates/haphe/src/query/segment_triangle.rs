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
    /// `d[kz] > 0`.
    forward: bool,
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
        let usable = p0.is_finite()
            && p1.is_finite()
            && dz != 0.0
            && shear_x.is_finite()
            && shear_y.is_finite()
            && (1.0 / dz).is_finite();
        Segment {
            p0,
            p1,
            kz,
            kx,
            ky,
            shear_x,
            shear_y,
            forward: dz > 0.0,
            usable,
        }
    }

    /// Whether the segment can hit nothing: zero length, a non-finite end point, or a
    /// direction whose shear does not fit in `f64` (shorter than about `1e-308` m).
    #[inline]
    pub fn is_degenerate(&self) -> bool {
        !self.usable
    }

    /// Corner `p` translated by `−p0` and sheared: `(x, y)` in the plane `⊥ d`, and the L1
    /// norm of `p − p0` (floored for the error bound), metres.
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
            (q.x.abs() + q.y.abs() + q.z.abs()).max(NORM_FLOOR),
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

/// Relative bound on the rounding error of a sheared edge function: `|E − Ẽ| ≤
/// EDGE_ERROR · m_P · m_Q`, where `m` is the L1 norm of a corner minus `p0`.
///
/// Each sheared coordinate is within `7u (|q_k| + |q_z|)` of its exact value (`u = 2⁻⁵³`:
/// the differences `p − p0` and `p1 − p0`, the shear quotient, its product and the
/// subtraction; `|shear| ≤ 1` because `kz` is the largest component of `d`), so the two
/// products and their difference are within about `33 u m_P m_Q`; the constant is twice
/// that.
const EDGE_ERROR: f64 = 64.0 * super::exact::ROUNDOFF;

/// Smallest corner norm used in the bound (metres): below it the bound would underflow,
/// and a floor this small keeps the bound above every underflow error.
const NORM_FLOOR: f64 = 2.5e-121; // about 2⁻⁴⁰⁰

/// Largest relative error accepted for the two plane orientations `t` is computed from;
/// beyond it they are recomputed in double-double arithmetic.
const PARAMETER_ERROR: f64 = 1.0 / (1u64 << 40) as f64;

/// The sign `−1`, `0` or `1` of `x` when it exceeds the error bound `bound`, `0` otherwise
/// (and for NaN).
#[inline(always)]
fn certain_sign(x: f64, bound: f64) -> i8 {
    if x > bound {
        1
    } else if x < -bound {
        -1
    } else {
        0
    }
}

impl Segment {
    /// The exact sign of the edge function `E(P → Q)` for the segment's line moved by the
    /// infinitesimal `(−ε, −ε²)` of the sheared frame (the tie-break documented on
    /// [`intersect_segment_triangle`]); `0` only for an edge parallel to the segment (or
    /// non-finite input).
    ///
    /// Exactly, `E(P → Q) = −det[P − p0, Q − p0, p1 − p0] / |d[kz]|` (the shear has
    /// determinant 1, and the axis order is cyclic when `d[kz] > 0`, swapped otherwise), so
    /// its sign is that of `−orient3d(P, Q, p1, p0)`; when that is 0 the line and the edge are coplanar and the
    /// perturbation decides: `E + ε·(−e.y) + ε²·e.x` with `e` the sheared `Q − P`, whose
    /// components have the signs of `(Q − P)[k]·d[kz] − d[k]·(Q − P)[kz]` times
    /// `sign(d[kz])`, for `k = ky` and `kx`. Every sign is computed exactly.
    #[cold]
    fn exact_edge_sign(&self, p: DVec3, q: DVec3) -> i8 {
        // Four points with one coordinate in common lie in that axis' plane: the
        // orientation is zero without the adaptive predicate's full expansion (the common
        // case of a motion in the plane of a wall on a part with round coordinates).
        let in_an_axis_plane =
            (0..3).any(|k| p[k] == q[k] && q[k] == self.p0[k] && self.p0[k] == self.p1[k]);
        let orientation = if in_an_axis_plane {
            0
        } else {
            -super::exact::orient3d_sign(p, q, self.p1, self.p0)
        };
        if orientation != 0 {
            return orientation;
        }
        let flip = if self.forward { 1 } else { -1 };
        let (kx, ky, kz) = (self.kx as usize, self.ky as usize, self.kz as usize);
        let points = [q, p, self.p1, self.p0];
        let ey = super::exact::cross_of_differences_sign(points, ky, kz) * flip;
        if ey != 0 {
            return -ey;
        }
        super::exact::cross_of_differences_sign(points, kx, kz) * flip
    }
}

/// Watertight test of a segment against triangle `[a, b, c]` (metres, the segment's frame,
/// counter-clockwise seen from the front).
///
/// Returns the crossing when the segment's line passes through the triangle (with the
/// tie-break below on edges and vertices) at a parameter `0 ≤ t ≤ 1`. No hit when:
///
/// - the segment is parallel to the triangle's plane (exactly), including a segment lying
///   in the plane: such a triangle is *seen edge-on* and is never hit;
/// - the segment has zero length or a non-finite end point ([`Segment::is_degenerate`]);
/// - a corner is not finite, or the products overflow or underflow so far that no
///   parameter can be formed (coordinates beyond about `1e±150`).
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
/// (it *enters* a solid).
///
/// Every **decision** is exact, as if computed in real arithmetic on the `f64` inputs:
///
/// - the sign of each edge function is taken from its `f64` value when that exceeds a
///   bound on its rounding error, and otherwise computed exactly (`orient3d` of the edge
///   and the segment's end points, Shewchuk's adaptive predicate);
/// - whether the crossing lies on the segment is the exact side of `p0` and of `p1` with
///   respect to the triangle's plane (the same filtered `orient3d`).
///
/// The **parameter** is `t = o0 / (o0 − o1)` with `o0, o1` the orientations of `p0, p1`
/// against the triangle's plane, in `f64` when their error bounds allow a relative error
/// below `2⁻⁴⁰`, in double-double otherwise (a segment almost in the triangle's plane,
/// where the crossing point moves far along the segment for a rounding-sized change). The
/// weights come from `U, V, W` (or, when `det` is within rounding of 0, from the crossing
/// point projected on the triangle), clamped to `[0, 1]`.
///
/// # Tie-break: who owns an edge or vertex
///
/// When the line passes exactly through an edge (an edge function is exactly `0`), the
/// segment's line is treated as if moved by an infinitesimal `(−ε, −ε²)` in the sheared
/// frame, i.e. toward `−kx` and, when that does not decide, toward `−ky` (symbolic
/// perturbation, "simulation of simplicity"; a translation by a multiple of world axes
/// `kx, ky`, which the shear leaves unchanged). For an edge `P → Q` whose function is
/// exactly 0 and whose sheared direction is `e = Q − P`, the perturbed function is
/// `E + ε·(−e.y) + ε²·e.x`, whose sign is `−sign(e.y)`, or `sign(e.x)` when `e.y = 0`;
/// those signs are computed exactly too. Equivalently: a point on an edge belongs to the
/// triangle on the edge's `−x` side, and a point on an edge parallel to `x` to the triangle
/// below it (the top-left rule of rasterisers, mirrored). Only an edge parallel to `d` has
/// no perturbed sign; it belongs only to triangles seen edge-on, which are never hit.
///
/// # Why it is watertight, including segments in a face's plane
///
/// Call `L'` the perturbed line. Because every sign above is the exact sign of `L'`
/// against an edge, and the sign of an edge flips exactly with its direction, the answer
/// for every triangle is the answer for `L'`, which is in general position:
///
/// - `L'` meets no edge (its perturbed function is never 0) except edges parallel to
///   `d`, which are not near `L'`; so `L'` meets no vertex and no edge-on triangle (it
///   would have to enter and leave such a triangle through its edges);
/// - so `L'` meets the surface only at interior points of triangles that are not seen
///   edge-on, transversally, and each such point is reported by exactly the one triangle
///   that contains it, when its parameter is in `[0, 1]` (decided exactly).
///
/// Hence, for end points off the surface, the hits are exactly the crossings of the
/// slightly moved segment: a transversal crossing through an edge or a vertex is reported
/// once; where the surface folds over seen along `d` (a ridge, a silhouette), `L'` meets
/// it 0 or 2 times (entering and leaving); and the signed count (entering − leaving) equals
/// the change of winding number between the end points, so a segment from outside to
/// inside a closed surface is never without a hit. This holds in particular when the
/// segment lies in the plane of a face: that face is seen edge-on, and the faces around it
/// that are not catch the crossing — which needs the *exact* signs, because the edges they
/// meet at (the two long edges of a side wall, say) are different edges that only
/// coincide in the projection along `d`, where rounding alone could put `O` outside both.
///
/// # Limits
///
/// - The tests `0 ≤ t ≤ 1` are exact for the triangle's plane, but when an end point lies
///   on the surface the crossing there may be reported for the segment ending at that
///   point, for the next segment starting there, for both, or for neither (the tie-break
///   moves the line sideways, not along itself). Callers chaining segments (one HIP to the
///   next) must treat one end as open and handle a HIP resting on the surface explicitly.
/// - Exactness assumes no product of coordinate differences underflows (differences of
///   zero or above about `1e-150`): true for any mesh in metres or millimetres.
///
/// # Real-time
/// Allocation-free, constant time, no loop over input, never panics. The usual miss costs
/// about 40 floating-point operations; a hit adds two filtered orientations (about 60); a
/// line within rounding of an edge or a vertex, or a segment almost in a face's plane,
/// takes the exact path (a few hundred operations, on the stack).
#[inline]
pub fn intersect_segment_triangle(segment: &Segment, [a, b, c]: [DVec3; 3]) -> Option<SegmentHit> {
    if !segment.usable {
        return None;
    }
    let (ax, ay, ma) = segment.shear(a);
    let (bx, by, mb) = segment.shear(b);
    let (cx, cy, mc) = segment.shear(c);

    // E(P → Q) = Q.x·P.y − Q.y·P.x, the same expression for every edge.
    let u = cx * by - cy * bx;
    let v = ax * cy - ay * cx;
    let w = bx * ay - by * ax;
    let (bu, bv, bw) = (
        EDGE_ERROR * mb * mc,
        EDGE_ERROR * mc * ma,
        EDGE_ERROR * ma * mb,
    );
    let (mut su, mut sv, mut sw) = (
        certain_sign(u, bu),
        certain_sign(v, bv),
        certain_sign(w, bw),
    );
    if (su > 0 || sv > 0 || sw > 0) && (su < 0 || sv < 0 || sw < 0) {
        return None;
    }
    if su == 0 {
        su = segment.exact_edge_sign(b, c);
    }
    if sv == 0 {
        sv = segment.exact_edge_sign(c, a);
    }
    if sw == 0 {
        sw = segment.exact_edge_sign(a, b);
    }
    if su == 0 || su != sv || sv != sw {
        return None;
    }
    let entering = su > 0;

    // On the segment: p0 in front of the plane (or on it) and p1 behind, or the reverse.
    let (p0, p1) = (segment.p0, segment.p1);
    let (o0, e0) = super::exact::orient3d_with_bound(a, b, c, p0);
    let (o1, e1) = super::exact::orient3d_with_bound(a, b, c, p1);
    let mut s0 = certain_sign(o0, e0);
    if s0 == 0 {
        s0 = super::exact::orient3d_sign(a, b, c, p0);
    }
    let mut s1 = certain_sign(o1, e1);
    if s1 == 0 {
        s1 = super::exact::orient3d_sign(a, b, c, p1);
    }
    // orient3d is positive behind the plane.
    let on_segment = if entering {
        s0 <= 0 && s1 >= 0
    } else {
        s0 >= 0 && s1 <= 0
    };
    if !on_segment {
        return None;
    }
    let t = if s0 == 0 {
        0.0
    } else if s1 == 0 {
        1.0
    } else {
        let (o0, o1) = if e0 + e1 <= PARAMETER_ERROR * (o0.abs() + o1.abs()) {
            (o0, o1)
        } else {
            (
                super::exact::orient3d_double_double(a, b, c, p0),
                super::exact::orient3d_double_double(a, b, c, p1),
            )
        };
        o0 / (o0 - o1)
    };
    if !t.is_finite() {
        return None;
    }
    let t = t.clamp(0.0, 1.0);

    let det = u + v + w;
    let unit = |x: f64| x.clamp(0.0, 1.0);
    let weights = if det.abs() > (bu + bv + bw) / PARAMETER_ERROR && det.is_finite() {
        let inverse = 1.0 / det;
        [unit(u * inverse), unit(v * inverse), unit(w * inverse)]
    } else {
        weights_in_plane([a, b, c], p0 + t * (p1 - p0))
    };
    if !weights.iter().all(|w| w.is_finite()) {
        return None;
    }
    Some(SegmentHit {
        t,
        weights,
        entering,
    })
}

/// Barycentric weights of `x` projected on the plane of `[a, b, c]`, clamped to `[0, 1]`
/// and normalised (a point on the triangle up to rounding); equal weights for a triangle
/// without area.
fn weights_in_plane([a, b, c]: [DVec3; 3], x: DVec3) -> [f64; 3] {
    let n = (b - a).cross(c - a);
    let area2 = n.length_squared();
    let raw = [
        n.dot((b - x).cross(c - x)) / area2,
        n.dot((c - x).cross(a - x)) / area2,
        n.dot((a - x).cross(b - x)) / area2,
    ]
    .map(|w| {
        if w.is_finite() {
            w.clamp(0.0, 1.0)
        } else {
            0.0
        }
    });
    let sum = raw[0] + raw[1] + raw[2];
    if sum > 0.0 {
        raw.map(|w| w / sum)
    } else {
        [1.0 / 3.0; 3]
    }
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

    #[test]
    fn the_exact_edge_sign_is_the_sign_of_the_sheared_edge_function() {
        // Generic configurations, every dominant axis and direction: where the f64 edge
        // function is far from 0, the exact path must give its sign.
        let mut random = crate::rng::SplitMix64::new(5);
        let mut checked = 0;
        for _ in 0..2000 {
            let p0 = random.point_in(DVec3::splat(-1.0), DVec3::splat(1.0));
            let p1 = random.point_in(DVec3::splat(-1.0), DVec3::splat(1.0));
            let (p, q) = (
                random.point_in(DVec3::splat(-1.0), DVec3::splat(1.0)),
                random.point_in(DVec3::splat(-1.0), DVec3::splat(1.0)),
            );
            let segment = Segment::new(p0, p1);
            let (px, py, _) = segment.shear(p);
            let (qx, qy, _) = segment.shear(q);
            let e = qx * py - qy * px;
            if e.abs() > 1e-9 {
                assert_eq!(segment.exact_edge_sign(p, q), certain_sign(e, 0.0));
                assert_eq!(segment.exact_edge_sign(q, p), -certain_sign(e, 0.0));
                checked += 1;
            }
        }
        assert!(checked > 1900, "{checked}");
    }
}
