//! `intersect_triangle_triangle`: known configurations, every shared-corner case, an exact
//! separating-axis reference on small integer coordinates (where every degeneracy is
//! frequent), symmetry, and the procedural shapes, which must have no intersecting pair.

use haphe::DVec3;
use haphe::query::intersect_triangle_triangle;
use proptest::prelude::*;

use super::meshes::solids;

fn v(x: f64, y: f64, z: f64) -> DVec3 {
    DVec3::new(x, y, z)
}

/// The answer, checked to be the same for both argument orders and all corner orders
/// (rotations and reflections) of both triangles.
fn intersect(t1: [DVec3; 3], t2: [DVec3; 3]) -> bool {
    let first = intersect_triangle_triangle(t1, t2);
    let orders = [
        [0, 1, 2],
        [1, 2, 0],
        [2, 0, 1],
        [0, 2, 1],
        [2, 1, 0],
        [1, 0, 2],
    ];
    for o1 in orders {
        for o2 in orders {
            let (u1, u2) = (o1.map(|i| t1[i]), o2.map(|i| t2[i]));
            assert_eq!(intersect_triangle_triangle(u1, u2), first, "{u1:?} {u2:?}");
            assert_eq!(intersect_triangle_triangle(u2, u1), first, "{u2:?} {u1:?}");
        }
    }
    first
}

// ---------------------------------------------------------------------------------------
// Known configurations

const FLOOR: [DVec3; 3] = [
    DVec3::ZERO,
    DVec3::new(2.0, 0.0, 0.0),
    DVec3::new(0.0, 2.0, 0.0),
];

#[test]
fn without_shared_corners() {
    // Piercing, crossing, separated, above, beside.
    assert!(intersect(
        FLOOR,
        [v(0.5, 0.5, -1.), v(0.5, 0.5, 1.), v(3., 3., 0.5)]
    ));
    assert!(intersect(
        FLOOR,
        [v(-1., 0.5, -1.), v(3., 0.5, -1.), v(1., 0.5, 1.)]
    ));
    assert!(!intersect(
        FLOOR,
        [v(0., 0., 1.), v(1., 0., 1.), v(0., 1., 1.)]
    ));
    assert!(!intersect(
        FLOOR,
        [v(2., 2., -1.), v(2., 2., 1.), v(3., 1., 0.)]
    ));
    assert!(!intersect(
        FLOOR,
        [v(0.5, 0.5, 0.1), v(0.5, 0.5, 1.), v(1., 0.2, 0.5)]
    ));
}

#[test]
fn touching_counts_when_not_at_a_shared_corner() {
    // A corner on the face, on an edge, on a corner (equal positions are shared, so that
    // one is the one-shared-corner case below); an edge lying on the face; edges crossing.
    assert!(intersect(
        FLOOR,
        [v(0.5, 0.5, 0.), v(0.5, 0.5, 1.), v(1., 0., 1.)]
    ));
    assert!(intersect(
        FLOOR,
        [v(1., 0., 0.), v(1., -1., 1.), v(1., -1., -1.)]
    ));
    assert!(intersect(
        FLOOR,
        [v(0.2, 0.2, 0.), v(1., 0.5, 0.), v(0.5, 0.5, 1.)]
    ));
    assert!(intersect(
        FLOOR,
        [v(1., -1., 0.), v(1., 1., 0.), v(1., 0., 1.)]
    ));
    // Just apart.
    assert!(!intersect(
        FLOOR,
        [v(0.5, 0.5, 1e-300), v(0.5, 0.5, 1.), v(1., 0., 1.)]
    ));
    assert!(!intersect(
        FLOOR,
        [v(1., 1. + 1e-15, 0.), v(3., 3., 0.), v(3., 1.5, 0.)]
    ));
}

