//! Watertightness of `intersect_segment_triangle` on closed meshes: a segment crossing the
//! surface through a vertex or an edge is reported by exactly one triangle, grazing
//! segments by zero or two, and the signed number of hits always equals the change of
//! winding number between the end points.

use haphe::DVec3;
use haphe::query::{Segment, SegmentHit};
use proptest::prelude::*;
use robust::{Coord3D, orient3d};

use super::meshes::{Solid, signed, solids};

/// End points closer than this to the surface are skipped: their winding number is not a
/// clear 0 or 1 and whether they count as crossing is a matter of rounding (metres).
const ON_SURFACE_M: f64 = 1e-12;

fn coord(p: DVec3) -> Coord3D<f64> {
    Coord3D {
        x: p.x,
        y: p.y,
        z: p.z,
    }
}

/// How the segment `p0 → p1` crosses the plane of `tri`, exactly: `1` or `−1` for the two
/// directions when the end points lie strictly on opposite sides, `0` otherwise.
fn crossing_side([a, b, c]: [DVec3; 3], p0: DVec3, p1: DVec3) -> i8 {
    let o0 = orient3d(coord(a), coord(b), coord(c), coord(p0));
    let o1 = orient3d(coord(a), coord(b), coord(c), coord(p1));
    if o0 > 0.0 && o1 < 0.0 {
        1
    } else if o0 < 0.0 && o1 > 0.0 {
        -1
    } else {
        0
    }
}

/// The hits of `segment` among `triangles`.
fn hits_among(solid: &Solid, segment: &Segment, triangles: &[usize]) -> Vec<(usize, SegmentHit)> {
    solid
        .hits(segment)
        .into_iter()
        .filter(|(t, _)| triangles.contains(t))
        .collect()
}

/// Whether the segment crosses every triangle of `triangles` (planes) strictly and in the
/// same direction: then, around a vertex or an edge of a closed surface that the segment
/// passes through, it crosses the surface transversally there.
fn transversal(solid: &Solid, triangles: &[usize], p0: DVec3, p1: DVec3) -> bool {
    let sides: Vec<i8> = triangles
        .iter()
        .map(|&t| crossing_side(solid.mesh.corners(t), p0, p1))
        .collect();
    sides[0] != 0 && sides.iter().all(|&s| s == sides[0])
}

/// The checks every segment through a vertex fan or an edge pair must pass; `Err` with a
/// description when one fails, `Ok(false)` when the end points are too close to the
/// surface to judge.
fn check_local_crossing(
    solid: &Solid,
    local: &[usize],
    p0: DVec3,
    p1: DVec3,
) -> Result<bool, String> {
    if solid.distance(p0) < ON_SURFACE_M || solid.distance(p1) < ON_SURFACE_M {
        return Ok(false);
    }
    let segment = Segment::new(p0, p1);
    let all = solid.hits(&segment);
    let here = hits_among(solid, &segment, local);
    let expected = solid.winding(p1) - solid.winding(p0);
    let context = || format!("{}: {p0} → {p1}, local {local:?}, hits {all:?}", solid.name);
    if signed(&all) != expected {
        return Err(format!(
            "signed count {} ≠ winding change {expected}: {}",
            signed(&all),
            context()
        ));
    }
    if (all.len() as i64 - expected).rem_euclid(2) != 0 {
        return Err(format!(
            "parity of {} hits ≠ winding change: {}",
            all.len(),
            context()
        ));
    }
    if transversal(solid, local, p0, p1) {
        if here.len() != 1 {
            return Err(format!(
                "transversal crossing reported {} times: {}",
                here.len(),
                context()
            ));
        }
    } else if signed(&here).abs() > 1 || (here.len() as i64 - signed(&here)).rem_euclid(2) != 0 {
        return Err(format!("inconsistent local hits {here:?}: {}", context()));
    }
    Ok(true)
}

