//! Triangle–box overlap: Akenine-Möller's separating-axis test.

use glam::DVec3;

/// Whether the triangle `corners` overlaps the **closed** axis-aligned box with centre
/// `box_centre` and half extents `box_half` (all in one frame and unit, half extents
/// non-negative).
///
/// This is the separating-axis test of Akenine-Möller (*Fast 3D Triangle-Box Overlap
/// Testing*, 2001): the triangle and the box are disjoint exactly when their projections
/// are disjoint on one of thirteen axes — the three box normals, the triangle's normal and
/// the nine cross products of a triangle edge with a box normal. A triangle that only
/// touches the box (a corner on a face, an edge along an edge) overlaps it. Degenerate
/// triangles (a segment or a point) are handled exactly too: their zero normal and zero
/// cross products never separate, and the remaining axes are the ones a segment needs.
///
/// The answer is exact for exactly representable intermediate values (for example small
/// integer or dyadic coordinates); otherwise rounding can decide configurations within a
/// few units in the last place of touching either way, which is why the voxel map enlarges
/// its cells slightly before testing (`OVERLAP_TOLERANCE_REL`).
/// Work relative to the box (or in cell units, as the map does) to keep rounding small.
///
/// # Performance
/// About 70 floating-point operations in the worst case, fewer when an early axis
/// separates. No allocation, no panic for any input (non-finite input gives an
/// unspecified answer).
///
/// # Examples
/// ```
/// use haphe::DVec3;
/// use haphe::map::overlap_triangle_box;
/// let tri = [DVec3::new(1.0, 0.0, 0.0), DVec3::new(2.0, 0.0, 0.0), DVec3::new(1.0, 1.0, 0.0)];
/// // The unit box centred at the origin: the triangle touches its face x = 1.
/// assert!(overlap_triangle_box(tri, DVec3::ZERO, DVec3::ONE));
/// assert!(!overlap_triangle_box(tri, DVec3::ZERO, DVec3::splat(0.999)));
/// ```
#[inline]
pub fn overlap_triangle_box(corners: [DVec3; 3], box_centre: DVec3, box_half: DVec3) -> bool {
    let [v0, v1, v2] = corners.map(|p| p - box_centre);
    let h = box_half;

    // The three box normals: the triangle's bounding box against the box. (Comparisons
    // rather than `min`/`max`, which are slower for their NaN rules.)
    for axis in 0..3 {
        let (a, b, c, r) = (v0[axis], v1[axis], v2[axis], h[axis]);
        if (a > r && b > r && c > r) || (a < -r && b < -r && c < -r) {
            return false;
        }
    }

    // The triangle's plane against the box (in practice the axis that separates most
    // often among cells near a triangle, so it comes before the nine below).
    let (e0, e1, e2) = (v1 - v0, v2 - v1, v0 - v2);
    let normal = e0.cross(e1);
    let distance = normal.dot(v0);
    let r = h.x * normal.x.abs() + h.y * normal.y.abs() + h.z * normal.z.abs();
    if distance > r || distance < -r {
        return false;
    }

    // The nine edge × box-normal axes. For the axis `e × x̂ = (0, e.z, −e.y)` both ends of
    // edge `e` project to the same value, so two projections suffice: one end and the
    // opposite corner.
    !(separated_across_edge(e0, v0, v2, h)
        || separated_across_edge(e1, v1, v0, h)
        || separated_across_edge(e2, v2, v1, h))
}

/// Whether one of the axes `e × x̂`, `e × ŷ`, `e × ẑ` separates the triangle (with `p` on
/// edge `e` and `q` the opposite corner, relative to the box centre) from the box of half
/// extents `h`.
#[inline]
fn separated_across_edge(e: DVec3, p: DVec3, q: DVec3, h: DVec3) -> bool {
    let separated = |a: f64, b: f64, r: f64| (a > r && b > r) || (a < -r && b < -r);
    let (ax, ay, az) = (e.x.abs(), e.y.abs(), e.z.abs());
    // e × x̂ = (0, e.z, −e.y)
    separated(
        e.z * p.y - e.y * p.z,
        e.z * q.y - e.y * q.z,
        h.y * az + h.z * ay,
    )
    // e × ŷ = (−e.z, 0, e.x)
    || separated(
        e.x * p.z - e.z * p.x,
        e.x * q.z - e.z * q.x,
        h.x * az + h.z * ax,
    )
    // e × ẑ = (e.y, −e.x, 0)
    || separated(
        e.y * p.x - e.x * p.y,
        e.y * q.x - e.x * q.y,
        h.x * ay + h.y * ax,
    )
}