#[test]
fn coplanar_overlaps_containment_and_separation() {
    assert!(intersect(
        FLOOR,
        [v(1., 1., 0.), v(3., 1., 0.), v(1., 3., 0.)]
    ));
    assert!(intersect(
        FLOOR,
        [v(0.2, 0.2, 0.), v(0.5, 0.2, 0.), v(0.2, 0.5, 0.)]
    ));
    assert!(intersect(
        FLOOR,
        [v(-1., -1., 0.), v(5., -1., 0.), v(-1., 5., 0.)]
    ));
    // The star of David: no corner inside the other, only edges crossing.
    let up = [v(0., 0., 0.), v(6., 0., 0.), v(3., 5., 0.)];
    let down = [v(0., 3.4, 0.), v(3., -1.6, 0.), v(6., 3.4, 0.)];
    assert!(intersect(up, down));
    // Touching along part of an edge, at a corner on an edge.
    assert!(intersect(
        FLOOR,
        [v(0.5, 0., 0.), v(3., 0., 0.), v(1., -1., 0.)]
    ));
    assert!(intersect(
        FLOOR,
        [v(1., 1., 0.), v(3., 1., 0.), v(3., 3., 0.)]
    ));
    assert!(!intersect(
        FLOOR,
        [v(1.5, 1.5, 0.), v(3., 1., 0.), v(3., 3., 0.)]
    ));
}

#[test]
fn one_shared_corner() {
    let s = DVec3::ZERO;
    // Flat neighbours in a fan; a folded neighbour; bent away out of the plane.
    assert!(!intersect(FLOOR, [s, v(-1., 2., 0.), v(-2., 0., 0.)]));
    assert!(!intersect(FLOOR, [s, v(-1., 1., 0.), v(-1., -1., 0.)]));
    assert!(intersect(FLOOR, [s, v(1., 0.5, 0.), v(-1., 2., 0.)]));
    assert!(!intersect(FLOOR, [s, v(1., 1., 1.), v(-1., 1., 1.)]));
    // Coplanar, sharing the direction of an edge, or one inside the other's sector.
    assert!(intersect(FLOOR, [s, v(1., 0., 0.), v(1., -1., 0.)]));
    assert!(intersect(FLOOR, [s, v(0.5, 0.1, 0.), v(0.1, 0.5, 0.)]));
    // Not coplanar: an edge from s lying in the other's plane, inside or outside it.
    assert!(intersect(FLOOR, [s, v(0.5, 0.5, 0.), v(0., 0., 1.)]));
    assert!(!intersect(FLOOR, [s, v(-0.5, 0.5, 0.), v(0., 0., 1.)]));
    // The opposite edge piercing the other triangle.
    assert!(intersect(FLOOR, [s, v(1., 1., -1.), v(0.5, 0.5, 1.)]));
    // Above the face but for s; then with its opposite edge touching the face's edge.
    assert!(!intersect(FLOOR, [s, v(-1., 1., 1.), v(1., -1., 1.)]));
    assert!(intersect(
        FLOOR,
        [s, v(1., 1., 0.) + v(0., 0., -1.), v(1., 1., 1.)]
    ));
}

#[test]
fn two_shared_corners() {
    let (p, q) = (v(2., 0., 0.), v(0., 2., 0.));
    // Flat neighbours across the edge, bent at any angle, folded flat onto the face.
    assert!(!intersect(FLOOR, [p, v(2., 2., 0.), q]));
    assert!(!intersect(FLOOR, [p, v(2., 2., 1.), q]));
    assert!(!intersect(FLOOR, [p, v(0.5, 0.5, 1e-12), q]));
    assert!(intersect(FLOOR, [p, v(0.5, 0.5, 0.), q]));
    assert!(intersect(FLOOR, [p, v(1., -1., 0.), q]));
    // Collinear with the edge and extending beyond it: the overlap is the edge.
    assert!(!intersect(FLOOR, [p, v(3., -1., 0.), q]));
}

#[test]
fn three_shared_corners_are_the_same_triangle() {
    assert!(!intersect(FLOOR, FLOOR));
    assert!(!intersect(FLOOR, [FLOOR[0], FLOOR[2], FLOOR[1]]));
}