/// Directions with dyadic components: the 26 of the unit cube and 48 of the form
/// `(±1, ±½, ±¼)` permuted.
fn dyadic_directions() -> Vec<DVec3> {
    let mut out = Vec::new();
    for x in -1..=1 {
        for y in -1..=1 {
            for z in -1..=1 {
                if (x, y, z) != (0, 0, 0) {
                    out.push(DVec3::new(f64::from(x), f64::from(y), f64::from(z)));
                }
            }
        }
    }
    for perm in [
        [0, 1, 2],
        [0, 2, 1],
        [1, 0, 2],
        [1, 2, 0],
        [2, 0, 1],
        [2, 1, 0],
    ] {
        for signs in 0..8 {
            let mut v = [0.0; 3];
            for (k, magnitude) in [1.0, 0.5, 0.25].into_iter().enumerate() {
                let sign = if signs >> k & 1 == 1 { -1.0 } else { 1.0 };
                v[perm[k]] = sign * magnitude;
            }
            out.push(DVec3::from_array(v));
        }
    }
    out
}

#[test]
fn exact_crossings_through_every_vertex_of_dyadic_solids() {
    // Every coordinate is a multiple of 2⁻⁸, so p = v ± d/32 is exact and the segment's line
    // passes exactly through the vertex: its sheared position is exactly the origin and
    // all edge functions of the fan's spokes are exactly 0 (for axis-aligned directions,
    // with no shear at all). Only the tie-break decides.
    let directions = dyadic_directions();
    for solid in solids().iter().filter(|s| s.dyadic) {
        let mut transversal_count = 0;
        for (v, fan) in solid.fans.iter().enumerate() {
            let vertex = solid.mesh.vertices[v];
            for &d in &directions {
                let (p0, p1) = (vertex + d / 32.0, vertex - d / 32.0);
                assert_eq!((p0 + p1) / 2.0, vertex, "not exact");
                if let Err(message) = check_local_crossing(solid, fan, p0, p1) {
                    panic!("vertex {v}: {message}");
                }
                transversal_count += usize::from(transversal(solid, fan, p0, p1));
            }
        }
        assert!(
            transversal_count > 100,
            "{}: {transversal_count}",
            solid.name
        );
    }
}

#[test]
fn exact_crossings_through_every_edge_of_dyadic_solids() {
    let directions = dyadic_directions();
    for solid in solids().iter().filter(|s| s.dyadic) {
        for (&(p, q), pair) in &solid.edges {
            let (p, q) = (
                solid.mesh.vertices[p as usize],
                solid.mesh.vertices[q as usize],
            );
            for x in [(p + q) / 2.0, p + (q - p) / 4.0, q + (p - q) / 4.0] {
                for &d in &directions {
                    let (p0, p1) = (x + d / 256.0, x - d / 256.0);
                    assert_eq!((p0 + p1) / 2.0, x, "not exact");
                    if let Err(message) = check_local_crossing(solid, pair, p0, p1) {
                        panic!("edge through {x}: {message}");
                    }
                }
            }
        }
    }
}

/// A unit vector, roughly uniform over directions.
fn direction() -> impl Strategy<Value = DVec3> {
    (-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0)
        .prop_map(|(x, y, z)| DVec3::new(x, y, z))
        .prop_filter("non-zero", |d| d.length() > 0.1)
        .prop_map(DVec3::normalize)
}

/// A solid of [`solids`], by index.
fn solid_index() -> impl Strategy<Value = usize> {
    0..solids().len()
}

/// A convex solid of [`solids`], by index.
fn convex_solid_index() -> impl Strategy<Value = usize> {
    let convex: Vec<usize> = (0..solids().len())
        .filter(|&s| solids()[s].convex)
        .collect();
    prop::sample::select(convex)
}

/// The edges of `solid` whose two triangles are not coplanar, in a fixed order.
fn folded_edges(solid: &Solid) -> Vec<((u32, u32), [usize; 2])> {
    let mut edges: Vec<_> = solid
        .edges
        .iter()
        .map(|(&e, pair)| (e, [pair[0], pair[1]]))
        .filter(|(_, [t0, t1])| solid.normal(*t0).dot(solid.normal(*t1)) < 1.0 - 1e-6)
        .collect();
    edges.sort();
    edges
}

