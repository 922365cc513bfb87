//! Closest point on a triangle, with the feature (face, edge or vertex) it lies on.
//!
//! The classification into the seven Voronoi regions of the triangle follows Ericson,
//! *Real-Time Collision Detection*, §5.1.5: the vertex regions from two dot products each,
//! the edge regions from the signs of the 2×2 determinants `va, vb, vc`, the face last.
//! Two changes make it safe on any input:
//!
//! - **Degenerate triangles** (collinear or coincident corners, and any triangle whose
//!   smallest altitude is at most [`DEGENERATE_MAX_RELATIVE_HEIGHT`] times its longest edge,
//!   the mesh stage's definition) are treated as the union of their three edges: the
//!   closest point is the nearest of the three clamped edge projections, with finite
//!   weights. Ericson's edge formulas would divide `0 / 0` on a zero-length edge, and his
//!   face formula by a vanishing area.
//! - **The face case** returns the projection `p − n (n·ap) / n·n` along the face normal
//!   `n = ab × ac`, accurate to rounding whatever the triangle's shape, and computes the
//!   weights from the normal too, `v = n·(ap × ac) / n·n` and `w = n·(ab × ap) / n·n`: their
//!   rounding error grows like `1 / relative height`, instead of its square for Ericson's
//!   `vb / (va + vb + vc)`, so even slivers at the degeneracy limit keep weights to about
//!   `1e-7`.
//!
//! [`DEGENERATE_MAX_RELATIVE_HEIGHT`]: crate::mesh::DEGENERATE_MAX_RELATIVE_HEIGHT

use glam::DVec3;

use crate::mesh::DEGENERATE_MAX_RELATIVE_HEIGHT;

/// Which part of a triangle a closest point lies on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Feature {
    /// The interior of the face.
    Face,
    /// The edge opposite corner `i` (0, 1 or 2), excluding its end points.
    Edge(u8),
    /// Corner `i` (0, 1 or 2).
    Vertex(u8),
}

/// The closest point of a triangle to a query point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClosestPoint {
    /// The point, metres, in the triangle's frame.
    pub point: DVec3,
    /// Barycentric weights of `point` for corners `a, b, c` (each in `[0, 1]`, summing to 1
    /// up to rounding). For [`Feature::Edge(i)`](Feature::Edge) weight `i` is exactly 0; for
    /// [`Feature::Vertex(i)`](Feature::Vertex) weight `i` is exactly 1 and the others 0.
    pub weights: [f64; 3],
    /// The feature the point lies on.
    pub feature: Feature,
}

