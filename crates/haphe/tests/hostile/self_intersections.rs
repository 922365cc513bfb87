//! The self-intersection search on repeated and stacked triangles: coincident triangles
//! found by sorting and counted exactly; a bounded search that says when it stopped.

use haphe::DVec3;
use haphe::map::{MapOptions, VoxelMap};
use haphe::mesh::shapes::Catalog;
use haphe::mesh::{Mesh, Surface, SurfaceOptions, TriId};
use haphe::query::{intersect_triangle_triangle, self_intersection_budget, self_intersections};

/// Every intersecting pair, testing all pairs (coincident triangles share all their
/// corners: the triangle test does not count them), and the coincident pairs.
fn all_pairs(surface: &Surface) -> (usize, usize) {
    let n = surface.triangle_count() as u32;
    let sorted = |t: u32| {
        let mut c = surface.triangle(TriId(t));
        c.sort_unstable();
        c
    };
    let (mut count, mut coincident) = (0, 0);
    for a in 0..n {
        for b in a + 1..n {
            coincident += usize::from(sorted(a) == sorted(b));
            count += usize::from(intersect_triangle_triangle(
                surface.corners(TriId(a)),
                surface.corners(TriId(b)),
            ));
        }
    }
    (count, coincident)
}

/// Two interpenetrating boxes, some of whose faces are repeated (2, 3 and 4 copies): the
/// counts equal testing every pair (each copy's crossings with the other box count).
#[test]
fn repeated_faces_are_counted_as_testing_every_pair_does() {
    let a = Catalog::Box.with_triangles(100);
    let mut mesh = Mesh {
        vertices: a.vertices.clone(),
        triangles: a.triangles.clone(),
    };
    let offset = mesh.vertices.len() as u32;
    mesh.vertices
        .extend(a.vertices.iter().map(|p| *p + DVec3::new(0.05, 0.03, 0.02)));
    mesh.triangles
        .extend(a.triangles.iter().map(|t| t.map(|v| v + offset)));
    for t in 0..6 {
        for _ in 0..=t % 3 {
            let mut copy = mesh.triangles[t * 7];
            copy.rotate_left(t % 3);
            mesh.triangles.push(copy);
        }
    }
    let surface = Surface::new(mesh, &SurfaceOptions::default()).expect("surface");
    let map = VoxelMap::build(&surface, &MapOptions::default()).expect("map");
    let found = self_intersections(&surface, &map);
    assert!(found.complete);
    assert_eq!((found.count, found.coincident), all_pairs(&surface));
    assert_eq!(found.coincident, 1 + 3 + 6 + 1 + 3 + 6);
}

/// Distinct triangles all crossing one line, in the same cells: the search stops at its
/// budget, says so, and what it reports are real pairs.
#[test]
fn stacked_triangles_stop_at_the_budget() {
    let n = 2_500u32;
    let mut mesh = Mesh {
        vertices: Vec::new(),
        triangles: Vec::new(),
    };
    for i in 0..n {
        let h = (f64::from(i) / f64::from(n) - 0.5) * 0.1 + 1e-4;
        mesh.vertices.extend([
            DVec3::new(0.0, 0.0, h),
            DVec3::new(1.0, 0.0, -h),
            DVec3::new(0.0, 1.0, -h),
        ]);
        mesh.triangles.push([3 * i, 3 * i + 1, 3 * i + 2]);
    }
    let surface = Surface::new(mesh.clone(), &SurfaceOptions::default()).expect("surface");
    let map = VoxelMap::build(&surface, &MapOptions::default()).expect("map");
    let found = self_intersections(&surface, &map);
    assert!(!found.complete);
    assert!(found.candidates <= self_intersection_budget(n as usize));
    assert!(found.count > 1_000_000, "{}", found.count);
    // Listed pairs are indices of the mesh the surface was built from.
    for &[a, b] in &found.pairs {
        assert!(intersect_triangle_triangle(
            mesh.corners(a as usize),
            mesh.corners(b as usize)
        ));
    }
}
