//! The watertight segment–triangle test: hits, misses and their parameters, every
//! dominant axis, degenerate input, and shared edges and vertices reported once.

use proptest::prelude::*;

use super::*;

const A: DVec3 = DVec3::new(0.0, 0.0, 0.0);
const B: DVec3 = DVec3::new(1.0, 0.0, 0.0);
const C: DVec3 = DVec3::new(0.0, 1.0, 0.0);

fn hit(p0: DVec3, p1: DVec3, tri: [DVec3; 3]) -> Option<SegmentHit> {
    intersect_segment_triangle(&Segment::new(p0, p1), tri)
}

#[test]
fn front_hit_enters_with_weights_and_parameter() {
    let h = hit(
        DVec3::new(0.25, 0.5, 2.0),
        DVec3::new(0.25, 0.5, -2.0),
        [A, B, C],
    )
    .expect("hit");
    assert_eq!(h.t, 0.5);
    assert!(h.entering);
    assert_eq!(h.weights, [0.25, 0.25, 0.5]);
}

#[test]
fn back_hit_leaves() {
    let h = hit(
        DVec3::new(0.25, 0.5, -1.0),
        DVec3::new(0.25, 0.5, 3.0),
        [A, B, C],
    )
    .expect("hit");
    assert_eq!(h.t, 0.25);
    assert!(!h.entering);
    assert_eq!(h.weights, [0.25, 0.25, 0.5]);
}

#[test]
fn every_dominant_axis_and_sign_agrees() {
    // The same crossing, the triangle and segment rotated through the axes and
    // mirrored, must give the same answer with every permutation of the shear.
    let tri = [
        DVec3::new(0.1, -0.3, 0.2),
        DVec3::new(0.9, 0.1, -0.1),
        DVec3::new(-0.2, 0.8, 0.3),
    ];
    let (p0, p1) = (DVec3::new(0.2, 0.2, 1.5), DVec3::new(0.3, 0.1, -1.0));
    let reference = hit(p0, p1, tri).expect("hit");
    let rotate = |v: DVec3, k: usize| match k {
        0 => v,
        1 => DVec3::new(v.z, v.x, v.y),
        _ => DVec3::new(v.y, v.z, v.x),
    };
    for k in 0..3 {
        let t = tri.map(|v| rotate(v, k));
        let h = hit(rotate(p0, k), rotate(p1, k), t).expect("rotated hit");
        assert!((h.t - reference.t).abs() < 1e-14);
        assert_eq!(h.entering, reference.entering);
        let back = hit(rotate(p1, k), rotate(p0, k), t).expect("reversed hit");
        assert!((back.t - (1.0 - reference.t)).abs() < 1e-14);
        assert_eq!(back.entering, !reference.entering);
        for i in 0..3 {
            assert!((h.weights[i] - reference.weights[i]).abs() < 1e-14);
            assert!((back.weights[i] - reference.weights[i]).abs() < 1e-14);
        }
    }
}

#[test]
fn end_points_on_the_plane_give_t_zero_and_one() {
    let start = hit(
        DVec3::new(0.2, 0.2, 0.0),
        DVec3::new(0.2, 0.2, -1.0),
        [A, B, C],
    );
    assert_eq!(start.map(|h| h.t), Some(0.0));
    let end = hit(
        DVec3::new(0.2, 0.2, 1.0),
        DVec3::new(0.2, 0.2, 0.0),
        [A, B, C],
    );
    assert_eq!(end.map(|h| h.t), Some(1.0));
}