/// The point of triangle `[a, b, c]` closest to `p` (all metres, one frame, usually the
/// object frame), the feature it lies on and its barycentric weights.
///
/// For a non-degenerate triangle the point is the exact closest point up to rounding; the
/// weights rebuild it up to about `1e-16 / relative height` times the triangle's size, and
/// a point near an edge of a sliver may be put on that edge within that error.
///
/// A degenerate triangle — collinear or coincident corners, or thinner than
/// [`DEGENERATE_MAX_RELATIVE_HEIGHT`](crate::mesh::DEGENERATE_MAX_RELATIVE_HEIGHT) — is
/// taken as its three edges: the point is the closest point on the segment (or the point)
/// the corners span, with [`Feature::Edge`] or [`Feature::Vertex`] and finite weights. For a
/// sliver at that limit this is off from the true face point by at most its smallest
/// altitude.
///
/// The closest point is unique (a triangle is convex), but for a degenerate triangle whose
/// edges overlap it may lie on several of them; which one is named is then unspecified.
///
/// Finite input gives finite output as long as squared distances stay finite (coordinates
/// below about `1e150` m). Non-finite input gives a meaningless, possibly non-finite,
/// answer; it never panics.
///
/// # Real-time
/// Allocation-free, constant time: at most about 70 multiplications and one division.
///
/// # Examples
/// ```
/// use haphe::DVec3;
/// use haphe::query::{Feature, closest_point_triangle};
/// let tri = [DVec3::ZERO, DVec3::X, DVec3::Y];
/// let above = closest_point_triangle(DVec3::new(0.25, 0.25, 1.0), tri);
/// assert_eq!(above.point, DVec3::new(0.25, 0.25, 0.0));
/// assert_eq!(above.feature, Feature::Face);
/// let beyond = closest_point_triangle(DVec3::new(2.0, -1.0, 0.0), tri);
/// assert_eq!((beyond.point, beyond.feature), (DVec3::X, Feature::Vertex(1)));
/// ```
#[inline]
pub fn closest_point_triangle(p: DVec3, [a, b, c]: [DVec3; 3]) -> ClosestPoint {
    let ab = b - a;
    let ac = c - a;
    let ap = p - a;
    let d1 = ab.dot(ap);
    let d2 = ac.dot(ap);
    // The vertex regions are exact optimality conditions ((p − x)·(y − x) ≤ 0 for both
    // edges at x), valid for degenerate triangles too.
    if d1 <= 0.0 && d2 <= 0.0 {
        return vertex(0, a);
    }
    let bp = p - b;
    let d3 = ab.dot(bp);
    let d4 = ac.dot(bp);
    if d3 >= 0.0 && d4 <= d3 {
        return vertex(1, b);
    }
    let cp = p - c;
    let d5 = ab.dot(cp);
    let d6 = ac.dot(cp);
    if d6 >= 0.0 && d5 <= d6 {
        return vertex(2, c);
    }

    let n = ab.cross(ac);
    let nn = n.length_squared();
    let bc = c - b;
    let longest2 = ab
        .length_squared()
        .max(ac.length_squared())
        .max(bc.length_squared());
    let min_nn = DEGENERATE_MAX_RELATIVE_HEIGHT * longest2;
    // At least MIN_POSITIVE so that 1 / nn stays finite for tiny triangles.
    let has_area = nn > min_nn * min_nn && nn >= f64::MIN_POSITIVE;
    if !has_area {
        // Also taken for NaN (non-finite input) and for an overflowing area.
        return closest_point_edges(p, [a, b, c]);
    }

    // Edges: the denominators are the squared edge lengths (d1 − d3 = |ab|², d2 − d6 = |ac|²,
    // (d4 − d3) + (d5 − d6) = |bc|²), positive for a triangle with area unless rounding
    // swamps them (p some 1e16 edge lengths away), which `fraction` guards.
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return on_edge(2, [a, b], fraction(d1, d1 - d3));
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return on_edge(1, [a, c], fraction(d2, d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 {
        return on_edge(0, [b, c], fraction(d4 - d3, (d4 - d3) + (d5 - d6)));
    }

    // Face: the projection along the normal, and the weights of b and c from the normal,
    // which stay accurate for slivers.
    let inverse = 1.0 / nn;
    let v = (n.dot(ap.cross(ac)) * inverse).clamp(0.0, 1.0);
    // min/max rather than clamp, which panics on a NaN bound (non-finite input).
    let w = (n.dot(ab.cross(ap)) * inverse).min(1.0 - v).max(0.0);
    ClosestPoint {
        point: p - n * (n.dot(ap) * inverse),
        weights: [1.0 - v - w, v, w],
        feature: Feature::Face,
    }
}

/// `numerator / denominator`, or 0 when the denominator is not positive (so never NaN for
/// finite input).
#[inline]
fn fraction(numerator: f64, denominator: f64) -> f64 {
    if denominator > 0.0 {
        numerator / denominator
    } else {
        0.0
    }
}

/// How far along the segment from `from` to `to` (a fraction in `[0, 1]`) its point
/// closest to `p` lies; 0 for a segment of zero length.
#[inline]
fn segment_fraction(p: DVec3, [from, to]: [DVec3; 2]) -> f64 {
    let e = to - from;
    fraction(e.dot(p - from), e.length_squared()).clamp(0.0, 1.0)
}

/// Distance from `p` to the segment from `from` to `to`, metres.
#[inline]
pub(crate) fn distance_to_segment(p: DVec3, [from, to]: [DVec3; 2]) -> f64 {
    let s = segment_fraction(p, [from, to]);
    (from + s * (to - from)).distance(p)
}

/// Corner `i` at `x`.
#[inline]
fn vertex(i: u8, x: DVec3) -> ClosestPoint {
    let mut weights = [0.0; 3];
    weights[usize::from(i % 3)] = 1.0;
    ClosestPoint {
        point: x,
        weights,
        feature: Feature::Vertex(i),
    }
}

/// The point a fraction `s` of the way from `from` to `to`, the two corners other than
/// corner `opposite`, lower index first; an end point is labelled as that vertex.
#[inline]
fn on_edge(opposite: u8, [from, to]: [DVec3; 2], s: f64) -> ClosestPoint {
    let (i_from, i_to) = match opposite {
        0 => (1, 2),
        1 => (0, 2),
        _ => (0, 1),
    };
    let s = s.clamp(0.0, 1.0);
    if s == 0.0 {
        return vertex(i_from, from);
    }
    if s == 1.0 {
        return vertex(i_to, to);
    }
    let mut weights = [0.0; 3];
    weights[usize::from(i_from)] = 1.0 - s;
    weights[usize::from(i_to)] = s;
    ClosestPoint {
        point: from + (to - from) * s,
        weights,
        feature: Feature::Edge(opposite),
    }
}

/// The closest point on the three edges of `[a, b, c]`: the answer for a degenerate
/// triangle, which is the union of its edges. Each edge is clamped separately, so
/// zero-length edges (coincident corners) give their end point.
fn closest_point_edges(p: DVec3, [a, b, c]: [DVec3; 3]) -> ClosestPoint {
    let mut best = on_segment(p, 2, [a, b]);
    for candidate in [on_segment(p, 0, [b, c]), on_segment(p, 1, [a, c])] {
        if candidate.1 < best.1 {
            best = candidate;
        }
    }
    best.0
}

/// The closest point to `p` on the edge from `from` to `to` (opposite corner `opposite`)
/// and its squared distance, m².
#[inline]
fn on_segment(p: DVec3, opposite: u8, [from, to]: [DVec3; 2]) -> (ClosestPoint, f64) {
    let s = segment_fraction(p, [from, to]);
    let found = on_edge(opposite, [from, to], s);
    (found, (p - found.point).length_squared())
}

#[cfg(test)]
mod tests {
    use super::*;

    const A: DVec3 = DVec3::new(0.0, 0.0, 0.0);
    const B: DVec3 = DVec3::new(2.0, 0.0, 0.0);
    const C: DVec3 = DVec3::new(0.0, 2.0, 0.0);

    #[test]
    fn all_seven_regions() {
        let cases = [
            (
                DVec3::new(0.5, 0.5, 3.0),
                DVec3::new(0.5, 0.5, 0.0),
                Feature::Face,
            ),
            (DVec3::new(-1.0, -1.0, 1.0), A, Feature::Vertex(0)),
            (DVec3::new(3.0, -0.5, -1.0), B, Feature::Vertex(1)),
            (DVec3::new(-0.5, 3.0, 0.0), C, Feature::Vertex(2)),
            (
                DVec3::new(1.0, -1.0, 0.5),
                DVec3::new(1.0, 0.0, 0.0),
                Feature::Edge(2),
            ),
            (
                DVec3::new(-1.0, 1.5, 0.0),
                DVec3::new(0.0, 1.5, 0.0),
                Feature::Edge(1),
            ),
            (
                DVec3::new(2.0, 2.0, -2.0),
                DVec3::new(1.0, 1.0, 0.0),
                Feature::Edge(0),
            ),
        ];
        for (p, expected, feature) in cases {
            let found = closest_point_triangle(p, [A, B, C]);
            assert_eq!((found.point, found.feature), (expected, feature), "{p}");
            let rebuilt = found.weights[0] * A + found.weights[1] * B + found.weights[2] * C;
            assert!((rebuilt - found.point).length() < 1e-15);
        }
    }

    #[test]
    fn edge_weights_name_the_corners() {
        let found = closest_point_triangle(DVec3::new(2.0, 2.0, 0.0), [A, B, C]);
        assert_eq!(found.weights, [0.0, 0.5, 0.5]);
        let found = closest_point_triangle(DVec3::new(-1.0, 0.5, 0.0), [A, B, C]);
        assert_eq!(found.weights, [0.75, 0.0, 0.25]);
        let found = closest_point_triangle(DVec3::new(1.5, -1.0, 0.0), [A, B, C]);
        assert_eq!(found.weights, [0.25, 0.75, 0.0]);
    }

    #[test]
    fn points_on_the_triangle_are_their_own_closest_point() {
        for p in [
            A,
            B,
            C,
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(0.5, 0.25, 0.0),
        ] {
            let found = closest_point_triangle(p, [A, B, C]);
            assert!((found.point - p).length() < 1e-15, "{p}: {found:?}");
        }
    }

    #[test]
    fn collinear_corners_give_the_segment() {
        let mid = DVec3::new(1.0, 0.0, 0.0);
        for tri in [[A, mid, B], [mid, A, B], [A, B, mid], [B, A, mid]] {
            for (p, expected) in [
                (DVec3::new(1.5, 1.0, 0.0), DVec3::new(1.5, 0.0, 0.0)),
                (DVec3::new(0.5, 0.0, -1.0), DVec3::new(0.5, 0.0, 0.0)),
                (DVec3::new(-1.0, 1.0, 1.0), A),
                (DVec3::new(5.0, 1.0, 1.0), B),
            ] {
                let found = closest_point_triangle(p, tri);
                assert!(
                    (found.point - expected).length() < 1e-15,
                    "{tri:?} {p}: {found:?}"
                );
                assert!(found.weights.iter().all(|w| w.is_finite()));
                assert!(!matches!(found.feature, Feature::Face));
            }
        }
    }

    #[test]
    fn coincident_corners_give_the_point_or_segment() {
        let p = DVec3::new(0.3, 1.0, -1.0);
        let found = closest_point_triangle(p, [B, B, B]);
        assert_eq!(found.point, B);
        assert!(matches!(found.feature, Feature::Vertex(_)));
        for tri in [[A, A, B], [A, B, A], [B, A, A]] {
            let found = closest_point_triangle(p, tri);
            assert!(
                (found.point - DVec3::new(0.3, 0.0, 0.0)).length() < 1e-15,
                "{tri:?}"
            );
            assert!(found.weights.iter().all(|w| w.is_finite()));
        }
    }

    #[test]
    fn far_queries_stay_finite() {
        for p in [
            DVec3::new(1e20, 3e19, 1.0),
            DVec3::new(0.5, 0.5, 1e30),
            DVec3::splat(-1e140),
        ] {
            for tri in [[A, B, C], [A, A * 1e-20 + B * 1e-20, C]] {
                let found = closest_point_triangle(p, tri);
                assert!(found.point.is_finite(), "{p} {tri:?}: {found:?}");
                assert!(
                    found.weights.iter().all(|w| w.is_finite()),
                    "{p}: {found:?}"
                );
            }
        }
    }

    #[test]
    fn non_finite_input_does_not_panic() {
        let nan = DVec3::splat(f64::NAN);
        let _ = closest_point_triangle(nan, [A, B, C]);
        let _ = closest_point_triangle(A, [nan, B, C]);
        let _ = closest_point_triangle(A, [A, DVec3::splat(f64::INFINITY), C]);
        let _ = closest_point_triangle(DVec3::splat(f64::MAX), [A, B, C * 1e300]);
    }
}
