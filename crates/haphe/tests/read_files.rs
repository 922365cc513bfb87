//! Reading the shared test meshes: every malformed or unusual file in `odd/` has an exact
//! outcome (a load with known counts, or a known error naming the file and the place), and
//! every model in `models/` loads.
//!
//! Counts were found by reading the files by hand (and, for the binary STL files, by
//! unpacking their records with a short script); each test says how.

mod support;

use haphe::mesh::{Mesh, Place, ReadError, ReadErrorKind, ReadOptions, read_mesh};

/// Reads `folder/name` from the real meshes with default options (always `Some`: every
/// file these tests name is in the repository's `meshes/` too).
fn read(folder: &str, name: &str) -> Option<Result<Mesh, ReadError>> {
    let path = support::meshes().join(folder).join(name);
    let bytes = std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    Some(read_mesh(name, &bytes, &ReadOptions::default()))
}

/// Asserts that `odd/name` loads with `triangles` triangles and `vertices` welded vertices.
fn assert_loads(name: &str, triangles: usize, vertices: usize) -> Option<Mesh> {
    let mesh = read("odd", name)?.unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(
        (mesh.triangles.len(), mesh.vertices.len()),
        (triangles, vertices),
        "{name}: (triangles, vertices)"
    );
    Some(mesh)
}

/// Asserts that `odd/name` fails with exactly `kind` and the message `text` (which starts
/// with the file name).
fn assert_fails(name: &str, kind: ReadErrorKind, text: &str) {
    let Some(result) = read("odd", name) else {
        return;
    };
    let err = result.expect_err(name);
    assert_eq!(err.kind, kind, "{name}");
    assert_eq!(err.file, name);
    assert_eq!(err.to_string(), text);
}

/// Signed volume enclosed by the triangles (positive when they face outwards).
fn signed_volume(mesh: &Mesh) -> f64 {
    (0..mesh.triangles.len())
        .map(|t| {
            let [a, b, c] = mesh.corners(t);
            a.dot(b.cross(c)) / 6.0
        })
        .sum()
}

/// Total area of the triangles.
fn area(mesh: &Mesh) -> f64 {
    (0..mesh.triangles.len())
        .map(|t| {
            let [a, b, c] = mesh.corners(t);
            0.5 * (b - a).cross(c - a).length()
        })
        .sum()
}

fn assert_close(actual: f64, expected: f64, relative: f64, what: &str) {
    assert!(
        (actual - expected).abs() <= relative * expected.abs(),
        "{what}: {actual} != {expected}"
    );
}

#[test]
fn busted_stl_is_a_binary_with_an_odd_header() {
    // Header "FileType: Binary", count 3878, size 84 + 50 × 3878 = 193 984 bytes: binary.
    // Unpacking the records gives 1941 distinct corner positions.
    assert_loads("busted.STL", 3878, 1941);
}

#[test]
fn comments_off_is_a_cube_with_comments_and_face_colours() {
    // 8 vertices, 6 quads with RGBA after the indices → 12 triangles; a comment after a
    // vertex. The quads wind outwards, so the volume is the cube's, positive.
    let Some(mesh) = assert_loads("comments.off", 12, 8) else {
        return;
    };
    let edge = mesh.vertices[0].distance(mesh.vertices[1]);
    assert_close(signed_volume(&mesh), edge.powi(3), 1e-5, "volume");
}

#[test]
fn empty_stl_is_an_ascii_solid_without_facets() {
    // "solid Empty\nendsolid Empty": no facets.
    assert_fails(
        "empty.stl",
        ReadErrorKind::NoFaces { vertices: 0 },
        "empty.stl: no faces: the file holds no geometry",
    );
}

#[test]
fn joined_tetrahedra_obj_shares_positions_across_normals() {
    // 5 positions, 8 triangles in `v//vn` form (two tetrahedra on one base); welding by
    // position keeps the 5 vertices whatever the normals. Both tetrahedra face outwards:
    // twice (base area 3√3/4) × height 1 / 3 = √3/2.
    let Some(mesh) = assert_loads("joined_tetrahedra.obj", 8, 5) else {
        return;
    };
    assert_close(signed_volume(&mesh), 3f64.sqrt() / 2.0, 1e-6, "volume");
}

#[test]
fn nancolor_obj_loads_despite_nan_colours() {
    // 8 vertices with RGB colours (one NaN triple, ignored), 12 triangles, CRLF: a unit
    // cube facing outwards.
    let Some(mesh) = assert_loads("nancolor.obj", 12, 8) else {
        return;
    };
    assert_close(signed_volume(&mesh), 1.0, 1e-12, "volume");
}

#[test]
fn negative_indices_obj_resolves_relative_indices() {
    // 8 vertices, 6 quads written with negative indices → 12 triangles: a 2 m cube.
    let Some(mesh) = assert_loads("negative_indices.obj", 12, 8) else {
        return;
    };
    assert_close(signed_volume(&mesh), 8.0, 1e-12, "volume");
}

#[test]
fn notenoughindices_obj_fails_at_its_two_corner_face() {
    // Line 9 is `f 1// 2//`.
    assert_fails(
        "notenoughindices.obj",
        ReadErrorKind::TooFewCorners {
            at: Place::Line(9),
            corners: 2,
        },
        "notenoughindices.obj: line 9: a face has 2 corner(s); a face needs at least 3",
    );
}

#[test]
fn obj_empty_has_only_comments() {
    // Two comment lines, no statement.
    assert_fails(
        "obj_empty.obj",
        ReadErrorKind::Empty,
        "obj_empty.obj: the file is empty",
    );
}

