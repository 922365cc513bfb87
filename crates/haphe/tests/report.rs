//! The validation report on small hand-built meshes whose defects are known by construction.

mod support;

use haphe::DVec3;
use haphe::mesh::{Mesh, MeshReport, Surface, SurfaceError, SurfaceOptions, Usability};
use support::append;

/// A tetrahedron with outward (counter-clockwise) faces, corners at the origin and the unit
/// axes scaled by `s` and shifted by `offset`.
fn tetrahedron(s: f64, offset: DVec3) -> Mesh {
    Mesh {
        vertices: vec![
            offset,
            offset + s * DVec3::X,
            offset + s * DVec3::Y,
            offset + s * DVec3::Z,
        ],
        triangles: vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
    }
}

/// An axis-aligned cube of half-size `h` centred at the origin, 12 outward triangles.
fn cube(h: f64) -> Mesh {
    let mut vertices = Vec::new();
    for i in 0..8 {
        let bit = |b: usize| if i >> b & 1 == 1 { h } else { -h };
        vertices.push(DVec3::new(bit(0), bit(1), bit(2)));
    }
    let quads = [
        [0, 2, 3, 1], // -z
        [4, 5, 7, 6], // +z
        [0, 1, 5, 4], // -y
        [2, 6, 7, 3], // +y
        [0, 4, 6, 2], // -x
        [1, 3, 7, 5], // +x
    ];
    let triangles = quads
        .iter()
        .flat_map(|&[a, b, c, d]| [[a, b, c], [a, c, d]])
        .collect();
    Mesh {
        vertices,
        triangles,
    }
}

fn flipped(m: &Mesh) -> Mesh {
    Mesh {
        vertices: m.vertices.clone(),
        triangles: m.triangles.iter().map(|&[a, b, c]| [a, c, b]).collect(),
    }
}

#[test]
fn tetrahedron_is_a_closed_solid_of_genus_zero() {
    let r = MeshReport::of(&tetrahedron(1.0, DVec3::ZERO));
    assert_eq!(
        (r.triangles, r.vertices, r.edges, r.components),
        (4, 4, 6, 1)
    );
    assert!(r.closed);
    assert_eq!(r.usable_as, Usability::Solid);
    assert_eq!(r.genus, Some(0));
    let volume = r.volume.expect("closed and oriented");
    assert!((volume - 1.0 / 6.0).abs() < 1e-15, "{volume}");
    let area = 1.5 + 3f64.sqrt() / 2.0;
    assert!((r.area - area).abs() < 1e-15);
    assert!(r.problems().is_empty());
}

#[test]
fn inside_out_tetrahedron_is_reported_and_only_a_surface() {
    let r = MeshReport::of(&flipped(&tetrahedron(1.0, DVec3::ZERO)));
    assert_eq!(r.inverted_components, 1);
    assert_eq!(r.defects.inverted_components, vec![0]);
    assert!(r.volume.expect("closed") < 0.0);
    assert_eq!(r.usable_as, Usability::Surface);
}

#[test]
fn missing_face_leaves_three_boundary_edges() {
    let mut m = tetrahedron(1.0, DVec3::ZERO);
    m.triangles.pop();
    let r = MeshReport::of(&m);
    assert!(!r.closed);
    assert_eq!(r.boundary_edges, 3);
    assert_eq!(r.defects.boundary_edges, vec![[1, 2], [1, 3], [2, 3]]);
    assert_eq!(r.volume, None);
    assert_eq!(r.genus, None);
    assert_eq!(r.usable_as, Usability::Surface);
}

#[test]
fn one_flipped_face_conflicts_on_its_three_edges() {
    let mut m = tetrahedron(1.0, DVec3::ZERO);
    m.triangles[3] = [1, 3, 2];
    let r = MeshReport::of(&m);
    assert!(r.closed);
    assert_eq!(r.orientation_conflicts, 3);
    assert_eq!(r.volume, None);
    assert_eq!(r.usable_as, Usability::Surface);
}

#[test]
fn two_tetrahedra_touching_at_a_vertex_make_it_non_manifold() {
    let a = tetrahedron(1.0, DVec3::ZERO);
    let mut b = tetrahedron(1.0, DVec3::ZERO);
    // Mirror through the origin (flip winding back to outward), then share vertex 0.
    b.vertices.iter_mut().for_each(|p| *p = -*p);
    b = flipped(&b);
    let mut m = append(&a, &b);
    for t in &mut m.triangles {
        for v in t.iter_mut() {
            if *v == 4 {
                *v = 0;
            }
        }
    }
    m = haphe::mesh::weld(&m, haphe::mesh::Weld::Exact).0;
    let r = MeshReport::of(&m);
    assert!(r.closed);
    assert_eq!(
        r.components, 2,
        "components are joined through edges, not vertices"
    );
    assert_eq!(r.defects.nonmanifold_vertices, vec![0]);
    assert_eq!(r.nonmanifold_edges, 0);
    assert_eq!(r.usable_as, Usability::Surface);
}