#[test]
fn misses_short_segments_and_points_beside_the_triangle() {
    // Stops short of the plane, starts past it, passes beside the triangle.
    assert!(
        hit(
            DVec3::new(0.2, 0.2, 2.0),
            DVec3::new(0.2, 0.2, 0.5),
            [A, B, C]
        )
        .is_none()
    );
    assert!(
        hit(
            DVec3::new(0.2, 0.2, -0.5),
            DVec3::new(0.2, 0.2, -2.0),
            [A, B, C]
        )
        .is_none()
    );
    assert!(
        hit(
            DVec3::new(0.6, 0.6, 1.0),
            DVec3::new(0.6, 0.6, -1.0),
            [A, B, C]
        )
        .is_none()
    );
    assert!(
        hit(
            DVec3::new(-0.1, 0.2, 1.0),
            DVec3::new(-0.1, 0.2, -1.0),
            [A, B, C]
        )
        .is_none()
    );
}

#[test]
fn parallel_and_in_plane_segments_never_hit() {
    assert!(
        hit(
            DVec3::new(-1.0, 0.2, 0.5),
            DVec3::new(2.0, 0.2, 0.5),
            [A, B, C]
        )
        .is_none()
    );
    assert!(
        hit(
            DVec3::new(-1.0, 0.2, 0.0),
            DVec3::new(2.0, 0.2, 0.0),
            [A, B, C]
        )
        .is_none()
    );
    assert!(
        hit(
            DVec3::new(0.1, 0.1, 0.0),
            DVec3::new(0.2, 0.3, 0.0),
            [A, B, C]
        )
        .is_none()
    );
}

#[test]
fn degenerate_and_non_finite_input_never_hits_nor_panics() {
    let p = DVec3::new(0.2, 0.2, 0.0);
    assert!(Segment::new(p, p).is_degenerate());
    assert!(hit(p, p, [A, B, C]).is_none());
    let nan = DVec3::new(f64::NAN, 0.0, 0.0);
    let inf = DVec3::new(0.0, f64::INFINITY, 0.0);
    for bad in [nan, inf, -inf] {
        assert!(hit(bad, DVec3::new(0.2, 0.2, -1.0), [A, B, C]).is_none());
        assert!(hit(DVec3::new(0.2, 0.2, 1.0), bad, [A, B, C]).is_none());
        let down = (DVec3::new(0.2, 0.2, 1.0), DVec3::new(0.2, 0.2, -1.0));
        assert!(hit(down.0, down.1, [bad, B, C]).is_none());
        assert!(hit(down.0, down.1, [A, bad, C]).is_none());
        assert!(hit(down.0, down.1, [A, B, bad]).is_none());
    }
    let huge = 1e300;
    let big = [A * huge, B * huge, C * huge];
    assert!(
        hit(
            DVec3::new(0.2, 0.2, 1.0) * huge,
            DVec3::new(0.2, 0.2, -1.0) * huge,
            big
        )
        .is_none_or(|h| h.t.is_finite() && h.weights.iter().all(|w| w.is_finite()))
    );
    // A degenerate triangle is seen edge-on from every direction: no hit.
    let line = [A, B, 2.0 * B];
    assert!(hit(DVec3::new(0.5, 0.0, 1.0), DVec3::new(0.5, 0.0, -1.0), line).is_none());
}

#[test]
fn a_shared_edge_is_reported_once() {
    // Two triangles of the unit square sharing the diagonal B–C, the segment straight
    // down through its midpoint, and through its end points.
    let d = DVec3::new(1.0, 1.0, 0.0);
    let (first, second) = ([A, B, C], [B, d, C]);
    for x in [DVec3::new(0.5, 0.5, 0.0), B, C] {
        let (p0, p1) = (x + DVec3::Z, x - DVec3::Z);
        let count = [first, second]
            .into_iter()
            .filter(|&t| hit(p0, p1, t).is_some())
            .count();
        assert!(count <= 1, "{x}: {count}");
    }
    let mid = DVec3::new(0.5, 0.5, 0.0);
    let hits = [first, second].map(|t| hit(mid + DVec3::Z, mid - DVec3::Z, t).is_some());
    assert_eq!(hits.iter().filter(|&&h| h).count(), 1);
}