/// The vertices of `solid` where it is strictly convex, with the sum of their fan's unit
/// normals (inside the normal cone): every other corner of the fan is clearly below the
/// plane through the vertex normal to that sum. Flat vertices, and vertices on a box
/// edge, touch a supporting plane along a line instead.
fn strictly_convex_vertices(solid: &Solid) -> Vec<(usize, DVec3)> {
    (0..solid.mesh.vertices.len())
        .filter_map(|v| {
            let vertex = solid.mesh.vertices[v];
            let fan = &solid.fans[v];
            let m = fan
                .iter()
                .map(|&t| solid.normal(t))
                .sum::<DVec3>()
                .normalize();
            let below = fan
                .iter()
                .flat_map(|&t| solid.mesh.corners(t))
                .all(|x| x == vertex || m.dot(x - vertex) < -1e-6 * (x - vertex).length());
            below.then_some((v, m))
        })
        .collect()
}

/// A dyadic fraction of an edge, strictly inside it.
fn edge_fraction() -> impl Strategy<Value = f64> {
    (1u32..16).prop_map(|k| f64::from(k) / 16.0)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    /// Segments aimed through a mesh vertex (the end points are rounded, so the line passes
    /// within rounding of it), in any direction.
    #[test]
    fn segments_through_vertices(
        s in solid_index(),
        v in any::<prop::sample::Index>(),
        d in direction(),
        length in 1e-3f64..0.3,
    ) {
        let solid = &solids()[s];
        let v = v.index(solid.mesh.vertices.len());
        let vertex = solid.mesh.vertices[v];
        let result = check_local_crossing(solid, &solid.fans[v], vertex + length * d, vertex - length * d);
        prop_assert!(result.is_ok(), "vertex {}: {}", v, result.unwrap_err());
    }

    /// Segments aimed through a point on a shared edge.
    #[test]
    fn segments_through_edges(
        s in solid_index(),
        e in any::<prop::sample::Index>(),
        fraction in edge_fraction(),
        d in direction(),
        length in 1e-3f64..0.3,
    ) {
        let solid = &solids()[s];
        let mut edges: Vec<_> = solid.edges.iter().collect();
        edges.sort();
        let (&(p, q), pair) = edges[e.index(edges.len())];
        let (p, q) = (solid.mesh.vertices[p as usize], solid.mesh.vertices[q as usize]);
        let x = p + fraction * (q - p);
        let result = check_local_crossing(solid, pair, x + length * d, x - length * d);
        prop_assert!(result.is_ok(), "{}", result.unwrap_err());
    }

    /// From well outside to well inside a convex solid: exactly one hit, entering; and
    /// back out, leaving. Half the segments are aimed at a vertex or an edge point.
    #[test]
    fn outside_to_inside_of_convex_solids_hits_once(
        s in convex_solid_index(),
        target in any::<prop::sample::Index>(),
        aim in 0u8..3,
        fraction in edge_fraction(),
        d in direction(),
        out_scale in 1.5f64..4.0,
        in_scale in -0.9f64..0.5,
        inner in direction(),
    ) {
        let solid = &solids()[s];
        let vertices = &solid.mesh.vertices;
        let (lo, hi) = solid.mesh.bounds().expect("a solid has vertices");
        let radius = (hi - lo).length() / 2.0;
        let (outside, inside) = match aim {
            0 => {
                let v = vertices[target.index(vertices.len())];
                (out_scale * v, in_scale * v)
            }
            1 => {
                let [a, b, _] = solid.mesh.corners(target.index(solid.mesh.triangles.len()));
                let x = a + fraction * (b - a);
                (out_scale * x, in_scale * x)
            }
            _ => (out_scale * radius * d, 0.5 * in_scale.abs() * lo.abs().min_element() * inner),
        };
        prop_assume!(solid.winding(outside) == 0 && solid.winding(inside) == 1);
        for (p0, p1, entering) in [(outside, inside, true), (inside, outside, false)] {
            let hits = solid.hits(&Segment::new(p0, p1));
            prop_assert_eq!(hits.len(), 1, "{}: {} → {}: {:?}", solid.name, p0, p1, hits);
            prop_assert_eq!(hits[0].1.entering, entering);
        }
    }

    /// Between two points outside a convex solid: 0 or 2 hits, one entering and one leaving.
    #[test]
    fn outside_to_outside_of_convex_solids_hits_evenly(
        s in convex_solid_index(),
        d0 in direction(),
        d1 in direction(),
        r0 in 1.5f64..4.0,
        r1 in 1.5f64..4.0,
    ) {
        let solid = &solids()[s];
        let (lo, hi) = solid.mesh.bounds().expect("a solid has vertices");
        let radius = (hi - lo).length() / 2.0;
        let (p0, p1) = (r0 * radius * d0, r1 * radius * d1);
        let hits = solid.hits(&Segment::new(p0, p1));
        prop_assert!(hits.is_empty() || hits.len() == 2, "{}: {:?}", solid.name, hits);
        prop_assert_eq!(signed(&hits), 0);
    }

    /// Segments tangent to a convex edge (they touch the solid only along the edge, at one
    /// point): the two triangles fold over seen along the segment, 0 or 2 hits.
    #[test]
    fn segments_grazing_convex_edges_hit_zero_or_two_times(
        s in convex_solid_index(),
        e in any::<prop::sample::Index>(),
        fraction in edge_fraction(),
        along in -2.0f64..2.0,
        length in 1e-3f64..0.3,
    ) {
        let solid = &solids()[s];
        let edges = folded_edges(solid);
        let ((p, q), pair) = edges[e.index(edges.len())];
        let (n0, n1) = (solid.normal(pair[0]), solid.normal(pair[1]));
        let (p, q) = (solid.mesh.vertices[p as usize], solid.mesh.vertices[q as usize]);
        let x = p + fraction * (q - p);
        let d = ((n0 - n1).normalize() + along * (q - p).normalize()).normalize();
        let hits = solid.hits(&Segment::new(x + length * d, x - length * d));
        prop_assert!(hits.is_empty() || hits.len() == 2, "{}: {:?}", solid.name, hits);
        prop_assert_eq!(signed(&hits), 0);
        prop_assert!(hits.iter().all(|(t, _)| pair.contains(t)));
    }

    /// Segments in a supporting plane of a strictly convex vertex, which touches the solid
    /// only there.
    #[test]
    fn segments_grazing_convex_vertices_hit_zero_or_two_times(
        s in convex_solid_index(),
        v in any::<prop::sample::Index>(),
        d in direction(),
        length in 1e-3f64..0.3,
    ) {
        let solid = &solids()[s];
        let candidates = strictly_convex_vertices(solid);
        let (v, m) = candidates[v.index(candidates.len())];
        let tangent = (d - d.dot(m) * m).normalize();
        prop_assume!(tangent.is_finite());
        let vertex = solid.mesh.vertices[v];
        let hits = solid.hits(&Segment::new(vertex + length * tangent, vertex - length * tangent));
        prop_assert!(hits.is_empty() || hits.len() == 2, "{}: {:?}", solid.name, hits);
        prop_assert_eq!(signed(&hits), 0);
        prop_assert!(hits.iter().all(|(t, _)| solid.fans[v].contains(t)));
    }

    /// Any segment against any closed solid: the signed count of hits is the change of
    /// winding number, and the parity of the count follows.
    #[test]
    fn signed_hits_equal_the_winding_change(
        s in solid_index(),
        c0 in (-1.5f64..1.5, -1.5f64..1.5, -1.5f64..1.5),
        c1 in (-1.5f64..1.5, -1.5f64..1.5, -1.5f64..1.5),
    ) {
        let solid = &solids()[s];
        let (lo, hi) = solid.mesh.bounds().expect("a solid has vertices");
        let half = (hi - lo) / 2.0;
        let p0 = DVec3::new(c0.0, c0.1, c0.2) * half;
        let p1 = DVec3::new(c1.0, c1.1, c1.2) * half;
        prop_assume!(solid.distance(p0) > ON_SURFACE_M && solid.distance(p1) > ON_SURFACE_M);
        let hits = solid.hits(&Segment::new(p0, p1));
        let change = solid.winding(p1) - solid.winding(p0);
        prop_assert_eq!(signed(&hits), change, "{}: {:?}", solid.name, hits);
    }
}