#[test]
fn degenerate_triangles_are_segments_and_points() {
    let segment = [v(0.5, 0.5, -1.), v(0.5, 0.5, 1.), v(0.5, 0.5, 0.25)];
    assert!(intersect(FLOOR, segment));
    assert!(!intersect(
        FLOOR,
        [v(0.5, 0.5, 0.1), v(0.5, 0.5, 1.), v(0.5, 0.5, 0.25)]
    ));
    assert!(intersect(FLOOR, [v(0.5, 0.5, 0.); 3]));
    assert!(!intersect(FLOOR, [v(5., 0.5, 0.); 3]));
    // A degenerate triangle sharing a corner: only its part beyond the corner counts.
    assert!(!intersect(
        FLOOR,
        [v(0., 0., 0.), v(-1., -1., 0.), v(-2., -2., 0.)]
    ));
    assert!(intersect(
        FLOOR,
        [v(0., 0., 0.), v(1., 1., 0.), v(-1., -1., 0.)]
    ));
    assert!(!intersect(
        FLOOR,
        [v(0., 0., 0.), v(0., 0., 1.), v(0., 0., 2.)]
    ));
    assert!(!intersect(FLOOR, [v(0., 0., 0.); 3]));
    // Sharing two corners with a segment along the edge, extending beyond or not.
    assert!(!intersect(
        FLOOR,
        [v(0., 0., 0.), v(2., 0., 0.), v(3., 0., 0.)]
    ));
    assert!(!intersect(
        FLOOR,
        [v(0., 0., 0.), v(2., 0., 0.), v(1., 0., 0.)]
    ));
    // Two degenerate triangles.
    let line = [v(0., 0., 0.), v(1., 1., 1.), v(2., 2., 2.)];
    assert!(intersect(
        line,
        [v(1., 1., 0.), v(1., 1., 5.), v(1., 1., 2.)]
    ));
    assert!(!intersect(
        line,
        [v(1., 0., 0.), v(1., 0., 5.), v(1., 0., 2.)]
    ));
    assert!(intersect(
        line,
        [v(2., 2., 2.), v(1.5, 1.5, 1.5), v(3., 3., 3.)]
    ));
    assert!(!intersect(
        line,
        [v(2., 2., 2.), v(2.5, 2.5, 2.5), v(3., 3., 3.)]
    ));
}

#[test]
fn non_finite_corners_give_false() {
    let bad = [v(f64::NAN, 0., 0.), v(1., 0., 0.), v(0., 1., 0.)];
    assert!(!intersect_triangle_triangle(FLOOR, bad));
    assert!(!intersect_triangle_triangle(bad, FLOOR));
    let huge = [v(1e300, 0., 0.), v(-1e300, 1e300, 0.), v(0., -1e300, 1e300)];
    let _ = intersect_triangle_triangle(huge, FLOOR);
}

// ---------------------------------------------------------------------------------------
// Exact reference: separating axes in i128

type P = [i128; 3];

