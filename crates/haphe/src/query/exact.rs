//! Error-free floating-point transformations for the few decisions of the segment test
//! that rounding must not change: exact signs of small polynomials in the input
//! coordinates, and a double-double orientation for parameters that must stay accurate
//! when a segment runs almost in a triangle's plane.
//!
//! Everything is exact (or double-double) as long as no product underflows, that is for
//! coordinate differences above about `1e-150` in magnitude or exactly zero; finite input
//! never panics, non-finite input gives a NaN or a zero sign.

use glam::DVec3;
use robust::{Coord3D, orient3d};

/// Unit roundoff of `f64`, `2⁻⁵³`.
pub(crate) const ROUNDOFF: f64 = f64::EPSILON / 2.0;

/// `a + b = s + e` exactly (Knuth's two-sum).
#[inline]
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    let e = (a - (s - bb)) + (b - bb);
    (s, e)
}

/// `a − b = s + e` exactly.
#[inline]
fn two_diff(a: f64, b: f64) -> (f64, f64) {
    two_sum(a, -b)
}

/// `a · b = p + e` exactly: with a fused multiply–add where the target has one, else by
/// Dekker's splitting (a handful of products, where `f64::mul_add` would be a call to a
/// software routine), which is exact while `a` and `b` stay below [`SPLIT_MAX`]; beyond
/// it, the correctly rounded `f64::mul_add` of every target.
#[inline]
fn two_product(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    if cfg!(target_feature = "fma") || !(a.abs() < SPLIT_MAX && b.abs() < SPLIT_MAX) {
        return (p, a.mul_add(b, -p));
    }
    let (ah, al) = split(a);
    let (bh, bl) = split(b);
    (p, ((ah * bh - p) + ah * bl + al * bh) + al * bl)
}

/// Largest magnitude [`split`] takes: far below where `(2²⁷ + 1)·a` overflows.
const SPLIT_MAX: f64 = 1e290;

/// `a = hi + lo` exactly, each half with at most 26 significant bits (Veltkamp's split), so
/// that the product of two halves is exact.
#[inline(always)]
fn split(a: f64) -> (f64, f64) {
    const SPLITTER: f64 = 134_217_729.0; // 2²⁷ + 1
    let c = SPLITTER * a;
    let hi = c - (c - a);
    (hi, a - hi)
}

/// The sign (`−1`, `0` or `1`) of the exact sum of `terms`, by Shewchuk's grow-expansion:
/// the running expansion stays non-overlapping, so its largest non-zero component has the
/// sign of the sum. Zero terms are left out (on meshes with round coordinates most of the
/// rounding terms are zero). NaN terms give `0`.
fn sign_of_sum<const N: usize>(terms: [f64; N]) -> i8 {
    let mut expansion = [0.0f64; N];
    let mut len = 0;
    for &b in terms.iter().filter(|&&b| b != 0.0) {
        let mut q = b;
        for e in expansion.iter_mut().take(len) {
            let (s, err) = two_sum(q, *e);
            *e = err;
            q = s;
        }
        if let Some(slot) = expansion.get_mut(len) {
            *slot = q;
            len += 1;
        }
    }
    match expansion.iter().take(len).rev().find(|&&x| x != 0.0) {
        Some(&x) if x > 0.0 => 1,
        Some(&x) if x < 0.0 => -1,
        _ => 0,
    }
}

/// The exact sign of `(q_i − p_i)(s_j − r_j) − (q_j − p_j)(s_i − r_i)`: the orientation of
/// the vectors `q − p` and `s − r` projected on the axes `i, j`.
///
/// Filtered: the `f64` value decides when it exceeds Shewchuk's bound on its rounding
/// error (`ccwerrboundA` of his `orient2d`, which rounds the same differences and
/// products: `(3 + 16ε)ε` times the sum of the two products' magnitudes); otherwise the
/// sign comes from the exact expansion of the sixteen rounding terms.
#[inline]
pub(crate) fn cross_of_differences_sign(points: [DVec3; 4], i: usize, j: usize) -> i8 {
    let [q, p, s, r] = points;
    let left = (q[i] - p[i]) * (s[j] - r[j]);
    let right = (q[j] - p[j]) * (s[i] - r[i]);
    let value = left - right;
    const BOUND: f64 = (3.0 + 16.0 * ROUNDOFF) * ROUNDOFF;
    let bound = BOUND * (left.abs() + right.abs());
    if value > bound {
        1
    } else if value < -bound {
        -1
    } else {
        cross_of_differences_sign_exact(points, i, j)
    }
}

