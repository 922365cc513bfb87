//! The cheap filter of the crossing walk never skips a triangle the watertight test hits.

use super::*;
use crate::mesh::SurfaceOptions;
use crate::mesh::shapes::Catalog;
use crate::query::intersect_segment_triangle;
use crate::rng::SplitMix64;
use crate::verify::{SegmentKind, segments};

/// For every hit of every triangle by each segment, the filter keeps the triangle on
/// parts of the segment around the hit: the whole segment, a random part holding the
/// hit, and a part a hair long on each side of it (the narrowest a walk tests). Returns
/// how many hits were checked.
fn check_filter_keeps_hits(surface: &Surface, queries: &[(DVec3, DVec3)], seed: u64) -> usize {
    let mut random = SplitMix64::new(seed);
    let mut checked = 0;
    for &(p0, p1) in queries {
        let segment = Segment::new(p0, p1);
        for t in 0..surface.triangle_count() as u32 {
            let corners = surface.corners(TriId(t));
            let Some(hit) = intersect_segment_triangle(&segment, corners) else {
                continue;
            };
            let hair = 1e-9;
            let parts = [
                (0.0, 1.0),
                (random.range(0.0, hit.t), random.range(hit.t, 1.0)),
                ((hit.t - hair).max(0.0), (hit.t + hair).min(1.0)),
            ];
            for (from, to) in parts {
                let (q0, q1) = (point_at(p0, p1, from), point_at(p0, p1, to));
                assert!(
                    !cannot_cross(surface, t, q0, q1, 0.0),
                    "triangle {t} skipped on [{from}, {to}] of {p0:?} → {p1:?}, hit {hit:?}"
                );
            }
            checked += 1;
        }
    }
    checked
}

#[test]
fn the_filter_keeps_every_hit_triangle() {
    for (shape, triangles) in [
        (Catalog::ThinPlate, 1000),
        (Catalog::Sphere, 500),
        (Catalog::ConcaveCorner, 500),
        (Catalog::Blob, 1000),
    ] {
        let surface = Surface::new(shape.with_triangles(triangles), &SurfaceOptions::default())
            .expect("a procedural shape");
        let mut checked = 0;
        for (k, kind) in SegmentKind::ALL.into_iter().enumerate() {
            let queries = segments(&surface, kind, 150, 11 + k as u64);
            checked += check_filter_keeps_hits(&surface, &queries, 7 + k as u64);
        }
        assert!(checked > 400, "{shape}: only {checked} hits");
    }
}

#[test]
fn the_filter_skips_triangles_whose_plane_the_line_meets_elsewhere() {
    // A flat fan of triangles: a steep segment through one of them meets every plane (the
    // same plane), and only the triangle it crosses is kept.
    let surface = Surface::new(
        Catalog::ThinPlate.with_triangles(1000),
        &SurfaceOptions::default(),
    )
    .expect("a procedural shape");
    let (p0, p1) = (
        DVec3::new(0.009, 0.016, 0.03),
        DVec3::new(0.011, 0.014, -0.03),
    );
    let segment = Segment::new(p0, p1);
    let kept: Vec<u32> = (0..surface.triangle_count() as u32)
        .filter(|&t| !cannot_cross(&surface, t, p0, p1, 0.0))
        .collect();
    let hit: Vec<u32> = (0..surface.triangle_count() as u32)
        .filter(|&t| intersect_segment_triangle(&segment, surface.corners(TriId(t))).is_some())
        .collect();
    assert_eq!(hit.len(), 2, "the plate's two faces");
    assert_eq!(kept, hit);
}