#[test]
fn obj_points_has_vertices_only() {
    // 8 `v` lines, no `f`.
    assert_fails(
        "obj_points.obj",
        ReadErrorKind::NoFaces { vertices: 8 },
        "obj_points.obj: no faces: the file holds 8 vertices (a point cloud or a wireframe) but no triangles or polygons",
    );
}

#[test]
fn obj_wireframe_has_lines_only() {
    // 8 `v` lines and 12 `l` lines, no `f`.
    assert_fails(
        "obj_wireframe.obj",
        ReadErrorKind::NoFaces { vertices: 8 },
        "obj_wireframe.obj: no faces: the file holds 8 vertices (a point cloud or a wireframe) but no triangles or polygons",
    );
}

#[test]
fn ply_empty_header_declares_nothing() {
    // `ply`, `format ascii 1.0`, `end_header`: no elements.
    assert_fails(
        "ply_empty_header.ply",
        ReadErrorKind::NoFaces { vertices: 0 },
        "ply_empty_header.ply: no faces: the file holds no geometry",
    );
}

#[test]
fn ply_points_bin_has_zero_faces() {
    // Binary little endian, `element vertex 8` (x y z nx ny nz floats), `element face 0`.
    assert_fails(
        "ply_points_bin.ply",
        ReadErrorKind::NoFaces { vertices: 8 },
        "ply_points_bin.ply: no faces: the file holds 8 vertices (a point cloud or a wireframe) but no triangles or polygons",
    );
}

#[test]
fn points_ascii_ply_has_no_face_element() {
    // `element vertex 5`, no face element, a blank line at the end.
    assert_fails(
        "points_ascii.ply",
        ReadErrorKind::NoFaces { vertices: 5 },
        "points_ascii.ply: no faces: the file holds 5 vertices (a point cloud or a wireframe) but no triangles or polygons",
    );
}

#[test]
fn polygonfaces_obj_triangulates_a_pentagon() {
    // 5 vertices, one face `f 1// 2// 3// 4// 5//` (a non-planar pentagon) → 3 triangles.
    assert_loads("polygonfaces.obj", 3, 5);
}

#[test]
fn soup_stl_shares_no_corners() {
    // Binary, 100 triangles (84 + 5000 bytes), 300 distinct corner positions.
    assert_loads("soup.stl", 100, 300);
}

#[test]
fn stl_empty_ascii_has_no_facets() {
    // `solid ...` then `endsolid ...`.
    assert_fails(
        "stl_empty_ascii.stl",
        ReadErrorKind::NoFaces { vertices: 0 },
        "stl_empty_ascii.stl: no faces: the file holds no geometry",
    );
}

#[test]
fn stl_empty_bin_has_a_zero_count() {
    // 84 bytes, count 0: a binary STL with no triangles.
    assert_fails(
        "stl_empty_bin.stl",
        ReadErrorKind::NoFaces { vertices: 0 },
        "stl_empty_bin.stl: no faces: the file holds no geometry",
    );
}

#[test]
fn wallhole_obj_ear_clips_non_convex_polygons() {
    // 92 `v` lines (35 distinct positions), 13 polygons (8, 11, 8, 6 × 10 corners; some
    // continued over two lines with a backslash, CRLF): Σ (n − 2) = 66 triangles. The
    // 11-gons are U-shaped walls with T-junctions, so a fan would overlap. An exact
    // triangulation covers the polygons' total area (721.42, computed per polygon with
    // Newell's formula) and encloses the solid's volume (1000 − 100 for the tunnel + 166.67
    // for the roof pyramid).
    let Some(mesh) = assert_loads("wallhole.obj", 66, 35) else {
        return;
    };
    assert_close(area(&mesh), 721.421_356_237_309_7, 1e-12, "area");
    assert_close(signed_volume(&mesh), 3200.0 / 3.0, 1e-12, "volume");
}

#[test]
fn whitespace_off_has_an_indented_glued_header() {
    // A tab and spaces, then `OFF8 6 12 # or nah`; 8 vertices, 6 coloured quads → 12.
    let Some(mesh) = assert_loads("whitespace.off", 12, 8) else {
        return;
    };
    let edge = mesh.vertices[0].distance(mesh.vertices[1]);
    assert_close(signed_volume(&mesh), edge.powi(3), 1e-5, "volume");
}

#[test]
fn every_odd_file_has_a_test() {
    // A new file in odd/ must get its own test above.
    let dir = support::meshes();
    let mut names: Vec<String> = std::fs::read_dir(dir.join("odd"))
        .expect("odd/ is readable")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    let tested = [
        "busted.STL",
        "comments.off",
        "empty.stl",
        "joined_tetrahedra.obj",
        "nancolor.obj",
        "negative_indices.obj",
        "notenoughindices.obj",
        "obj_empty.obj",
        "obj_points.obj",
        "obj_wireframe.obj",
        "ply_empty_header.ply",
        "ply_points_bin.ply",
        "points_ascii.ply",
        "polygonfaces.obj",
        "soup.stl",
        "stl_empty_ascii.stl",
        "stl_empty_bin.stl",
        "wallhole.obj",
        "whitespace.off",
    ];
    assert_eq!(names, tested);
}

#[test]
fn every_model_loads() {
    let models = support::model_files();
    let least = if support::SHARED { 21 } else { 7 };
    assert!(models.len() >= least, "{models:?}");
    for (name, path) in models {
        let bytes = std::fs::read(&path).expect("model is readable");
        let mesh =
            read_mesh(&name, &bytes, &ReadOptions::default()).unwrap_or_else(|e| panic!("{e}"));
        assert!(!mesh.triangles.is_empty(), "{name}");
        eprintln!(
            "{name}: {} triangles, {} vertices",
            mesh.triangles.len(),
            mesh.vertices.len()
        );
    }
}
