//! Triangle–triangle intersection with exact predicates, not counting the corners the two
//! triangles share: the test behind the self-intersection count of mesh validation.
//!
//! The semantics, exactness and method are documented on [`intersect_triangle_triangle`].

use glam::DVec3;
use robust::{Coord, Coord3D, orient2d, orient3d};

/// A coordinate plane to project on, dropping one axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Plane {
    /// Drop z.
    Xy,
    /// Drop x.
    Yz,
    /// Drop y.
    Zx,
}

impl Plane {
    const ALL: [Plane; 3] = [Plane::Xy, Plane::Yz, Plane::Zx];

    #[inline]
    fn project(self, p: DVec3) -> Coord<f64> {
        match self {
            Plane::Xy => Coord { x: p.x, y: p.y },
            Plane::Yz => Coord { x: p.y, y: p.z },
            Plane::Zx => Coord { x: p.z, y: p.x },
        }
    }

    /// Orientation of `a, b, c` projected on this plane: exact sign.
    #[inline]
    fn orient(self, a: DVec3, b: DVec3, c: DVec3) -> f64 {
        orient2d(self.project(a), self.project(b), self.project(c))
    }
}

#[inline]
fn coord3(p: DVec3) -> Coord3D<f64> {
    Coord3D {
        x: p.x,
        y: p.y,
        z: p.z,
    }
}

