//! Watertight segment–triangle intersection, after Woop, Benthin & Wald, *Watertight
//! Ray/Triangle Intersection* (JCGT 2013), with a tie-break that hands every edge and vertex
//! to exactly one triangle.
//!
//! The method, the tie-break and its limits are documented on
//! [`intersect_segment_triangle`].

use glam::DVec3;

use crate::mesh::TriFrame;

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
    /// The first row of the shear, `e[kx] − (d[kx] / d[kz]) e[kz]` (dimensionless), so
    /// that a corner's sheared `x` is a dot product (no select on the axes, whose branches
    /// a per-segment axis makes unpredictable across queries). Its zero component adds
    /// exact zeros: the same value as `q[kx] − (d[kx] / d[kz]) q[kz]`.
    row_x: DVec3,
    /// The second row, `e[ky] − (d[ky] / d[kz]) e[kz]`.
    row_y: DVec3,
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
        let row = |k: Axis, shear: f64| {
            let mut row = DVec3::ZERO;
            row[k as usize] = 1.0;
            row[kz as usize] = -shear;
            row
        };
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
            row_x: row(kx, shear_x),
            row_y: row(ky, shear_y),
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
        (
            self.row_x.dot(q),
            self.row_y.dot(q),
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
pub fn intersect_segment_triangle(segment: &Segment, corners: [DVec3; 3]) -> Option<SegmentHit> {
    intersect(segment, corners, None)
}

/// The two end points' orientations against a triangle's plane, with their error bounds
/// (`orient3d` of the corners and each end point, positive behind the plane).
type Sides = ((f64, f64), (f64, f64));

/// [`intersect_segment_triangle`] of the segment `p0 → p1` (metres) for a triangle of a
/// surface whose [frame](crate::mesh::TriFrame) is at hand: the same decision (hit or
/// not), the same parameter and the same side, and weights equal up to rounding.
/// `segment` gives the prepared segment of `p0 → p1` when the whole test needs it.
///
/// A segment that crosses the triangle well inside it (each weight above the frame's
/// error bound, a few `1e-5` for a well-shaped triangle) with both end points certainly
/// off its plane is answered from the two plane orientations and the frame's duals,
/// without the shear of the three corners (nor the segment's, which is only prepared when
/// the whole test runs). The answer is the whole test's: the line meets the plane strictly
/// inside the triangle, so every edge function has the sign of the determinant and no
/// tie-break applies; the end points' sides are the same certain signs the whole test
/// takes, so `entering` is `p0` in front; and `t` is computed from the same orientations
/// in the same way (the fast path is only taken when the whole test would not refine
/// them). Any other case takes the whole watertight test, reusing the orientations.
///
/// # Real-time
/// As [`intersect_segment_triangle`].
#[inline]
pub(crate) fn intersect_segment_framed(
    p0: DVec3,
    p1: DVec3,
    corners: [DVec3; 3],
    frame: &TriFrame,
    segment: impl FnOnce() -> Segment,
) -> Option<SegmentHit> {
    let [a, b, c] = corners;
    let sides = (
        super::exact::orient3d_with_bound(a, b, c, p0),
        super::exact::orient3d_with_bound(a, b, c, p1),
    );
    let ((o0, e0), (o1, e1)) = sides;
    let (s0, s1) = (certain_sign(o0, e0), certain_sign(o1, e1));
    if s0 * s1 > 0 {
        // Both end points certainly on one side: the whole test finds them so too.
        return None;
    }
    if s0 * s1 < 0 && e0 + e1 <= PARAMETER_ERROR * (o0.abs() + o1.abs()) {
        let t = o0 / (o0 - o1);
        match frame_weights(p0, p1, frame, t) {
            Certain::Inside(weights) => {
                return Some(SegmentHit {
                    t: t.clamp(0.0, 1.0),
                    weights,
                    entering: s0 < 0,
                });
            }
            Certain::Outside => return None,
            Certain::Neither => {}
        }
    }
    intersect(&segment(), corners, Some(sides))
}

/// Where the line of a segment meets a triangle's plane, as far as the frame's duals
/// tell for certain.
enum Certain {
    /// Strictly inside the triangle, with these weights (each in `(0, 1)`).
    Inside([f64; 3]),
    /// Strictly outside: beyond an edge, or a segment the whole test never hits.
    Outside,
    /// Too near an edge for the frame's precision: the whole test decides.
    Neither,
}

/// The fast path of [`intersect_segment_framed`]: the barycentric weights of the point at
/// `t` on `p0 → p1` from the frame's duals, and whether each certainly exceeds 0 for the
/// exact point where the segment's line meets the plane, or one certainly is negative.
///
/// The point computed at `t` is within `|Δt| |d| + 4u (|p0| + |d|)` (max norms; `u` the
/// unit roundoff) of the exact crossing
/// (`|Δt| ≤ 2⁻³⁹`: the orientations are within `2⁻⁴⁰` of their sum, which is `|o0 − o1|`
/// since they have opposite signs); a dual is within [`FRAME_DIRECTION_ERROR`] of its
/// length (in the L1 norm) of the exact one. The margin bounds the sum of both effects on
/// a weight, with room to spare. A segment that the whole test does not take (a
/// non-finite point, or a direction too short for its reciprocal) is `Outside`.
///
/// [`FRAME_DIRECTION_ERROR`]: super::frame_error::FRAME_DIRECTION_ERROR
#[inline(always)]
fn frame_weights(p0: DVec3, p1: DVec3, frame: &TriFrame, t: f64) -> Certain {
    let d = p1 - p0;
    let x = p0 + t * d;
    let r = x - frame.origin;
    let (wb, wc) = (frame.dual_b.dot(r), frame.dual_c.dot(r));
    let wa = 1.0 - wb - wc;
    let reach = d.abs().max_element();
    let position_error =
        POSITION_ERROR * reach + 8.0 * super::exact::ROUNDOFF * (p0.abs().max_element() + reach);
    let margin = (frame.dual_b.abs().element_sum() + frame.dual_c.abs().element_sum())
        * (super::frame_error::FRAME_DIRECTION_ERROR * r.abs().max_element() + position_error);
    // The NaN of a non-finite point or margin fails every comparison below.
    let usable = (1.0 / reach).is_finite() & p0.is_finite() & p1.is_finite();
    if !usable {
        Certain::Outside
    } else if (wa > margin) & (wb > margin) & (wc > margin) {
        Certain::Inside([wa, wb, wc])
    } else if (wa < -margin) | (wb < -margin) | (wc < -margin) {
        Certain::Outside
    } else {
        Certain::Neither
    }
}

/// Bound on a fast-path crossing point's error from its parameter's, relative to the
/// segment's largest coordinate extent: `2⁻³⁸`, twice the parameter's bound.
const POSITION_ERROR: f64 = 1.0 / (1u64 << 38) as f64;

/// The watertight test; `sides` are the end points' orientations when already computed.
#[inline(always)]
fn intersect(segment: &Segment, [a, b, c]: [DVec3; 3], sides: Option<Sides>) -> Option<SegmentHit> {
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
    let ((o0, e0), (o1, e1)) = sides.unwrap_or_else(|| {
        (
            super::exact::orient3d_with_bound(a, b, c, p0),
            super::exact::orient3d_with_bound(a, b, c, p1),
        )
    });
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
mod tests;