#[test]
fn ties_go_where_the_documented_perturbation_puts_the_point() {
    // Dyadic corners, points and directions whose other components are power-of-two
    // fractions of the largest: every sheared coordinate is exact, so a segment through
    // a vertex or an edge point has edge functions exactly 0 and only the tie-break
    // decides. The owner must be the triangle hit by the same segment moved by
    // (−δ, −δ²) in the sheared frame (a move with no kz component keeps the shear).
    let ring = [
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(0.5, 1.0, 0.25),
        DVec3::new(-0.5, 1.0, 0.0),
        DVec3::new(-1.0, 0.0, -0.25),
        DVec3::new(-0.5, -1.0, 0.125),
        DVec3::new(0.5, -1.0, 0.0),
    ];
    let fan: Vec<[DVec3; 3]> = (0..6).map(|k| [A, ring[k], ring[(k + 1) % 6]]).collect();
    let delta = 1e-7;
    let mut single = 0;
    for through in [A, ring[2] * 0.5, ring[5] * 0.25, (ring[0] + ring[1]) * 0.5] {
        for (i, j, k) in [
            (1, 2, 4),
            (0, 0, 1),
            (-1, 0, 2),
            (0, -2, 1),
            (1, 1, -4),
            (2, -1, -1),
            (4, 1, -2),
            (-1, -1, -1),
            (0, 1, 0),
        ] {
            let d = DVec3::new(f64::from(i), f64::from(j), f64::from(k)) / 8.0;
            let segment = Segment::new(through + d, through - d);
            let mut shift = [0.0; 3];
            shift[segment.kx as usize] = -delta;
            shift[segment.ky as usize] = -delta * delta;
            let shift = DVec3::from_array(shift);
            let moved = Segment::new(segment.p0 + shift, segment.p1 + shift);
            let hits = |s: &Segment| -> Vec<usize> {
                (0..6)
                    .filter(|&t| intersect_segment_triangle(s, fan[t]).is_some())
                    .collect()
            };
            assert_eq!(hits(&segment), hits(&moved), "through {through} along {d}");
            single += usize::from(hits(&segment).len() == 1);
        }
    }
    assert!(single >= 24, "{single}");
}

#[test]
fn a_vertex_in_a_flat_fan_is_reported_once() {
    // Six triangles around the origin, every segment direction through it.
    let ring: Vec<DVec3> = (0..6)
        .map(|k| {
            let (s, c) = (f64::from(k) * std::f64::consts::FRAC_PI_3).sin_cos();
            DVec3::new(c, s, 0.0)
        })
        .collect();
    let fan: Vec<[DVec3; 3]> = (0..6).map(|k| [A, ring[k], ring[(k + 1) % 6]]).collect();
    for dir in [
        DVec3::Z,
        DVec3::new(0.5, 0.0, 1.0),
        DVec3::new(0.0, -0.25, 1.0),
        DVec3::new(0.3, 0.7, 0.2),
        DVec3::new(-1.0, -1.0, 1.0),
    ] {
        for sign in [1.0, -1.0] {
            let (p0, p1) = (A + sign * dir, A - sign * dir);
            let hits: Vec<SegmentHit> = fan.iter().filter_map(|&t| hit(p0, p1, t)).collect();
            assert_eq!(hits.len(), 1, "{dir} {sign}");
            assert_eq!(hits[0].entering, sign > 0.0);
        }
    }
}