/// The separating-axis test of [`overlap_triangle_box`] prepared for one triangle against
/// many boxes of the same size: the triangle's projections onto the thirteen axes are
/// computed once, so each box costs one dot product and two comparisons per axis.
///
/// Coordinates are absolute (not relative to each box), which changes rounding by about
/// `1e-16 ×` the coordinates' magnitude compared with [`overlap_triangle_box`]; the voxel
/// map works in cell units and enlarges its boxes far beyond that.
#[derive(Debug, Clone, Copy)]
pub(crate) struct TriangleBoxes {
    /// Axes: three box normals are implicit (`bounds`); then the normal and nine edge
    /// axes.
    axes: [DVec3; 10],
    /// A box centre `c` is separated on axis `k` when `axes[k]·c` is outside
    /// `[low[k], high[k]]`.
    low: [f64; 10],
    high: [f64; 10],
    /// The triangle's bounding box enlarged by the half extents.
    min: DVec3,
    max: DVec3,
}

impl TriangleBoxes {
    /// Prepares triangle `corners` against boxes of half extents `half`.
    pub(crate) fn new(corners: [DVec3; 3], half: DVec3) -> TriangleBoxes {
        let [v0, v1, v2] = corners;
        let edges = [(v1 - v0, v0, v2), (v2 - v1, v1, v0), (v0 - v2, v2, v1)];
        let normal = (v1 - v0).cross(v2 - v1);
        let mut axes = [DVec3::ZERO; 10];
        let mut low = [0.0; 10];
        let mut high = [0.0; 10];
        let d = normal.dot(v0);
        let r = half.x * normal.x.abs() + half.y * normal.y.abs() + half.z * normal.z.abs();
        axes[0] = normal;
        (low[0], high[0]) = (d - r, d + r);
        let mut k = 1;
        for (e, p, q) in edges {
            for axis in [
                DVec3::new(0.0, e.z, -e.y),
                DVec3::new(-e.z, 0.0, e.x),
                DVec3::new(e.y, -e.x, 0.0),
            ] {
                let (a, b) = (axis.dot(p), axis.dot(q));
                let r = half.x * axis.x.abs() + half.y * axis.y.abs() + half.z * axis.z.abs();
                axes[k] = axis;
                (low[k], high[k]) = (if a < b { a } else { b } - r, if a < b { b } else { a } + r);
                k += 1;
            }
        }
        TriangleBoxes {
            axes,
            low,
            high,
            min: v0.min(v1).min(v2) - half,
            max: v0.max(v1).max(v2) + half,
        }
    }