/// Exact in-plane directions of triangle `[a, b, c]`: its edges and a few dyadic
/// combinations of them (every sum stays exact on dyadic solids).
fn in_plane_directions([a, b, c]: [DVec3; 3]) -> Vec<DVec3> {
    let (u, v) = (b - a, c - a);
    vec![
        u,
        v,
        v - u,
        u + v,
        u - v,
        u + 2.0 * v,
        2.0 * u + v,
        u - 2.0 * v,
        4.0 * u - v,
    ]
}

#[test]
fn segments_exactly_in_a_face_plane_of_dyadic_solids() {
    // Every face of the dyadic solids, segments lying exactly in its plane through its
    // corners, edge points and an interior point, short (inside the face) and long
    // (reaching past the face, into the solid where the plane cuts through a concave part):
    // the face is seen edge-on, and the signed count must still be the change of winding
    // number — a segment from outside to inside is never without a hit.
    let mut judged = 0;
    let mut crossing = 0;
    for solid in solids().iter().filter(|s| s.dyadic) {
        for t in 0..solid.mesh.triangles.len() {
            let [a, b, c] = solid.mesh.corners(t);
            for x in [
                a,
                b,
                c,
                (a + b) / 2.0,
                (b + c) / 2.0,
                (c + a) / 2.0,
                (2.0 * a + b + c) / 4.0,
            ] {
                for d in in_plane_directions([a, b, c]) {
                    for scale in [0.25, 1.0, 4.0] {
                        let (p0, p1) = (x + scale * d, x - scale * d);
                        assert_eq!((p0 + p1) / 2.0, x, "not exact");
                        if solid.distance(p0) < ON_SURFACE_M || solid.distance(p1) < ON_SURFACE_M {
                            continue;
                        }
                        let hits = solid.hits(&Segment::new(p0, p1));
                        let change = solid.winding(p1) - solid.winding(p0);
                        assert_eq!(
                            signed(&hits),
                            change,
                            "{} face {t}: {p0} → {p1}: {hits:?}",
                            solid.name
                        );
                        assert!(
                            hits.iter().all(|(h, _)| *h != t),
                            "{}: the edge-on face {t} was hit",
                            solid.name
                        );
                        judged += 1;
                        crossing += usize::from(change != 0);
                    }
                }
            }
        }
    }
    assert!(
        judged > 1000 && crossing > 50,
        "{judged} judged, {crossing} crossing"
    );
}