#[test]
fn the_exact_edge_sign_is_the_sign_of_the_sheared_edge_function() {
    // Generic configurations, every dominant axis and direction: where the f64 edge
    // function is far from 0, the exact path must give its sign.
    let mut random = crate::rng::SplitMix64::new(5);
    let mut checked = 0;
    for _ in 0..2000 {
        let p0 = random.point_in(DVec3::splat(-1.0), DVec3::splat(1.0));
        let p1 = random.point_in(DVec3::splat(-1.0), DVec3::splat(1.0));
        let (p, q) = (
            random.point_in(DVec3::splat(-1.0), DVec3::splat(1.0)),
            random.point_in(DVec3::splat(-1.0), DVec3::splat(1.0)),
        );
        let segment = Segment::new(p0, p1);
        let (px, py, _) = segment.shear(p);
        let (qx, qy, _) = segment.shear(q);
        let e = qx * py - qy * px;
        if e.abs() > 1e-9 {
            assert_eq!(segment.exact_edge_sign(p, q), certain_sign(e, 0.0));
            assert_eq!(segment.exact_edge_sign(q, p), -certain_sign(e, 0.0));
            checked += 1;
        }
    }
    assert!(checked > 1900, "{checked}");
}

/// The framed test, as the map's queries call it: with the triangle's frame, and the
/// prepared segment only when the whole test runs.
fn framed(p0: DVec3, p1: DVec3, tri: [DVec3; 3]) -> Option<SegmentHit> {
    let [a, b, c] = tri;
    intersect_segment_framed(p0, p1, tri, &TriFrame::new(a, b, c), || {
        Segment::new(p0, p1)
    })
}

/// The framed test gives the plain one's answer: the same decision, the same parameter
/// to the bit, the same side, and weights equal up to rounding.
fn check_framed(p0: DVec3, p1: DVec3, tri: [DVec3; 3]) -> Result<(), String> {
    let context = || format!("{p0:?} → {p1:?}, triangle {tri:?}");
    match (hit(p0, p1, tri), framed(p0, p1, tri)) {
        (None, None) => Ok(()),
        (Some(plain), Some(fast)) => {
            if plain.t.to_bits() != fast.t.to_bits() || plain.entering != fast.entering {
                return Err(format!("{plain:?} ≠ {fast:?}: {}", context()));
            }
            let apart = (0..3)
                .map(|k| (plain.weights[k] - fast.weights[k]).abs())
                .fold(0.0, f64::max);
            if apart > 1e-9 {
                return Err(format!(
                    "weights {apart:e} apart, {plain:?} {fast:?}: {}",
                    context()
                ));
            }
            Ok(())
        }
        (plain, fast) => Err(format!("plain {plain:?}, framed {fast:?}: {}", context())),
    }
}

#[test]
fn the_framed_test_agrees_on_hand_picked_cases() {
    let tri = [A, B, C];
    let down = |x: f64, y: f64| (DVec3::new(x, y, 1.0), DVec3::new(x, y, -1.0));
    let cases = [
        down(0.2, 0.2),                                          // well inside: the fast path
        down(0.5, 0.5),                                          // on the long edge: the whole test
        down(0.0, 0.0),                                          // through a corner
        down(0.0, 0.3),                                          // on an edge
        down(-0.1, 0.3),                                         // beside an edge
        down(0.5 + 1e-12, 0.5), // a hair outside, within the frame's margin
        (DVec3::new(0.2, 0.2, 1.0), DVec3::new(0.2, 0.2, 0.0)), // ending on the plane
        (DVec3::new(0.2, 0.2, 0.0), DVec3::new(0.2, 0.2, 1.0)), // starting on it
        (DVec3::new(0.2, 0.2, 1.0), DVec3::new(0.2, 0.2, 0.5)), // short of it
        (DVec3::new(-1.0, 0.2, 0.0), DVec3::new(1.0, 0.2, 0.0)), // in the plane
        (DVec3::new(-1.0, 0.2, 1e-300), DVec3::new(1.0, 0.2, -1e-300)), // nearly in it
        // A direction too short for its reciprocal: the whole test takes no such segment.
        (DVec3::new(0.2, 0.2, 1e-310), DVec3::new(0.2, 0.2, -1e-310)),
        (DVec3::new(0.2, 0.2, 1.0), DVec3::new(0.2, 0.2, 1.0)), // zero length
        (DVec3::new(0.2, 0.2, f64::NAN), DVec3::new(0.2, 0.2, -1.0)),
        (
            DVec3::new(0.2, 0.2, 1.0),
            DVec3::new(0.2, f64::INFINITY, -1.0),
        ),
    ];
    for (p0, p1) in cases {
        check_framed(p0, p1, tri).unwrap();
        check_framed(p1, p0, tri).unwrap();
    }
    assert!(framed(down(0.2, 0.2).0, down(0.2, 0.2).1, tri).is_some());
    // A degenerate triangle has a zero frame: never hit, by either test.
    let line = [A, B, 2.0 * B];
    let (p0, p1) = down(0.5, 0.0);
    assert_eq!(framed(p0, p1, line), None);
    check_framed(p0, p1, line).unwrap();
}