/// Which side of the plane through `a, b, c` the point `d` lies on: exact sign, zero when
/// coplanar.
#[inline]
fn orient(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> f64 {
    orient3d(coord3(a), coord3(b), coord3(c), coord3(d))
}

/// Whether two exact signs are both strictly positive or both strictly negative.
#[inline]
fn same_strict_sign(x: f64, y: f64) -> bool {
    (x > 0.0 && y > 0.0) || (x < 0.0 && y < 0.0)
}

/// Whether the signs of `x` and `y` are not strictly opposite (either may be zero).
#[inline]
fn not_opposite(x: f64, y: f64) -> bool {
    !((x > 0.0 && y < 0.0) || (x < 0.0 && y > 0.0))
}

/// A coordinate plane where `a, b, c` project to a non-degenerate triangle; `None` when they
/// are collinear (or coincide) in space.
fn plane_of(a: DVec3, b: DVec3, c: DVec3) -> Option<Plane> {
    Plane::ALL
        .into_iter()
        .find(|plane| plane.orient(a, b, c) != 0.0)
}

/// Whether `a, b, c` are collinear (or coincide) in space.
#[inline]
fn collinear(a: DVec3, b: DVec3, c: DVec3) -> bool {
    plane_of(a, b, c).is_none()
}

/// The point set of a triangle's corners.
#[derive(Debug, Clone, Copy)]
enum Shape {
    /// A proper triangle, with a coordinate plane where its projection is one-to-one.
    Triangle([DVec3; 3], Plane),
    /// Collinear corners: the segment between the two extreme ones, in the order of
    /// increasing coordinate along `axis`, an axis along which they differ.
    Segment([DVec3; 2], usize),
    /// Three equal corners.
    Point(DVec3),
}

impl Shape {
    fn of(t: [DVec3; 3]) -> Shape {
        if let Some(plane) = plane_of(t[0], t[1], t[2]) {
            return Shape::Triangle(t, plane);
        }
        let Some(axis) = (0..3).find(|&i| t.iter().any(|p| p[i] != t[0][i])) else {
            return Shape::Point(t[0]);
        };
        // Collinear, and not all equal along `axis`, so that coordinate orders them.
        let lowest = t
            .into_iter()
            .fold(t[0], |m, p| if p[axis] < m[axis] { p } else { m });
        let highest = t
            .into_iter()
            .fold(t[0], |m, p| if p[axis] > m[axis] { p } else { m });
        Shape::Segment([lowest, highest], axis)
    }
}

/// Whether `x` lies on the closed segment `[u, v]` (`u` may equal `v`).
fn point_on_segment(x: DVec3, [u, v]: [DVec3; 2]) -> bool {
    collinear(x, u, v) && (0..3).all(|i| u[i].min(v[i]) <= x[i] && x[i] <= u[i].max(v[i]))
}

/// Whether the closed 2D segments `[p, q]` and `[u, v]` (projected on `plane`, which must be
/// one-to-one on their common plane) meet. Either may have coincident ends.
fn segments_meet_in(plane: Plane, [p, q]: [DVec3; 2], [u, v]: [DVec3; 2]) -> bool {
    let (o1, o2) = (plane.orient(p, q, u), plane.orient(p, q, v));
    let (o3, o4) = (plane.orient(u, v, p), plane.orient(u, v, q));
    if o1 == 0.0 && o2 == 0.0 && o3 == 0.0 && o4 == 0.0 {
        // All on one line: overlap of the intervals along a projected axis on which the
        // points differ (if none, all four coincide).
        let (pp, pq, pu, pv) = (
            plane.project(p),
            plane.project(q),
            plane.project(u),
            plane.project(v),
        );
        let along_x = [pq.x, pu.x, pv.x].iter().any(|&x| x != pp.x);
        let key = |c: Coord<f64>| if along_x { c.x } else { c.y };
        let (a0, a1) = (key(pp).min(key(pq)), key(pp).max(key(pq)));
        let (b0, b1) = (key(pu).min(key(pv)), key(pu).max(key(pv)));
        return a0.max(b0) <= a1.min(b1);
    }
    !same_strict_sign(o1, o2) && !same_strict_sign(o3, o4)
}

/// Whether `x` (coplanar with the proper triangle `t`) lies in the closed triangle, using
/// `plane`, where `t` projects one-to-one.
fn point_in_triangle_in(plane: Plane, x: DVec3, [a, b, c]: [DVec3; 3]) -> bool {
    let o = plane.orient(a, b, c);
    [
        plane.orient(a, b, x),
        plane.orient(b, c, x),
        plane.orient(c, a, x),
    ]
    .into_iter()
    .all(|s| not_opposite(s, o))
}

/// Whether the closed 3D segments `[p, q]` and `[u, v]` meet (either may be a point).
fn segments_meet([p, q]: [DVec3; 2], [u, v]: [DVec3; 2]) -> bool {
    if p == q {
        return point_on_segment(p, [u, v]);
    }
    if u == v {
        return point_on_segment(u, [p, q]);
    }
    if orient(p, q, u, v) != 0.0 {
        return false;
    }
    // Coplanar: project on a plane that is one-to-one on the plane they span.
    for plane in Plane::ALL {
        if plane.orient(p, q, u) != 0.0 || plane.orient(p, q, v) != 0.0 {
            return segments_meet_in(plane, [p, q], [u, v]);
        }
    }
    // All four on the line through p ≠ q: intervals along an axis on which p and q differ.
    let i = (0..3).find(|&i| p[i] != q[i]).unwrap_or(0);
    p[i].min(q[i]).max(u[i].min(v[i])) <= p[i].max(q[i]).min(u[i].max(v[i]))
}

/// Whether the closed segment `[p, q]` (possibly a point) meets the closed proper triangle
/// `t`, which projects one-to-one on `plane`.
fn segment_meets_triangle([p, q]: [DVec3; 2], t: [DVec3; 3], plane: Plane) -> bool {
    let [a, b, c] = t;
    let (op, oq) = (orient(a, b, c, p), orient(a, b, c, q));
    if same_strict_sign(op, oq) {
        return false;
    }
    if op == 0.0 && oq == 0.0 {
        return point_in_triangle_in(plane, p, t)
            || point_in_triangle_in(plane, q, t)
            || [[a, b], [b, c], [c, a]]
                .into_iter()
                .any(|edge| segments_meet_in(plane, [p, q], edge));
    }
    // The segment crosses (or touches) the plane at one point: the line through it passes
    // through the closed triangle when it lies on the same side of all three edges.
    let sides = [orient(p, q, a, b), orient(p, q, b, c), orient(p, q, c, a)];
    let positive = sides.iter().any(|&s| s > 0.0);
    let negative = sides.iter().any(|&s| s < 0.0);
    !(positive && negative)
}

/// Whether two closed proper triangles have a common point.
fn triangles_meet(t1: [DVec3; 3], plane1: Plane, t2: [DVec3; 3], plane2: Plane) -> bool {
    let side1 = t1.map(|p| orient(t2[0], t2[1], t2[2], p));
    if side1.iter().all(|&s| s > 0.0) || side1.iter().all(|&s| s < 0.0) {
        return false;
    }
    let side2 = t2.map(|p| orient(t1[0], t1[1], t1[2], p));
    if side2.iter().all(|&s| s > 0.0) || side2.iter().all(|&s| s < 0.0) {
        return false;
    }
    let edges = |t: [DVec3; 3]| [[t[0], t[1]], [t[1], t[2]], [t[2], t[0]]];
    if side1.iter().all(|&s| s == 0.0) {
        // Coplanar: a corner of one inside the other, or two edges crossing.
        return t1.iter().any(|&p| point_in_triangle_in(plane2, p, t2))
            || t2.iter().any(|&p| point_in_triangle_in(plane2, p, t1))
            || edges(t1).into_iter().any(|e1| {
                edges(t2)
                    .into_iter()
                    .any(|e2| segments_meet_in(plane2, e1, e2))
            });
    }
    edges(t1)
        .into_iter()
        .any(|e| segment_meets_triangle(e, t2, plane2))
        || edges(t2)
            .into_iter()
            .any(|e| segment_meets_triangle(e, t1, plane1))
}

/// Whether two shapes have a common point.
fn shapes_meet(s1: Shape, s2: Shape) -> bool {
    match (s1, s2) {
        (Shape::Triangle(t1, plane1), Shape::Triangle(t2, plane2)) => {
            triangles_meet(t1, plane1, t2, plane2)
        }
        (Shape::Triangle(t, plane), Shape::Segment(e, _))
        | (Shape::Segment(e, _), Shape::Triangle(t, plane)) => segment_meets_triangle(e, t, plane),
        (Shape::Triangle(t, plane), Shape::Point(x))
        | (Shape::Point(x), Shape::Triangle(t, plane)) => segment_meets_triangle([x, x], t, plane),
        (Shape::Segment(e1, _), Shape::Segment(e2, _)) => segments_meet(e1, e2),
        (Shape::Segment(e, _), Shape::Point(x)) | (Shape::Point(x), Shape::Segment(e, _)) => {
            point_on_segment(x, e)
        }
        (Shape::Point(x), Shape::Point(y)) => x == y,
    }
}

/// Corners of `t` rotated so that corner `i` comes first (the winding is kept).
#[inline]
fn rotated(t: [DVec3; 3], i: usize) -> [DVec3; 3] {
    [t[i % 3], t[(i + 1) % 3], t[(i + 2) % 3]]
}

/// Whether `x` (coplanar with the proper triangle `[s, a, b]`, `x ≠ s`) lies in the closed
/// sector of that triangle's corner `s`.
fn in_corner_sector(plane: Plane, [s, a, b]: [DVec3; 3], x: DVec3) -> bool {
    let o = plane.orient(s, a, b);
    not_opposite(plane.orient(s, a, x), o) && not_opposite(plane.orient(s, x, b), o)
}

/// Whether shape `shape`, of which `s` is a corner, contains the points `s + ε (x − s)` for
/// all small `ε > 0` (`x ≠ s`): whether the direction `x − s` is in its tangent cone at `s`.
fn leaves_corner_into(shape: Shape, s: DVec3, x: DVec3) -> bool {
    match shape {
        Shape::Triangle(t, plane) => {
            let Some(i) = t.iter().position(|&p| p == s) else {
                return false;
            };
            let corner = rotated(t, i);
            orient(corner[0], corner[1], corner[2], x) == 0.0 && in_corner_sector(plane, corner, x)
        }
        Shape::Segment(ends, _) => ends.into_iter().any(|end| {
            end != s
                && collinear(s, end, x)
                && (0..3).all(|i| end[i].partial_cmp(&s[i]) == x[i].partial_cmp(&s[i]))
        }),
        Shape::Point(_) => false,
    }
}

/// Whether the two closed triangles `t1` and `t2` (corners in metres, one frame) have a
/// common point outside the convex hull of the corners they share.
///
/// The answer is exact (no tolerance), symmetric in `t1` and `t2`, and independent of the
/// order of the corners in each. Non-finite corners give `false`.
///
/// # Semantics
///
/// Both triangles are closed point sets (edges and corners included). Corners are *shared*
/// when their positions are exactly equal (in a welded mesh that is the same vertex). With
/// `S` the shared corners, the triangles intersect when they have a common point outside
/// the convex hull of `S`:
///
/// | shared corners | reported when |
/// |---|---|
/// | none | they have any common point (touching at a point counts) |
/// | one, `s` | they have a common point other than `s` |
/// | two (an edge) | they overlap beyond that edge: coplanar, folded onto each other |
/// | three | never: the same triangle (a duplicate face, which validation reports as such) |
///
/// # Exactness
///
/// Every decision is a sign of [`robust::orient3d`] or [`robust::orient2d`] (Shewchuk's
/// adaptive predicates) on input points, or a comparison of input coordinates; no new point
/// is constructed. The answer is therefore exact for the given `f64` coordinates as long as
/// the predicates neither overflow nor underflow: non-zero coordinates between about
/// `1e-90` and `1e90` in magnitude, far beyond any mesh in metres.
///
/// # Method
///
/// - Two non-degenerate triangles without shared corners: the plane-side early-outs of
///   Möller (1997) and Guigue–Devillers (2003) with `orient3d`, then either the coplanar test
///   in a coordinate plane where the projection is one-to-one, or — in the general case —
///   "an edge of one meets the other": the intersection of two non-coplanar triangles is a
///   segment on the line where their planes meet, and its end points lie on edges.
/// - One shared corner `s`: the edge opposite `s` in one triangle meets the other triangle,
///   or (coplanar) an edge leaving `s` points into the other triangle's corner sector.
/// - Two shared corners: coplanar with the third corners strictly on the same side.
/// - A degenerate triangle (collinear or coincident corners) is the segment between its
///   extreme corners, or a point; with shared corners, the question becomes whether that
///   segment leaves the shared part into the other triangle, which is a direction test at
///   a shared corner.
///
/// # Real-time
/// Allocation-free, constant time: at most a few dozen exact orientation predicates
/// (adaptive: a few nanoseconds each unless the configuration is nearly degenerate). Meant
/// for validation, not for the servo loop. Never panics.
///
/// # Examples
/// ```
/// use haphe::DVec3;
/// use haphe::query::intersect_triangle_triangle;
/// let floor = [DVec3::ZERO, DVec3::X, DVec3::Y];
/// let wall = [DVec3::new(0.2, 0.2, -1.0), DVec3::new(0.2, 0.2, 1.0), DVec3::new(2.0, 2.0, 0.0)];
/// assert!(intersect_triangle_triangle(floor, wall));
/// // Two triangles of a square, sharing the diagonal: neighbours, not an intersection.
/// let other_half = [DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y];
/// assert!(!intersect_triangle_triangle(floor, other_half));
/// ```
pub fn intersect_triangle_triangle(t1: [DVec3; 3], t2: [DVec3; 3]) -> bool {
    if !t1.iter().chain(&t2).all(|p| p.is_finite()) {
        return false;
    }
    // Distinct shared positions.
    let mut shared = [DVec3::ZERO; 3];
    let mut count = 0;
    for (i, &p) in t1.iter().enumerate() {
        if t2.contains(&p) && !t1[..i].contains(&p) {
            shared[count] = p;
            count += 1;
        }
    }
    let shared = &shared[..count];

    let (shape1, shape2) = (Shape::of(t1), Shape::of(t2));
    match (shape1, shape2) {
        _ if shared.is_empty() => shapes_meet(shape1, shape2),
        (Shape::Triangle(_, plane1), Shape::Triangle(_, plane2)) => match *shared {
            [s] => proper_with_shared_corner((t1, plane1), (t2, plane2), s),
            [s0, s1] => proper_with_shared_edge(t1, t2, [s0, s1]),
            _ => false,
        },
        (Shape::Segment(ends, axis), other) | (other, Shape::Segment(ends, axis)) => {
            segment_leaves_shared_part(ends, axis, shared, other)
        }
        // A point sharing a corner: the intersection is that corner.
        _ => false,
    }
}

/// Two proper triangles sharing exactly the corner `s`.
fn proper_with_shared_corner(
    (t1, plane1): ([DVec3; 3], Plane),
    (t2, plane2): ([DVec3; 3], Plane),
    s: DVec3,
) -> bool {
    // Rotating the corners keeps the orientation, so the planes stay one-to-one.
    let position = |t: [DVec3; 3]| t.iter().position(|&p| p == s).unwrap_or(0);
    let t1 = rotated(t1, position(t1));
    let t2 = rotated(t2, position(t2));
    // The opposite edges do not contain s, so any common point with them is not s.
    if segment_meets_triangle([t1[1], t1[2]], t2, plane2)
        || segment_meets_triangle([t2[1], t2[2]], t1, plane1)
    {
        return true;
    }
    // Otherwise only the corner sectors at s can overlap, and only when coplanar.
    let coplanar =
        orient(t2[0], t2[1], t2[2], t1[1]) == 0.0 && orient(t2[0], t2[1], t2[2], t1[2]) == 0.0;
    coplanar
        && (in_corner_sector(plane2, t2, t1[1])
            || in_corner_sector(plane2, t2, t1[2])
            || in_corner_sector(plane1, t1, t2[1])
            || in_corner_sector(plane1, t1, t2[2]))
}

/// Two proper triangles sharing exactly the corners `s0` and `s1`: they overlap beyond that
/// edge only when coplanar with their third corners strictly on the same side of it.
fn proper_with_shared_edge(t1: [DVec3; 3], t2: [DVec3; 3], [s0, s1]: [DVec3; 2]) -> bool {
    let third = |t: [DVec3; 3]| t.into_iter().find(|&p| p != s0 && p != s1);
    let (Some(x1), Some(x2)) = (third(t1), third(t2)) else {
        return false;
    };
    let Some(plane) = plane_of(s0, s1, x2) else {
        return false;
    };
    orient(s0, s1, x2, x1) == 0.0
        && same_strict_sign(plane.orient(s0, s1, x1), plane.orient(s0, s1, x2))
}

/// A degenerate triangle, the segment `ends` (ordered along `axis`), sharing the corners
/// `shared` (all on it) with the shape `other`: whether the segment continues into `other`
/// beyond the span of the shared corners.
fn segment_leaves_shared_part(
    [low, high]: [DVec3; 2],
    axis: usize,
    shared: &[DVec3],
    other: Shape,
) -> bool {
    let first = shared.first().copied().unwrap_or(low);
    let (mut span_low, mut span_high) = (first, first);
    for &s in shared {
        if s[axis] < span_low[axis] {
            span_low = s;
        }
        if s[axis] > span_high[axis] {
            span_high = s;
        }
    }
    (low != span_low && leaves_corner_into(other, span_low, low))
        || (high != span_high && leaves_corner_into(other, span_high, high))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(x: f64, y: f64, z: f64) -> DVec3 {
        DVec3::new(x, y, z)
    }

    #[test]
    fn shape_of_degenerate_corners() {
        assert!(matches!(
            Shape::of([v(0., 0., 0.), v(1., 0., 0.), v(0., 1., 0.)]),
            Shape::Triangle(..)
        ));
        let Shape::Segment([lo, hi], _) = Shape::of([v(1., 1., 1.), v(0., 0., 0.), v(2., 2., 2.)])
        else {
            panic!("collinear corners are a segment");
        };
        assert_eq!((lo, hi), (v(0., 0., 0.), v(2., 2., 2.)));
        assert!(matches!(Shape::of([v(1., 2., 3.); 3]), Shape::Point(_)));
    }

    #[test]
    fn segments_meet_in_every_configuration() {
        let (o, x, y) = (v(0., 0., 0.), v(1., 0., 0.), v(0., 1., 0.));
        assert!(segments_meet([o, x], [v(0.5, -1., 0.), v(0.5, 1., 0.)]));
        assert!(!segments_meet([o, x], [v(0.5, 0.1, 0.), v(0.5, 1., 0.)]));
        assert!(segments_meet([o, x], [x, y]));
        assert!(segments_meet([o, x], [v(0.5, 0., 0.), v(2., 0., 0.)]));
        assert!(!segments_meet([o, x], [v(1.5, 0., 0.), v(2., 0., 0.)]));
        assert!(segments_meet([o, x], [v(0.25, 0., 0.), v(0.25, 0., 0.)]));
        assert!(!segments_meet([o, o], [x, y]));
        assert!(segments_meet([y, y], [y, y]));
        // Skew lines.
        assert!(!segments_meet([o, x], [v(0.5, 0., 1.), v(0.5, 1., 1.)]));
    }
}