#[test]
fn segments_in_the_plane_of_a_side_wall_cross_where_it_meets_the_floor() {
    // A block with a rectangular pocket (hand-built, dyadic): segments in the plane of a
    // pocket wall, from the air above the block down into the material below the pocket's
    // floor. The wall is seen edge-on; the crossing is on the top face at the wall's top
    // edge or on the floor at its bottom edge — two different edges that coincide in the
    // projection along the segment. Exactly one must report it.
    let mut checked = 0;
    for (name, map) in [
        ("pocket", (|p| p) as fn(DVec3) -> DVec3),
        ("slanted pocket", super::meshes::slant),
    ] {
        let solid = solids()
            .iter()
            .find(|s| s.name == name)
            .expect("the pocket solids");
        for wall_x in [0.25, 0.75] {
            for y in [0.375, 0.5, 0.625] {
                for dy in [0.0, 0.125, -0.25] {
                    for z_top in [1.5, 1.25] {
                        let p0 = map(DVec3::new(wall_x, y + dy, z_top));
                        let p1 = map(DVec3::new(wall_x, y, 0.25));
                        let hits = solid.hits(&Segment::new(p0, p1));
                        assert_eq!(solid.winding(p0), 0);
                        assert_eq!(solid.winding(p1), 1);
                        // Slanted segments may pass through a pocket corner as well
                        // (enter, leave, enter); straight down there is one crossing.
                        assert_eq!(signed(&hits), 1, "{name}: {p0} → {p1}: {hits:?}");
                        if dy == 0.0 {
                            assert_eq!(hits.len(), 1, "{name}: {p0} → {p1}: {hits:?}");
                        }
                        checked += 1;
                    }
                }
            }
        }
    }
    assert_eq!(checked, 72);
}