/// A triangle for the framed test's properties: corners in a cube of side `10^scale`
/// around `centre`, or a sliver (its third corner a hair off the line of the other two).
fn any_triangle() -> impl Strategy<Value = [DVec3; 3]> {
    let corner = || prop::array::uniform3(-1.0..1.0f64).prop_map(DVec3::from_array);
    (
        corner(),
        corner(),
        corner(),
        0.0..1.0f64,
        -9.0..-1.0f64,
        -3.0..1.0f64,
        corner(),
    )
        .prop_map(|(a, b, c, along, thin, scale, centre)| {
            let c = if thin < -5.0 {
                c
            } else {
                a + along * (b - a) + c * 10f64.powf(thin)
            };
            let s = 10f64.powf(scale);
            [a, b, c].map(|p| p * s + centre * 10.0)
        })
}

/// A segment against `tri`: through a point of its plane given by weights (a corner, an
/// edge point or any point, inside or outside), in any direction or one nearly in the
/// plane, crossing it, ending on it or stopping short.
fn any_segment_against(tri: [DVec3; 3]) -> impl Strategy<Value = (DVec3, DVec3)> {
    let weights = prop_oneof![
        Just([1.0, 0.0, 0.0]),
        Just([0.0, 1.0, 0.0]),
        Just([0.5, 0.5, 0.0]),
        Just([0.0, 0.25, 0.75]),
        (-0.3..1.3f64, -0.3..1.3f64).prop_map(|(u, v)| [1.0 - u - v, u, v]),
        (0.0..1.0f64, 0.0..1.0f64).prop_map(|(u, v)| {
            let (u, v) = if u + v > 1.0 {
                (1.0 - u, 1.0 - v)
            } else {
                (u, v)
            };
            [1.0 - u - v, u, v]
        }),
    ];
    let direction = prop::array::uniform3(-1.0..1.0f64).prop_map(DVec3::from_array);
    (
        weights,
        direction,
        -14.0..0.0f64,
        0.0..1.0f64,
        -0.5..1.5f64,
        0..4u8,
    )
        .prop_map(move |(w, dir, tilt, lift, reach, kind)| {
            let [a, b, c] = tri;
            let on = w[0] * a + w[1] * b + w[2] * c;
            let size = (b - a).length().max((c - a).length());
            let normal = (b - a).cross(c - a).normalize_or_zero();
            let dir = match kind {
                // Nearly in the plane: tilted out of it by 10^tilt.
                0 => (dir - normal * dir.dot(normal)) + normal * 10f64.powf(tilt),
                _ => dir,
            } * size;
            let start = on + dir * (0.1 + lift);
            match kind {
                2 => (start, on),                       // ends on the plane
                3 => (start, on + dir * (reach - 1.0)), // may stop short or cross
                _ => (start, on - dir * (0.1 + reach.abs())),
            }
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(4096))]

    #[test]
    fn the_framed_test_gives_the_watertight_answer(
        (tri, (p0, p1)) in any_triangle()
            .prop_flat_map(|tri| (Just(tri), any_segment_against(tri)))
    ) {
        check_framed(p0, p1, tri).map_err(TestCaseError::fail)?;
        check_framed(p1, p0, tri).map_err(TestCaseError::fail)?;
    }
}
