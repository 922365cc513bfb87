//! `closest_point_triangle` against its optimality conditions and a plain reference, over
//! random, near-degenerate and degenerate triangles.

use haphe::DVec3;
use haphe::mesh::{TriFrame, relative_height};
use haphe::query::{ClosestPoint, Feature, closest_point_triangle};
use proptest::prelude::*;

/// The plain reference: the projection onto the plane when it falls inside the triangle,
/// else the nearest of the three clamped edge projections. Returns the distance, metres.
fn reference_distance(p: DVec3, [a, b, c]: [DVec3; 3]) -> f64 {
    let on_edge = |from: DVec3, to: DVec3| {
        let e = to - from;
        let s = if e.length_squared() > 0.0 {
            (e.dot(p - from) / e.length_squared()).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (p - (from + s * e)).length()
    };
    let edges = on_edge(a, b).min(on_edge(b, c)).min(on_edge(c, a));
    let frame = TriFrame::new(a, b, c);
    if !frame.is_degenerate() && frame.barycentric(p).iter().all(|&w| w >= 0.0) {
        edges.min(frame.height(p).abs())
    } else {
        edges
    }
}

/// The tolerances of a check on triangle `tri` and query `p`, metres: rounding grows with
/// the size of the numbers and, for the face, with `1 / relative height`; a triangle taken
/// as degenerate is off by at most its smallest altitude.
fn tolerance(p: DVec3, tri: [DVec3; 3], found: &ClosestPoint) -> f64 {
    let [a, b, c] = tri;
    let size = (b - a).length().max((c - b).length()).max((a - c).length());
    let reach = size + (p - found.point).length() + p.length() + a.length();
    let height = relative_height(a, b, c);
    let rounding = 1e-14 * reach / height.max(1e-9);
    rounding + 2.0 * height.min(1e-9) * size
}

/// Checks every property of one answer; `Err` describes the first that fails.
fn check(p: DVec3, tri: [DVec3; 3]) -> Result<ClosestPoint, String> {
    let found = closest_point_triangle(p, tri);
    let tol = tolerance(p, tri, &found);
    let context = || format!("p = {p}, tri = {tri:?}, found = {found:?}, tol = {tol:e}");
    let w = found.weights;
    if !w.iter().all(|&x| (0.0..=1.0).contains(&x)) || (w.iter().sum::<f64>() - 1.0).abs() > 1e-15 {
        return Err(format!("weights: {}", context()));
    }
    let rebuilt = w[0] * tri[0] + w[1] * tri[1] + w[2] * tri[2];
    if (rebuilt - found.point).length() > tol {
        return Err(format!("weights do not rebuild the point: {}", context()));
    }
    // Optimality for a convex set: (p − q)·(x − q) ≤ 0 for every corner x; moving q by δ
    // changes the product by at most δ (|x − q| + |p − q|) + δ².
    let to_p = p - found.point;
    for x in tri {
        if to_p.dot(x - found.point) > tol * ((x - found.point).length() + to_p.length() + tol) {
            return Err(format!("not optimal toward corner {x}: {}", context()));
        }
    }
    let reference = reference_distance(p, tri);
    if (to_p.length() - reference).abs() > tol {
        return Err(format!(
            "distance {} vs reference {reference}: {}",
            to_p.length(),
            context()
        ));
    }
    // The label agrees with the weights and with the local optimality condition.
    let ok = match found.feature {
        Feature::Vertex(i) => w[usize::from(i)] == 1.0 && found.point == tri[usize::from(i)],
        Feature::Edge(i) => {
            let i = usize::from(i);
            let (j, k) = ((i + 1) % 3, (i + 2) % 3);
            let edge = (tri[k] - tri[j]).normalize();
            w[i] == 0.0 && w[j] > 0.0 && w[k] > 0.0 && to_p.dot(edge).abs() <= tol
        }
        Feature::Face => {
            let [a, b, c] = tri;
            let n = (b - a).cross(c - a).normalize();
            (to_p - to_p.dot(n) * n).length() <= tol
        }
    };
    if ok {
        Ok(found)
    } else {
        Err(format!("feature label: {}", context()))
    }
}

fn point(range: f64) -> impl Strategy<Value = DVec3> {
    (-range..range, -range..range, -range..range).prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

/// Triangles of every kind: general, slivers of relative height down to 1e-15, exactly
/// collinear (dyadic corners), with coincident corners, and a single point.
fn triangle() -> impl Strategy<Value = [DVec3; 3]> {
    prop_oneof![
        4 => [point(1.0), point(1.0), point(1.0)],
        3 => (point(1.0), point(1.0), -0.5f64..1.5, point(1.0), -15.0f64..-1.0).prop_map(
            |(a, b, s, offset, exponent)| [a, b, a + s * (b - a) + 10f64.powf(exponent) * offset]
        ),
        1 => (-64i32..64, -64i32..64, 0i32..4).prop_map(|(x, y, k)| {
            let a = DVec3::new(f64::from(x), f64::from(y), 1.0) / 64.0;
            let b = a + DVec3::new(1.0, -2.0, 0.5) / 8.0;
            let m = a + (b - a) * f64::from(k) / 2.0;
            [a, m, b]
        }),
        1 => (point(1.0), point(1.0), 0usize..3).prop_map(|(a, b, k)| {
            let mut t = [a, a, a];
            t[k] = b;
            t
        }),
        1 => point(1.0).prop_map(|a| [a, a, a]),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(4096))]

    #[test]
    fn optimal_and_consistent_for_every_triangle(tri in triangle(), p in point(2.0)) {
        let result = check(p, tri);
        prop_assert!(result.is_ok(), "{}", result.unwrap_err());
    }

    /// Points on the triangle (from barycentric weights) are their own closest point.
    #[test]
    fn points_on_the_triangle_are_fixed(tri in triangle(), u in 0.0f64..1.0, v in 0.0f64..1.0) {
        let (u, v) = if u + v > 1.0 { (1.0 - u, 1.0 - v) } else { (u, v) };
        let p = tri[0] + u * (tri[1] - tri[0]) + v * (tri[2] - tri[0]);
        let found = check(p, tri);
        prop_assert!(found.is_ok(), "{}", found.as_ref().unwrap_err());
        let found = found.expect("checked");
        prop_assert!((found.point - p).length() <= tolerance(p, tri, &found), "{:?}", found);
    }

    /// Points pushed off a chosen feature of a well-shaped triangle along a direction in its
    /// normal cone come back to that feature, with that label.
    #[test]
    fn labels_name_the_voronoi_region(
        tri in [point(1.0), point(1.0), point(1.0)],
        feature in 0usize..7,
        s in 0.05f64..0.95,
        t in 0.05f64..0.95,
        lift in -1.0f64..1.0,
        push in 0.01f64..1.0,
    ) {
        let [a, b, c] = tri;
        prop_assume!(relative_height(a, b, c) > 0.05);
        let n = (b - a).cross(c - a).normalize();
        let outward_of_edge = |from: DVec3, to: DVec3, third: DVec3| {
            let e = (to - from).normalize();
            let away = (from - third) - (from - third).dot(e) * e;
            (away - away.dot(n) * n).normalize()
        };
        let (p, expected_point, expected) = match feature {
            0..=2 => {
                let corner = tri[feature];
                let (j, k) = (tri[(feature + 1) % 3], tri[(feature + 2) % 3]);
                // Inside the normal cone: a combination of the two edge normals at the
                // corner and the face normal.
                let cone = s * outward_of_edge(corner, j, k) + (1.0 - s) * outward_of_edge(corner, k, j);
                (corner + push * cone + lift * push * n, corner, Feature::Vertex(feature as u8))
            }
            3..=5 => {
                let i = feature - 3;
                let (j, k) = (tri[(i + 1) % 3], tri[(i + 2) % 3]);
                let on = j + s * (k - j);
                let out = outward_of_edge(j, k, tri[i]);
                (on + push * out + lift * push * n, on, Feature::Edge(i as u8))
            }
            _ => {
                let (s, t) = if s + t > 1.0 { (1.0 - s, 1.0 - t) } else { (s, t) };
                let on = a + s * (b - a) + t * (c - a);
                (on + lift * n, on, Feature::Face)
            }
        };
        let found = check(p, tri);
        prop_assert!(found.is_ok(), "{}", found.as_ref().unwrap_err());
        let found = found.expect("checked");
        prop_assert_eq!(found.feature, expected);
        prop_assert!((found.point - expected_point).length() < 1e-12, "{:?} vs {}", found, expected_point);
    }
}

#[test]
fn non_finite_queries_do_not_panic() {
    let tri = [DVec3::ZERO, DVec3::X, DVec3::Y];
    for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, f64::MAX] {
        let _ = closest_point_triangle(DVec3::splat(bad), tri);
        let _ = closest_point_triangle(DVec3::ZERO, [DVec3::splat(bad), DVec3::X, DVec3::Y]);
    }
}
