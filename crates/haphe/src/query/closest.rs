//! Closest point on a triangle (to be written).

use glam::DVec3;

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
    /// Barycentric weights of `point` for corners `a, b, c` (each in `[0, 1]`, summing to 1).
    pub weights: [f64; 3],
    /// The feature the point lies on.
    pub feature: Feature,
}

/// The point of triangle `[a, b, c]` closest to `p`.
pub fn closest_point_triangle(p: DVec3, [a, _b, _c]: [DVec3; 3]) -> ClosestPoint {
    let _ = p;
    ClosestPoint {
        point: a,
        weights: [1.0, 0.0, 0.0],
        feature: Feature::Vertex(0),
    }
}