    /// Whether the triangle overlaps the closed box centred at `centre`.
    #[inline]
    pub(crate) fn overlaps(&self, centre: DVec3) -> bool {
        if centre.cmplt(self.min).any() || centre.cmpgt(self.max).any() {
            return false;
        }
        for k in 0..10 {
            let s = self.axes[k].dot(centre);
            if s < self.low[k] || s > self.high[k] {
                return false;
            }
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Exact reference: does some point `a + u·(b − a) + v·(c − a)` with `u, v ≥ 0`,
    /// `u + v ≤ 1` lie in the closed box `[lo, hi]`? Integer coordinates, i128 arithmetic.
    /// The feasible set in `(u, v)` is a bounded convex polygon, so it is non-empty exactly
    /// when one of its vertices — the intersection of two independent constraint lines —
    /// satisfies every constraint.
    pub(crate) fn overlap_exact(tri: [[i64; 3]; 3], lo: [i64; 3], hi: [i64; 3]) -> bool {
        let [a, b, c] = tri.map(|p| p.map(i128::from));
        // Constraints α·u + β·v ≤ γ.
        let mut cons: Vec<[i128; 3]> = vec![[-1, 0, 0], [0, -1, 0], [1, 1, 1]];
        for k in 0..3 {
            let (eb, ec) = (b[k] - a[k], c[k] - a[k]);
            cons.push([eb, ec, i128::from(hi[k]) - a[k]]);
            cons.push([-eb, -ec, a[k] - i128::from(lo[k])]);
        }
        for i in 0..cons.len() {
            for j in i + 1..cons.len() {
                let [a1, b1, c1] = cons[i];
                let [a2, b2, c2] = cons[j];
                let det = a1 * b2 - a2 * b1;
                if det == 0 {
                    continue;
                }
                let (un, vn) = (c1 * b2 - c2 * b1, a1 * c2 - a2 * c1);
                let feasible = cons.iter().all(|&[al, be, ga]| {
                    let lhs = al * un + be * vn;
                    let rhs = ga * det;
                    if det > 0 { lhs <= rhs } else { lhs >= rhs }
                });
                if feasible {
                    return true;
                }
            }
        }
        false
    }

    fn to_f64(p: [i64; 3], scale: f64, shift: f64) -> DVec3 {
        DVec3::from_array(p.map(|x| x as f64 * scale + shift))
    }

    fn run(tri: [[i64; 3]; 3], lo: [i64; 3], hi: [i64; 3], scale: f64, shift: f64) -> bool {
        let corners = tri.map(|p| to_f64(p, scale, shift));
        let (l, h) = (to_f64(lo, scale, shift), to_f64(hi, scale, shift));
        overlap_triangle_box(corners, 0.5 * (l + h), 0.5 * (h - l))
    }

    #[test]
    fn touching_counts_as_overlap() {
        let unit = ([0, 0, 0], [2, 2, 2]);
        // A corner on a face, an edge on an edge, a face on a face, a point on a corner.
        let cases: [[[i64; 3]; 3]; 5] = [
            [[2, 1, 1], [4, 1, 1], [3, 3, 1]],
            [[2, 2, 0], [2, 2, 2], [4, 4, 1]],
            [[0, 0, 2], [2, 0, 2], [0, 2, 2]],
            [[2, 2, 2], [2, 2, 2], [2, 2, 2]],
            [[4, 0, 0], [0, 4, 0], [4, 4, 5]],
        ];
        for tri in cases {
            assert!(overlap_exact(tri, unit.0, unit.1), "{tri:?}");
            assert!(run(tri, unit.0, unit.1, 1.0, 0.0), "{tri:?}");
        }
        // Just off: the edge x + y = 4 + 1/4 misses the box corner (2, 2, 0).
        let off = [[17, 0, 0], [0, 17, 0], [17, 17, 20]];
        let box4 = ([0, 0, 0], [8, 8, 8]);
        assert!(!overlap_exact(off, box4.0, box4.1));
        assert!(!run(off, box4.0, box4.1, 0.25, 0.0));
    }

    #[test]
    fn a_triangle_around_the_box_misses_it_while_its_plane_cuts_it() {
        // A big triangle with a hole where the box is is impossible; instead: a triangle
        // whose plane cuts the box but whose edges pass beside it (edge axes separate).
        let tri = [[4, -10, 0], [4, 10, 0], [20, 0, 0]];
        let (lo, hi) = ([-2, -2, -2], [2, 2, 2]);
        assert!(!overlap_exact(tri, lo, hi));
        assert!(!run(tri, lo, hi, 1.0, 0.0));
        let slanted = [[3, -9, -9], [3, 9, 0], [-9, 0, 9]];
        assert_eq!(
            overlap_exact(slanted, lo, hi),
            run(slanted, lo, hi, 1.0, 0.0)
        );
    }

    fn point() -> impl Strategy<Value = [i64; 3]> {
        [-12i64..=12, -12i64..=12, -12i64..=12]
    }

    fn boxes() -> impl Strategy<Value = ([i64; 3], [i64; 3])> {
        (point(), [0i64..=6, 0i64..=6, 0i64..=6])
            .prop_map(|(lo, size)| (lo, [lo[0] + size[0], lo[1] + size[1], lo[2] + size[2]]))
    }

    fn near_triangle() -> impl Strategy<Value = [[i64; 3]; 3]> {
        // Corners near the box region so that touching and grazing cases are frequent.
        [point(), point(), point()]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(4000))]

        /// On integer coordinates scaled by powers of two and shifted by dyadic offsets all
        /// arithmetic is exact, so the test must agree with the exact reference every time.
        #[test]
        fn agrees_with_exact_reference(
            tri in near_triangle(),
            (lo, hi) in boxes(),
            scale_exp in -20i32..=20,
            shift in prop::sample::select(vec![0.0, 0.5, -3.25, 1024.0]),
        ) {
            let scale = 2f64.powi(scale_exp);
            let expected = overlap_exact(tri, lo, hi);
            prop_assert_eq!(run(tri, lo, hi, scale, shift * scale), expected);
        }

        /// Degenerate triangles (repeated or collinear corners) too.
        #[test]
        fn degenerate_triangles_agree(
            a in point(),
            b in point(),
            t in 0i64..=2,
            (lo, hi) in boxes(),
        ) {
            let c = [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2])];
            for tri in [[a, b, c], [a, a, a], [a, b, b]] {
                prop_assert_eq!(run(tri, lo, hi, 1.0, 0.0), overlap_exact(tri, lo, hi), "{:?}", tri);
            }
        }

        /// Order and orientation of the corners do not matter.
        #[test]
        fn symmetric_in_the_corners(tri in near_triangle(), (lo, hi) in boxes()) {
            let r = run(tri, lo, hi, 1.0, 0.0);
            prop_assert_eq!(run([tri[1], tri[2], tri[0]], lo, hi, 1.0, 0.0), r);
            prop_assert_eq!(run([tri[0], tri[2], tri[1]], lo, hi, 1.0, 0.0), r);
        }
    }
}
