//! The signed solid angle of a triangle seen from a point.

use glam::DVec3;

/// Signed solid angle (steradians) of triangle `[a, b, c]` seen from `p` (Van Oosterom and
/// Strackee): positive when `p` lies behind the triangle (on the side its normal points
/// away from), so a closed outward-oriented surface sums to 4π around a point inside it.
pub fn solid_angle([a, b, c]: [DVec3; 3], p: DVec3) -> f64 {
    let (a, b, c) = (a - p, b - p, c - p);
    let (la, lb, lc) = (a.length(), b.length(), c.length());
    let numerator = a.dot(b.cross(c));
    let denominator = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
    2.0 * numerator.atan2(denominator)
}
