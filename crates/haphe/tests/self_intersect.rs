//! Self-intersections found through the map against all pairs, on shapes whose answer is
//! known by construction and on the shared models.

mod support;

use haphe::DVec3;
use haphe::map::{MapOptions, VoxelMap};
use haphe::mesh::shapes::{self, Catalog};
use haphe::mesh::{Mesh, ReadOptions, Surface, SurfaceOptions, TriId, read_mesh};
use haphe::query::{SelfIntersections, intersect_triangle_triangle, self_intersections};
use support::append;

fn find(mesh: Mesh) -> (Surface, SelfIntersections) {
    let surface = Surface::new(mesh, &SurfaceOptions::default()).expect("surface");
    let map = VoxelMap::build(&surface, &MapOptions::default()).expect("map");
    let found = self_intersections(&surface, &map);
    (surface, found)
}

/// Every intersecting pair by testing all pairs (with a bounding-box early-out).
fn all_pairs(surface: &Surface) -> usize {
    let boxes: Vec<(DVec3, DVec3)> = (0..surface.triangle_count() as u32)
        .map(|t| {
            let c = surface.corners(TriId(t));
            (c[0].min(c[1]).min(c[2]), c[0].max(c[1]).max(c[2]))
        })
        .collect();
    let mut count = 0;
    for a in 0..boxes.len() {
        for b in a + 1..boxes.len() {
            let ((lo_a, hi_a), (lo_b, hi_b)) = (boxes[a], boxes[b]);
            if lo_a.cmple(hi_b).all()
                && lo_b.cmple(hi_a).all()
                && intersect_triangle_triangle(
                    surface.corners(TriId(a as u32)),
                    surface.corners(TriId(b as u32)),
                )
            {
                count += 1;
            }
        }
    }
    count
}

#[test]
fn procedural_shapes_do_not_intersect_themselves() {
    for shape in Catalog::ALL {
        let (_, found) = find(shape.with_triangles(5_000));
        assert_eq!(found.count, 0, "{shape}: {found:?}");
        assert!(found.candidates > 0);
    }
}

#[test]
fn interpenetrating_boxes_cross_and_match_all_pairs() {
    let a = shapes::cuboid(DVec3::splat(0.05), [3, 3, 3]);
    let mut b = shapes::cuboid(DVec3::splat(0.05), [3, 3, 3]);
    for p in &mut b.vertices {
        *p += DVec3::new(0.031, 0.017, 0.023);
    }
    let (surface, found) = find(append(&a, &b));
    assert!(found.crossing > 0, "{found:?}");
    assert_eq!(found.count, all_pairs(&surface));
    // The pairs name the mesh's own triangles: found again through the surface's order.
    let mut surface_index = vec![0u32; surface.triangle_count()];
    for (t, &s) in surface.source_triangles().iter().enumerate() {
        surface_index[s as usize] = t as u32;
    }
    for [x, y] in &found.pairs {
        assert!(x < y);
        assert!(intersect_triangle_triangle(
            surface.corners(TriId(surface_index[*x as usize])),
            surface.corners(TriId(surface_index[*y as usize]))
        ));
    }
}

#[test]
fn a_t_junction_only_touches() {
    // A square split in two triangles, and a second square standing on its diagonal's
    // midpoint, at a right angle: its bottom edge lies on the first square.
    let v = |x, y, z| DVec3::new(x, y, z);
    let mesh = Mesh {
        vertices: vec![
            v(0.0, 0.0, 0.0),
            v(1.0, 0.0, 0.0),
            v(1.0, 1.0, 0.0),
            v(0.0, 1.0, 0.0),
            v(0.25, 0.5, 0.0),
            v(0.75, 0.5, 0.0),
            v(0.75, 0.5, 1.0),
            v(0.25, 0.5, 1.0),
        ],
        triangles: vec![[0, 1, 2], [0, 2, 3], [4, 5, 6], [4, 6, 7]],
    };
    let (surface, found) = find(mesh);
    assert_eq!(found.crossing, 0, "{found:?}");
    assert!(found.touching > 0);
    assert_eq!(found.count, all_pairs(&surface));
}

/// (file, intersecting pairs, crossing pairs) of the models in the repository's `meshes/`.
const IN_TREE: &[(&str, usize, usize)] = &[
    ("20mm-xyz-cube.stl", 0, 0),
    ("cylinder.stl", 0, 0),
    ("fuze.ply", 0, 0),
    ("plate_holes.STL", 0, 0),
    ("sphere.ply", 0, 0),
    ("spot.obj", 0, 0),
    ("tet.ply", 0, 0),
];

/// The same for the other models of the shared collection.
const SHARED_ONLY: &[(&str, usize, usize)] = &[
    ("box.STL", 4665, 2454),
    ("bunny.ply", 4, 4),
    ("cow.obj", 81, 81),
    ("fandisk.obj", 0, 0),
    ("featuretype.STL", 1216, 0),
    ("fuze_ascii.ply", 0, 0),
    ("nefertiti.obj", 0, 0),
    ("octagonal_pocket.stl", 114, 0),
    ("rocker-arm.obj", 0, 0),
    ("stanford-bunny.obj", 0, 0),
    ("suzanne.obj", 90, 90),
    ("teapot.obj", 161, 161),
    ("torus.STL", 0, 0),
    ("unit_sphere.STL", 0, 0),
];

#[test]
fn real_models_match_all_pairs() {
    match_all_pairs(IN_TREE);
}

#[test]
#[cfg_attr(not(shared_meshes), ignore = "needs ../shared/meshes")]
fn shared_models_match_all_pairs() {
    match_all_pairs(SHARED_ONLY);
}

/// Each model's pairs as expected, and checked against all pairs for the smaller models.
fn match_all_pairs(expected: &[(&str, usize, usize)]) {
    let dir = support::meshes();
    for &(name, count, crossing) in expected {
        let bytes = std::fs::read(dir.join("models").join(name)).expect("readable");
        let mesh = read_mesh(name, &bytes, &ReadOptions::default()).expect("loads");
        let small = mesh.triangles.len() <= 10_000;
        let (surface, found) = find(mesh);
        assert_eq!((found.count, found.crossing), (count, crossing), "{name}");
        if small {
            assert_eq!(found.count, all_pairs(&surface), "{name}: all pairs");
        }
    }
}