fn sub(a: P, b: P) -> P {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn cross(a: P, b: P) -> P {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn dot(a: P, b: P) -> i128 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Whether the convex hulls of two point sets (integer coordinates up to about 2²⁶) are
/// disjoint: some axis separates them strictly. The axes tried include the normals of every
/// face and edge of the Minkowski difference and the directions between closest features,
/// whatever the dimensions of the hulls, so the test is exact.
fn hulls_disjoint(p: &[P], q: &[P]) -> bool {
    let within = |s: &[P]| {
        let mut out = Vec::new();
        for i in 0..s.len() {
            for j in i + 1..s.len() {
                out.push(sub(s[j], s[i]));
            }
        }
        out
    };
    let mut edges = within(p);
    edges.extend(within(q));
    let between: Vec<P> = p
        .iter()
        .flat_map(|&a| q.iter().map(move |&b| sub(b, a)))
        .collect();
    let mut normals = Vec::new();
    for i in 0..edges.len() {
        for j in i + 1..edges.len() {
            normals.push(cross(edges[i], edges[j]));
        }
    }
    let mut axes = normals.clone();
    axes.extend(&between);
    for &n in &normals {
        axes.extend(edges.iter().map(|&e| cross(n, e)));
    }
    for &e in &edges {
        axes.extend(between.iter().map(|&d| cross(e, cross(e, d))));
    }
    axes.iter().any(|&axis| {
        let (p_min, p_max) = p
            .iter()
            .map(|&x| dot(x, axis))
            .fold((i128::MAX, i128::MIN), |(lo, hi), d| (lo.min(d), hi.max(d)));
        let (q_min, q_max) = q
            .iter()
            .map(|&x| dot(x, axis))
            .fold((i128::MAX, i128::MIN), |(lo, hi), d| (lo.min(d), hi.max(d)));
        p_max < q_min || q_max < p_min
    })
}

/// `2^SHIFT`: corners are scaled by it, and the part of a triangle within `2^-SHIFT` (in
/// barycentric weight) of the shared corners is cut away. Small integer corners make the
/// intersection's vertices rationals with denominators far below `2^SHIFT`, so cutting
/// that thin part never loses a genuine intersection.
const SHIFT: u32 = 24;

/// The reference answer for triangles with integer coordinates in −2..=2.
fn reference(t1: [[i32; 3]; 3], t2: [[i32; 3]; 3]) -> Option<bool> {
    let scale = |c: [i32; 3]| c.map(|x| i128::from(x) << SHIFT);
    let shared: Vec<[i32; 3]> = {
        let mut s: Vec<[i32; 3]> = t1.iter().filter(|c| t2.contains(c)).copied().collect();
        s.dedup();
        s.sort();
        s.dedup();
        s
    };
    let proper = |t: [[i32; 3]; 3]| {
        let [a, b, c] = t.map(|c| c.map(i128::from));
        cross(sub(b, a), sub(c, a)) != [0; 3]
    };
    // The hull of a triangle with the shared corners pulled a hair toward the rest:
    // the triangle minus a thin neighbourhood of the shared corner or edge.
    let trimmed = |t: [[i32; 3]; 3]| -> Vec<P> {
        let own: Vec<[i32; 3]> = t.iter().filter(|c| !shared.contains(c)).copied().collect();
        let mut out: Vec<P> = own.iter().map(|&c| scale(c)).collect();
        for s in &shared {
            for o in &own {
                out.push(std::array::from_fn(|k| {
                    (i128::from(s[k]) << SHIFT) + i128::from(o[k] - s[k])
                }));
            }
        }
        out
    };
    match shared.len() {
        0 => Some(!hulls_disjoint(&t1.map(scale), &t2.map(scale))),
        1 | 2 if proper(t1) && proper(t2) => Some(
            !hulls_disjoint(&trimmed(t1), &t2.map(scale))
                || !hulls_disjoint(&t1.map(scale), &trimmed(t2)),
        ),
        3 if proper(t1) => Some(false),
        _ => None,
    }
}

fn small_corner() -> impl Strategy<Value = [i32; 3]> {
    [-2i32..=2, -2i32..=2, -2i32..=2]
}

/// Two triangles on the small lattice, the second often reusing corners of the first.
fn small_pair() -> impl Strategy<Value = ([[i32; 3]; 3], [[i32; 3]; 3])> {
    (
        [small_corner(), small_corner(), small_corner()],
        [small_corner(), small_corner(), small_corner()],
        [0usize..6, 0usize..6, 0usize..6],
    )
        .prop_map(|(t1, mut t2, reuse)| {
            for k in 0..3 {
                if reuse[k] < 3 {
                    t2[k] = t1[reuse[k]];
                }
            }
            (t1, t2)
        })
}

fn to_f64(t: [[i32; 3]; 3]) -> [DVec3; 3] {
    t.map(|c| DVec3::new(f64::from(c[0]), f64::from(c[1]), f64::from(c[2])))
}

fn point(range: f64) -> impl Strategy<Value = DVec3> {
    (-range..range, -range..range, -range..range).prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2048))]

    /// On a 5×5×5 lattice, coplanar, collinear, touching and shared-corner configurations
    /// are common; the answer must match the separating-axis reference exactly and be
    /// symmetric and independent of corner order.
    #[test]
    fn small_lattice_matches_the_reference((t1, t2) in small_pair(), offset in point(1e3)) {
        let got = intersect(to_f64(t1), to_f64(t2));
        if let Some(expected) = reference(t1, t2) {
            prop_assert_eq!(got, expected, "{:?} {:?}", t1, t2);
        }
        // A translation by a common exact offset (a multiple of 2^-10) changes nothing.
        let offset = (offset * 1024.0).round() / 1024.0;
        let moved = |t: [[i32; 3]; 3]| to_f64(t).map(|c| c + offset);
        prop_assert_eq!(intersect_triangle_triangle(moved(t1), moved(t2)), got);
    }

    /// A triangle and a copy moved along its normal never meet; moved within its plane by
    /// less than its size they always do. Corners are multiples of 2⁻¹⁰ and the moves
    /// exact, so the copies are exactly parallel or coplanar.
    #[test]
    fn translated_copies(
        corners in [small_corner(), small_corner(), small_corner()],
        scale in 1i32..1000,
        lift in 1i32..64,
        s in -16i32..=16,
        t in -16i32..=16,
    ) {
        let tri = to_f64(corners).map(|c| c * f64::from(scale) / 1024.0);
        let [a, b, c] = tri;
        let n = (b - a).cross(c - a);
        prop_assume!(n != DVec3::ZERO && (s, t) != (0, 0));
        let up = tri.map(|x| x + n * f64::from(lift) / 64.0);
        prop_assert!(!intersect(tri, up));
        let shift = (b - a) * f64::from(s) / 64.0 + (c - a) * f64::from(t) / 64.0;
        let moved = tri.map(|x| x + shift);
        prop_assert_eq!(intersect_triangle_triangle(tri, moved), true);
    }

    /// Random triangles in general position: symmetric and independent of corner order,
    /// and a float copy moved clearly along the normal never meets the original.
    #[test]
    fn general_position(t1 in [point(1.0), point(1.0), point(1.0)], t2 in [point(1.0), point(1.0), point(1.0)], lift in 1e-6f64..1.0) {
        let _ = intersect(t1, t2);
        let [a, b, c] = t1;
        let n = (b - a).cross(c - a);
        prop_assume!(n.length() > 1e-3);
        prop_assert!(!intersect(t1, t1.map(|x| x + lift * n.normalize())));
    }
}