#[test]
fn three_triangles_on_one_edge_make_it_non_manifold() {
    let m = Mesh {
        vertices: vec![
            DVec3::ZERO,
            DVec3::X,
            DVec3::Y,
            DVec3::Z,
            DVec3::new(0.0, -1.0, 0.5),
        ],
        triangles: vec![[0, 1, 2], [1, 0, 3], [0, 1, 4]],
    };
    let r = MeshReport::of(&m);
    assert_eq!(r.nonmanifold_edges, 1);
    assert_eq!(r.defects.nonmanifold_edges[0].edge, [0, 1]);
    assert_eq!(r.defects.nonmanifold_edges[0].triangles, vec![0, 1, 2]);
    assert!(!r.closed);
}

#[test]
fn duplicate_and_degenerate_faces_are_listed() {
    let mut m = tetrahedron(1.0, DVec3::ZERO);
    m.triangles.push([2, 0, 1]); // same vertices as face 0, other winding
    m.vertices.push(DVec3::new(0.5, 0.0, 0.0)); // on edge 0-1
    m.triangles.push([0, 1, 4]); // collinear: zero area
    m.triangles.push([2, 2, 3]); // repeated vertex
    let r = MeshReport::of(&m);
    assert_eq!(r.defects.duplicate_faces, vec![[0, 4]]);
    assert_eq!(r.defects.degenerate_triangles, vec![5, 6]);
    assert!(!r.closed, "edge 0-1 now has three uses");
}

#[test]
fn sliver_is_usable_but_reported() {
    let m = Mesh {
        vertices: vec![DVec3::ZERO, DVec3::X, DVec3::new(0.5, 1e-3, 0.0)],
        triangles: vec![[0, 1, 2]],
    };
    let r = MeshReport::of(&m);
    assert_eq!(r.sliver_triangles, 1);
    assert_eq!(r.degenerate_triangles, 0);
}

#[test]
fn cavity_inside_a_solid_is_not_inside_out() {
    let hollow = append(&cube(1.0), &flipped(&cube(0.5)));
    let r = MeshReport::of(&hollow);
    assert_eq!(r.components, 2);
    assert_eq!(r.inverted_components, 0);
    assert_eq!(r.usable_as, Usability::Solid);
    assert_eq!(r.component_list[1].depth, Some(1));
    let volume = r.volume.expect("closed");
    assert!((volume - (8.0 - 1.0)).abs() < 1e-12, "{volume}");

    // The same inner cube facing outward is a solid inside a solid (overlapping parts of
    // an assembly): reported, not inside out.
    let nested = append(&cube(1.0), &cube(0.5));
    let r = MeshReport::of(&nested);
    assert_eq!(r.inverted_components, 0);
    assert_eq!(r.defects.nested_solids, vec![1]);
    assert_eq!(r.usable_as, Usability::Solid);

    // An inside-out cube beside (not inside) the big one is inside out.
    let mut apart = cube(0.5);
    apart.vertices.iter_mut().for_each(|p| p.x += 3.0);
    let r = MeshReport::of(&append(&cube(1.0), &flipped(&apart)));
    assert_eq!(r.defects.inverted_components, vec![1]);
    assert_eq!(r.usable_as, Usability::Surface);
}

#[test]
fn separate_solids_are_each_at_depth_zero() {
    let two = append(&cube(0.5), &tetrahedron(1.0, DVec3::new(3.0, 0.0, 0.0)));
    let r = MeshReport::of(&two);
    assert_eq!(r.components, 2);
    assert!(r.component_list.iter().all(|c| c.depth == Some(0)));
    assert_eq!(r.usable_as, Usability::Solid);
}

#[test]
fn surface_neighbours_and_fans_of_a_cube() {
    let s = Surface::new(cube(0.5), &SurfaceOptions::default()).expect("a cube is valid");
    assert!(s.is_solid());
    for t in 0..s.triangle_count() as u32 {
        let t = haphe::mesh::TriId(t);
        for corner in 0..3 {
            let n = s
                .neighbour(t, corner)
                .expect("closed: every edge has a neighbour");
            let back = (0..3).filter(|&k| s.neighbour(n, k) == Some(t)).count();
            assert_eq!(back, 1, "neighbour relation is symmetric");
        }
    }
    // Each cube corner touches 3 faces, with 4 to 6 triangles; a fan is a closed cycle.
    for v in 0..8u32 {
        let fan = s.fan(haphe::mesh::VertId(v));
        assert!((3..=6).contains(&fan.len()));
        for k in 0..fan.len() {
            let (a, b) = (fan[k], fan[(k + 1) % fan.len()]);
            let shares_edge = s.neighbours(haphe::mesh::TriId(a)).contains(&b);
            assert!(shares_edge, "fan of {v} is in rotational order: {fan:?}");
        }
    }
    // 90° edges are creases at the default 30°: shading normals are the face normals (to
    // the single precision they are stored in).
    for t in 0..12u32 {
        let t = haphe::mesh::TriId(t);
        for n in s.corner_normals(t) {
            assert!((n - s.frame(t).normal).length() < 1e-7);
        }
    }
}

#[test]
fn surface_refuses_a_mesh_without_area() {
    let m = Mesh {
        vertices: vec![DVec3::ZERO, DVec3::X, 2.0 * DVec3::X],
        triangles: vec![[0, 1, 2]],
    };
    assert_eq!(
        Surface::new(m, &SurfaceOptions::default()).unwrap_err(),
        SurfaceError::NoArea { triangles: 1 }
    );
}