/// [`cross_of_differences_sign`] without the filter: the sign of the exact sum of the
/// products of the differences' two-term expansions.
fn cross_of_differences_sign_exact([q, p, s, r]: [DVec3; 4], i: usize, j: usize) -> i8 {
    let a = two_diff(q[i], p[i]);
    let b = two_diff(s[j], r[j]);
    let c = two_diff(q[j], p[j]);
    let d = two_diff(s[i], r[i]);
    let mut terms = [0.0f64; 16];
    for (k, (x, y, sign)) in [
        (a.0, b.0, 1.0),
        (a.0, b.1, 1.0),
        (a.1, b.0, 1.0),
        (a.1, b.1, 1.0),
        (c.0, d.0, -1.0),
        (c.0, d.1, -1.0),
        (c.1, d.0, -1.0),
        (c.1, d.1, -1.0),
    ]
    .into_iter()
    .enumerate()
    {
        let (hi, lo) = two_product(x, y);
        terms[2 * k] = sign * hi;
        terms[2 * k + 1] = sign * lo;
    }
    sign_of_sum(terms)
}

fn coord(p: DVec3) -> Coord3D<f64> {
    Coord3D {
        x: p.x,
        y: p.y,
        z: p.z,
    }
}

/// The exact sign of `det[a − p, b − p, c − p]` (Shewchuk's `orient3d`): positive when
/// `p` is behind the plane of the counter-clockwise triangle `a, b, c`, i.e. on the side
/// opposite to `(b − a) × (c − a)`. NaN gives `0`.
#[inline]
pub(crate) fn orient3d_sign(a: DVec3, b: DVec3, c: DVec3, p: DVec3) -> i8 {
    let o = orient3d(coord(a), coord(b), coord(c), coord(p));
    if o > 0.0 {
        1
    } else if o < 0.0 {
        -1
    } else {
        0
    }
}

/// `det[a − p, b − p, c − p]` in `f64` with Shewchuk's bound on its error (his
/// `o3derrboundA` times the permanent): the sign of the value is exact when its magnitude
/// exceeds the bound.
///
/// It is computed as `det[a − p, b − a, c − a]`, the same determinant (rows two and three
/// less row one): still three differences of input coordinates, each rounded once, so the
/// same bound holds, with a permanent that grows with the triangle's edges instead of the
/// distance of `p` cubed. For a point far from a small triangle (a long segment over a
/// fine mesh) the value is then decided, and accurate to far better than `2⁻⁴⁰`, in `f64`.
#[inline]
pub(crate) fn orient3d_with_bound(a: DVec3, b: DVec3, c: DVec3, p: DVec3) -> (f64, f64) {
    let (ad, bd, cd) = (a - p, b - a, c - a);
    let bxcy = bd.x * cd.y;
    let cxby = cd.x * bd.y;
    let cxay = cd.x * ad.y;
    let axcy = ad.x * cd.y;
    let axby = ad.x * bd.y;
    let bxay = bd.x * ad.y;
    let det = ad.z * (bxcy - cxby) + bd.z * (cxay - axcy) + cd.z * (axby - bxay);
    let permanent = (bxcy.abs() + cxby.abs()) * ad.z.abs()
        + (cxay.abs() + axcy.abs()) * bd.z.abs()
        + (axby.abs() + bxay.abs()) * cd.z.abs();
    const BOUND: f64 = (7.0 + 56.0 * ROUNDOFF) * ROUNDOFF;
    (det, BOUND * permanent)
}

/// A double-double number `hi + lo`, `|lo| ≤ ulp(hi)/2`.
#[derive(Clone, Copy)]
struct DoubleDouble {
    hi: f64,
    lo: f64,
}

impl DoubleDouble {
    fn difference(a: f64, b: f64) -> DoubleDouble {
        let (hi, lo) = two_diff(a, b);
        DoubleDouble { hi, lo }
    }

