//! Per-triangle data precomputed for fast barycentric coordinates.

use glam::DVec3;

/// A triangle's frame: its first corner, the dual vectors of its edges and its unit normal,
/// so that the barycentric coordinates of any point cost two dot products.
///
/// For a point `p` (metres, object frame) projected onto the triangle's plane,
/// `p ≈ a + u·(b − a) + v·(c − a)` with `u = dual_b · (p − a)` and `v = dual_c · (p − a)`;
/// the weights of the corners `a, b, c` are `(1 − u − v, u, v)`. The out-of-plane part of
/// `p − a` is `normal · (p − a)`.
///
/// Invariant: for a non-degenerate triangle `dual_b · (b − a) = 1`, `dual_b · (c − a) = 0`,
/// `dual_c · (b − a) = 0`, `dual_c · (c − a) = 1`, both duals lie in the plane, and `normal`
/// has unit length. A degenerate (zero-area) triangle (see [`TriFrame::is_degenerate`]) has all three vectors zero, so its
/// coordinates come out as `(1, 0, 0)` and it is never taken as a hit.
#[derive(Debug, Clone, Copy, PartialEq, Default, bytemuck::Pod, bytemuck::Zeroable)]
#[repr(C)]
pub struct TriFrame {
    /// Corner `a`, metres, object frame.
    pub origin: DVec3,
    /// Dual of edge `b − a`, 1/metres.
    pub dual_b: DVec3,
    /// Dual of edge `c − a`, 1/metres.
    pub dual_c: DVec3,
    /// Unit face normal `(b − a) × (c − a) / |…|`, pointing out of a solid.
    pub normal: DVec3,
}

impl TriFrame {
    /// The frame of triangle `(a, b, c)`.
    pub fn new(a: DVec3, b: DVec3, c: DVec3) -> TriFrame {
        let (e1, e2) = (b - a, c - a);
        let n = e1.cross(e2);
        let nn = n.length_squared();
        if is_degenerate_triangle(a, b, c) || !(nn > 0.0 && nn.is_finite()) {
            return TriFrame {
                origin: a,
                ..TriFrame::default()
            };
        }
        TriFrame {
            origin: a,
            dual_b: e2.cross(n) / nn,
            dual_c: n.cross(e1) / nn,
            normal: n / nn.sqrt(),
        }
    }

    /// Whether the triangle has a usable (non-zero, finite) area.
    #[inline]
    pub fn is_degenerate(&self) -> bool {
        self.normal == DVec3::ZERO
    }

    /// Barycentric weights `[w_a, w_b, w_c]` (summing to 1) of the projection of `p` onto
    /// the triangle's plane. A negative weight names the edge opposite that corner as the
    /// side `p` lies beyond — the rule of the surface walk.
    #[inline]
    pub fn barycentric(&self, p: DVec3) -> [f64; 3] {
        let d = p - self.origin;
        let u = self.dual_b.dot(d);
        let v = self.dual_c.dot(d);
        [1.0 - u - v, u, v]
    }

    /// Signed distance of `p` from the triangle's plane, metres, positive on the normal side.
    #[inline]
    pub fn height(&self, p: DVec3) -> f64 {
        self.normal.dot(p - self.origin)
    }
}

/// A triangle whose smallest altitude is below this fraction of its longest edge is
/// *degenerate* (zero area for practical purposes): its barycentric frame would keep fewer
/// than about seven significant digits of an `f64`, so it is never used as a contact.
pub const DEGENERATE_MAX_RELATIVE_HEIGHT: f64 = 1e-9;

/// A non-degenerate triangle whose smallest altitude is below this fraction of its longest
/// edge is a *sliver*: usable, but reported, since long thin triangles make shading and
/// walking less even.
pub const SLIVER_MAX_RELATIVE_HEIGHT: f64 = 1e-2;

/// Smallest altitude over longest edge of triangle `(a, b, c)`, i.e. `2·area / longest²`:
/// `√3/2 ≈ 0.866` for an equilateral triangle, 0 for a degenerate one (and for a point).
pub fn relative_height(a: DVec3, b: DVec3, c: DVec3) -> f64 {
    let longest2 = (b - a)
        .length_squared()
        .max((c - b).length_squared())
        .max((a - c).length_squared());
    let twice_area = (b - a).cross(c - a).length();
    if longest2 > 0.0 && twice_area.is_finite() {
        twice_area / longest2
    } else {
        0.0
    }
}

/// Whether triangle `(a, b, c)` is degenerate (see [`DEGENERATE_MAX_RELATIVE_HEIGHT`]).
#[inline]
pub fn is_degenerate_triangle(a: DVec3, b: DVec3, c: DVec3) -> bool {
    relative_height(a, b, c) <= DEGENERATE_MAX_RELATIVE_HEIGHT
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn barycentric_rebuilds_the_projected_point() {
        let (a, b, c) = (
            DVec3::new(0.1, 0.2, 0.3),
            DVec3::new(1.0, 0.1, -0.2),
            DVec3::new(0.3, 0.9, 0.5),
        );
        let f = TriFrame::new(a, b, c);
        let p = DVec3::new(0.4, 0.4, 0.7);
        let [wa, wb, wc] = f.barycentric(p);
        let rebuilt = wa * a + wb * b + wc * c + f.height(p) * f.normal;
        assert!((rebuilt - p).length() < 1e-12, "{rebuilt} vs {p}");
        assert_eq!(f.barycentric(b).map(|w| (w * 1e9).round()), [0.0, 1e9, 0.0]);
    }

    #[test]
    fn degenerate_triangle_has_a_zero_frame() {
        let f = TriFrame::new(DVec3::ZERO, DVec3::X, 2.0 * DVec3::X);
        assert!(f.is_degenerate());
        assert_eq!(f.barycentric(DVec3::Y), [1.0, 0.0, 0.0]);
    }
}