// ---------------------------------------------------------------------------------------
// Meshes

#[test]
fn no_pair_of_a_procedural_shape_intersects() {
    for solid in solids() {
        let mesh = &solid.mesh;
        let n = mesh.triangles.len();
        for i in 0..n {
            for j in i + 1..n {
                assert!(
                    !intersect_triangle_triangle(mesh.corners(i), mesh.corners(j)),
                    "{}: triangles {i} and {j}",
                    solid.name
                );
            }
        }
    }
}

#[test]
fn neighbours_bent_onto_each_other_do_intersect() {
    // On every edge of the dyadic box, a triangle folded flat onto one of the edge's two
    // triangles (third corner halfway toward that triangle's third corner, so exactly in
    // its plane, on its side): reported.
    let solid = &solids()[2];
    assert!(solid.dyadic);
    let mut count = 0;
    for (&(p, q), pair) in &solid.edges {
        let t0 = pair[0];
        let third = |t: usize| {
            solid.mesh.triangles[t]
                .into_iter()
                .find(|&x| x != p && x != q)
                .map(|x| solid.mesh.vertices[x as usize])
                .expect("a triangle has a corner off its edge")
        };
        let (a, b) = (
            solid.mesh.vertices[p as usize],
            solid.mesh.vertices[q as usize],
        );
        let folded = [a, b, (a + b) / 2.0 + (third(t0) - (a + b) / 2.0) / 2.0];
        assert!(intersect(solid.mesh.corners(t0), folded), "triangle {t0}");
        count += 1;
    }
    assert!(count > 0);
}