    fn add(self, o: DoubleDouble) -> DoubleDouble {
        let (s, e) = two_sum(self.hi, o.hi);
        let e = e + self.lo + o.lo;
        let (hi, lo) = two_sum(s, e);
        DoubleDouble { hi, lo }
    }

    fn neg(self) -> DoubleDouble {
        DoubleDouble {
            hi: -self.hi,
            lo: -self.lo,
        }
    }

    fn mul(self, o: DoubleDouble) -> DoubleDouble {
        let (p, e) = two_product(self.hi, o.hi);
        let e = e + (self.hi * o.lo + self.lo * o.hi);
        let (hi, lo) = two_sum(p, e);
        DoubleDouble { hi, lo }
    }
}

/// `det[a − p, b − p, c − p]` in double-double arithmetic, as `det[a − p, b − a, c − a]`
/// (see [`orient3d_with_bound`]): the differences are exact, and the result is within a
/// few `2⁻¹⁰⁶` times the permanent of the exact value.
pub(crate) fn orient3d_double_double(a: DVec3, b: DVec3, c: DVec3, p: DVec3) -> f64 {
    let d = |x: DVec3, from: DVec3| {
        [
            DoubleDouble::difference(x.x, from.x),
            DoubleDouble::difference(x.y, from.y),
            DoubleDouble::difference(x.z, from.z),
        ]
    };
    let (ad, bd, cd) = (d(a, p), d(b, a), d(c, a));
    let minor =
        |u: [DoubleDouble; 3], v: [DoubleDouble; 3]| u[0].mul(v[1]).add(u[1].mul(v[0]).neg());
    let det = ad[2]
        .mul(minor(bd, cd))
        .add(bd[2].mul(minor(cd, ad)))
        .add(cd[2].mul(minor(ad, bd)));
    det.hi + det.lo
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sums_that_cancel_in_floating_point_keep_their_sign() {
        assert_eq!(sign_of_sum([1e16, 1.0, -1e16]), 1);
        assert_eq!(sign_of_sum([1e16, -1.0, -1e16, 0.5]), -1);
        assert_eq!(sign_of_sum([0.1, 0.2, -0.1, -0.2]), 0);
        assert_eq!(sign_of_sum([f64::NAN, 1.0]), 0);
    }

    #[test]
    fn cross_of_differences_is_exact_where_floats_round_to_zero() {
        // (q − p) = (1 + 2⁻⁵², 1), (s − r) = (1, 1): the cross product is 2⁻⁵², but with
        // huge offsets each difference rounds.
        let big = 2f64.powi(60);
        let q = DVec3::new(big + 4096.0, big + 4096.0, 0.0);
        let p = DVec3::new(big, big, 0.0);
        let s = DVec3::new(3.0, 2.0 + 1e-300, 0.0);
        let r = DVec3::new(2.0, 1.0, 0.0);
        // (4096)(1 + tiny) − (4096)(1) > 0.
        assert_eq!(cross_of_differences_sign([q, p, s, r], 0, 1), 0);
        let s = DVec3::new(3.0, 2.0 + 2f64.powi(-51), 0.0);
        assert_eq!(cross_of_differences_sign([q, p, s, r], 0, 1), 1);
        assert_eq!(cross_of_differences_sign([q, p, s, r], 1, 0), -1);
    }

    #[test]
    fn the_filter_never_changes_the_exact_sign() {
        // Random points, points on one line through big offsets (the products cancel to
        // within rounding), and exact zeros: the filtered sign equals the expansion's.
        let mut unit = unit_stream(0x2545_f491_4f6c_dd1d);
        let mut decided_by_the_filter = 0;
        for k in 0..20_000 {
            let offset = [0.0, 1.0, 1e3, 2f64.powi(40)][k % 4];
            let p = DVec3::new(unit(), unit(), unit()) + offset;
            let q = p + DVec3::new(unit(), unit(), unit());
            let r = DVec3::new(unit(), unit(), unit()) - offset;
            let direction = q - p;
            let s = match k % 3 {
                0 => r + DVec3::new(unit(), unit(), unit()),
                1 => r + direction * unit() * 3.0,
                _ => r + direction * 2.0 + DVec3::splat(unit() * 1e-15),
            };
            for (i, j) in [(0, 1), (1, 2), (2, 0), (1, 0)] {
                let exact = cross_of_differences_sign_exact([q, p, s, r], i, j);
                let filtered = cross_of_differences_sign([q, p, s, r], i, j);
                assert_eq!(filtered, exact, "{k} {i} {j}: {q} {p} {s} {r}");
                decided_by_the_filter += usize::from(exact != 0);
            }
        }
        assert!(decided_by_the_filter > 40_000, "{decided_by_the_filter}");
    }

    /// A xorshift stream of `f64` in `[-0.5, 0.5)`.
    fn unit_stream(mut state: u64) -> impl FnMut() -> f64 {
        move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        }
    }

    #[test]
    fn two_product_is_exact_with_or_without_splitting() {
        let mut unit = unit_stream(0x9e37_79b9_7f4a_7c15);
        for k in 0..20_000 {
            // Magnitudes from 1e-150 to 1e150, and a few beyond the split's range.
            let scale = |u: f64| 10f64.powf(300.0 * u);
            let (a, b) = (unit() * scale(unit()), unit() * scale(unit()));
            let (a, b) = if k % 1000 == 0 {
                (a * 1e295, b)
            } else {
                (a, b)
            };
            let (p, e) = two_product(a, b);
            assert_eq!(p, a * b);
            // Exact wherever the error term is a normal number (no underflow).
            if p.is_finite() && p.abs() > 1e-280 {
                assert_eq!(e, a.mul_add(b, -p), "{a} × {b}");
            }
        }
    }

    #[test]
    fn orientation_bound_holds_for_far_points_over_small_triangles() {
        // Triangles a tenth of a millimetre across, points up to a metre away and points
        // within rounding of their planes: wherever the filter decides, it decides right,
        // and for far points its value is accurate to 2⁻⁴⁰ (with `det[a − p, b − p,
        // c − p]` the bound would be some 10⁸ times larger, and a segment's parameter
        // would need the double-double path).
        let mut unit = unit_stream(0x2545_f491_4f6c_dd1d);
        let mut accurate_far = 0;
        for k in 0..20_000 {
            let centre = DVec3::new(unit(), unit(), unit()) * 0.2;
            let a = centre + DVec3::new(unit(), unit(), unit()) * 1e-4;
            let b = centre + DVec3::new(unit(), unit(), unit()) * 1e-4;
            let c = centre + DVec3::new(unit(), unit(), unit()) * 1e-4;
            let n = (b - a).cross(c - a).normalize_or_zero();
            let in_plane = a + (b - a) * unit() * 40.0 + (c - a) * unit() * 40.0;
            let p = match k % 3 {
                0 => DVec3::new(unit(), unit(), unit()) * 2.0,
                1 => in_plane + n * unit() * 1e-17,
                _ => in_plane,
            };
            let (det, bound) = orient3d_with_bound(a, b, c, p);
            let exact = orient3d_sign(a, b, c, p);
            if det.abs() > bound {
                assert_eq!(if det > 0.0 { 1 } else { -1 }, exact, "{k}");
            }
            if k % 3 == 0 && bound <= det.abs() / (1u64 << 40) as f64 {
                accurate_far += 1;
            }
            let dd = orient3d_double_double(a, b, c, p);
            assert!(
                exact == 0 || (dd != 0.0 && (dd > 0.0) == (exact > 0)),
                "{k}"
            );
        }
        assert!(accurate_far > 6_600, "{accurate_far}");
    }

    #[test]
    fn double_double_orientation_matches_the_exact_sign() {
        let a = DVec3::new(0.1, 0.2, 0.3);
        let b = DVec3::new(1.7, -0.4, 0.9);
        let c = DVec3::new(-0.3, 1.1, 0.2);
        for k in 0..1000 {
            let s = f64::from(k) / 1000.0;
            let p = a + s * (b - a) + (1.0 - s) * 0.5 * (c - a);
            let exact = orient3d_sign(a, b, c, p);
            let dd = orient3d_double_double(a, b, c, p);
            assert!(
                exact == 0 && dd.abs() < 1e-30 || (dd > 0.0) == (exact > 0),
                "{k}"
            );
        }
    }
}
