//! glTF 2.0: the Khronos `Box` as a closed unit solid, every triangle primitive, indices of
//! every type, quantized positions, nested transforms flattened and kept apart as scene
//! objects, shared meshes built once, and hostile files refused with the file and the
//! place. The files are written by `gltf/writer.rs`; expected values come from the
//! geometry put in, transformed by hand.

#[path = "gltf/hostile.rs"]
mod hostile;
#[path = "gltf/scene.rs"]
mod scene;
#[path = "gltf/writer.rs"]
mod writer;

use haphe::DVec3;
use haphe::glam::{DAffine3, DQuat};
use haphe::mesh::{
    Format, GltfScene, Mesh, MeshReport, NoSideCars, ReadOptions, Units, Usability, Weld,
    read_gltf, read_mesh, read_unwelded, read_unwelded_with, weld,
};
use serde_json::json;
use writer::{UNSIGNED_BYTE, UNSIGNED_INT, UNSIGNED_SHORT, Writer, khronos_box};

/// Reads a glTF's default scene with no side-car files.
fn scene_of(bytes: &[u8]) -> GltfScene {
    read_gltf("test.glb", bytes, Units::Metres, &mut NoSideCars).unwrap_or_else(|e| panic!("{e}"))
}

/// The triangles of `mesh` as corner positions, each triangle rotated to start at its
/// smallest corner (so two meshes compare whatever their vertex order), sorted.
fn triangle_set(mesh: &Mesh) -> Vec<[[i64; 3]; 3]> {
    let key = |p: DVec3| (p * 1e9).round().to_array().map(|v| v as i64);
    let mut out: Vec<[[i64; 3]; 3]> = (0..mesh.triangles.len())
        .map(|t| {
            let c = mesh.corners(t).map(key);
            let first = (0..3).min_by_key(|&i| c[i]).expect("three");
            [c[first], c[(first + 1) % 3], c[(first + 2) % 3]]
        })
        .collect();
    out.sort();
    out
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

#[test]
fn the_khronos_box_is_a_closed_solid_of_volume_one() {
    let w = khronos_box();
    let glb = w.glb();
    let (gltf, mut files) = w.gltf_with_side_car("Box0.bin");
    let options = ReadOptions::default();
    assert_eq!(Format::detect("Box.glb", &glb), Ok(Format::Gltf));
    assert_eq!(Format::detect("Box.gltf", &gltf), Ok(Format::Gltf));
    let from_glb = read_unwelded("Box.glb", &glb, &options).unwrap_or_else(|e| panic!("{e}"));
    let from_gltf = read_unwelded_with("Box.gltf", &gltf, &options, &mut files)
        .unwrap_or_else(|e| panic!("{e}"));
    let embedded =
        read_unwelded("Box.gltf", &w.gltf_embedded(), &options).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(from_glb, from_gltf);
    assert_eq!(from_glb, embedded);
    // 24 split vertices as in the file, 12 triangles.
    assert_eq!(
        (from_glb.vertices.len(), from_glb.triangles.len()),
        (24, 12)
    );
    let (welded, _) = weld(&from_glb, Weld::Exact);
    assert_eq!(
        welded.vertices.len(),
        8,
        "welded by position to the cube's 8 corners"
    );
    let report = MeshReport::of(&welded);
    assert!(report.closed, "{:?}", report.problems());
    assert_eq!(
        report.usable_as,
        Usability::Solid,
        "{:?}",
        report.problems()
    );
    let volume = report.volume.expect("a solid has a volume");
    assert!((volume - 1.0).abs() < 1e-12, "volume {volume}");
    assert!((signed_volume(&welded) - 1.0).abs() < 1e-12);
    // read_mesh welds the same way.
    assert_eq!(read_mesh("Box.glb", &glb, &options).expect("reads"), welded);
}

#[test]
fn the_box_matrix_turns_z_up_into_y_up() {
    // The sample's matrix has the columns (1, 0, 0), (0, 0, -1), (0, 1, 0): a point
    // (x, y, z) goes to (x, z, -y). Moving the cube up z by 1 in the child shows it.
    let mut w = khronos_box();
    w.doc["nodes"][1]["translation"] = json!([0.0, 0.0, 1.0]);
    let mesh = scene_of(&w.glb()).flatten();
    let (lo, hi) = mesh.bounds().expect("vertices");
    // The child's z offset of 1 becomes a y offset of 1 (z maps to y).
    assert_eq!(lo, DVec3::new(-0.5, 0.5, -0.5));
    assert_eq!(hi, DVec3::new(0.5, 1.5, 0.5));
}

/// A unit square in the z = 0 plane as four vertices.
const SQUARE: [[f32; 3]; 4] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [1.0, 1.0, 0.0],
    [0.0, 1.0, 0.0],
];

#[test]
fn strips_fans_and_lists_of_every_index_type_read_the_same_triangles() {
    let mut expected_list = Writer::new();
    let m = expected_list.triangle_mesh(&SQUARE, &[[0, 1, 2], [0, 2, 3]]);
    expected_list.root(json!({"mesh": m}));
    let expected = triangle_set(&scene_of(&expected_list.glb()).flatten());
    // (mode, index sequence) drawing the same two counter-clockwise triangles.
    let cases: [(u32, &[u32]); 3] = [
        (4, &[0, 1, 2, 0, 2, 3]),
        (5, &[1, 2, 0, 3]),
        (6, &[0, 1, 2, 3]),
    ];
    for (mode, sequence) in cases {
        for component_type in [UNSIGNED_BYTE, UNSIGNED_SHORT, UNSIGNED_INT] {
            let mut w = Writer::new();
            let position = w.positions(&SQUARE);
            let indices = w.indices(sequence, component_type);
            let mesh = w.mesh(
                json!([{"attributes": {"POSITION": position}, "indices": indices, "mode": mode}]),
            );
            w.root(json!({"mesh": mesh}));
            let got = triangle_set(&scene_of(&w.glb()).flatten());
            assert_eq!(
                got, expected,
                "mode {mode}, component type {component_type}"
            );
        }
    }
    // Without indices, the vertices in order.
    let mut w = Writer::new();
    let fan = [SQUARE[0], SQUARE[1], SQUARE[2], SQUARE[3]];
    let position = w.positions(&fan);
    let mesh = w.mesh(json!([{"attributes": {"POSITION": position}, "mode": 6}]));
    w.root(json!({"mesh": mesh}));
    assert_eq!(triangle_set(&scene_of(&w.glb()).flatten()), expected);
    // Two primitives without indices in one mesh: the second draws its own vertices, not
    // the first's (the square, then the same square moved up by 2).
    let mut w = Writer::new();
    let lifted = SQUARE.map(|[x, y, z]| [x, y, z + 2.0]);
    let (first, second) = (w.positions(&fan), w.positions(&lifted));
    let mesh = w.mesh(json!([
        {"attributes": {"POSITION": first}, "mode": 6},
        {"attributes": {"POSITION": second}, "mode": 6},
    ]));
    w.root(json!({"mesh": mesh}));
    let mut both = expected.clone();
    let mut lifted_list = Writer::new();
    let m = lifted_list.triangle_mesh(&lifted, &[[0, 1, 2], [0, 2, 3]]);
    lifted_list.root(json!({"mesh": m}));
    both.extend(triangle_set(&scene_of(&lifted_list.glb()).flatten()));
    both.sort();
    assert_eq!(triangle_set(&scene_of(&w.glb()).flatten()), both);
}

#[test]
fn points_and_lines_are_skipped_and_listed() {
    let mut w = Writer::new();
    let position = w.positions(&SQUARE);
    let indices = w.indices(&[0, 1, 2], UNSIGNED_SHORT);
    let mesh = w.mesh(json!([
        {"attributes": {"POSITION": position}, "mode": 0},
        {"attributes": {"POSITION": position}, "indices": indices},
        {"attributes": {"POSITION": position}, "mode": 1},
        {"attributes": {"POSITION": position}, "mode": 3},
    ]));
    w.root(json!({"mesh": mesh}));
    let scene = scene_of(&w.glb());
    let skipped: Vec<(usize, &str)> = scene
        .skipped
        .iter()
        .map(|s| (s.primitive, s.mode))
        .collect();
    assert_eq!(
        skipped,
        vec![(0, "POINTS"), (2, "LINES"), (3, "LINE_STRIP")]
    );
    assert_eq!(scene.flatten().triangles.len(), 1);

    // Only lines: no triangles, said plainly.
    let mut w = Writer::new();
    let position = w.positions(&SQUARE);
    let mesh = w.mesh(json!([{"attributes": {"POSITION": position}, "mode": 2}]));
    w.root(json!({"mesh": mesh}));
    let err = read_gltf("lines.glb", &w.glb(), Units::Metres, &mut NoSideCars).unwrap_err();
    assert_eq!(
        err.to_string(),
        "lines.glb: header: no triangles: the scene's meshes draw only points or lines (1 primitives skipped)"
    );
}

#[test]
fn quantized_positions_are_read_as_the_extension_says() {
    // KHR_mesh_quantization: positions as normalised shorts and unnormalised unsigned
    // bytes; the node's scale brings them back to metres.
    let raw_shorts: [[i16; 3]; 3] = [[0, 0, 0], [32767, 0, 0], [0, -32767, -100]];
    let raw_bytes: [[u8; 3]; 3] = [[0, 0, 0], [200, 0, 0], [0, 10, 3]];
    for (component_type, normalized, bytes, expected) in [
        (
            writer::SHORT,
            true,
            raw_shorts
                .iter()
                .flatten()
                .flat_map(|v| v.to_le_bytes())
                .collect::<Vec<u8>>(),
            raw_shorts.map(|p| p.map(|c| f64::from(c) / 32767.0)),
        ),
        (
            UNSIGNED_BYTE,
            false,
            // Each element padded to 4 bytes, as vertex attributes must be.
            raw_bytes
                .iter()
                .flat_map(|p| [p[0], p[1], p[2], 0])
                .collect(),
            raw_bytes.map(|p| p.map(f64::from)),
        ),
    ] {
        let mut w = Writer::new();
        let stride = if component_type == UNSIGNED_BYTE {
            Some(4)
        } else {
            Some(8)
        };
        let bytes: Vec<u8> = if component_type == UNSIGNED_BYTE {
            bytes
        } else {
            bytes
                .chunks(6)
                .flat_map(|c| [c, &[0, 0]].concat())
                .collect()
        };
        let view = w.view(&bytes, stride);
        let position = w.accessor(json!({
            "bufferView": view, "componentType": component_type, "normalized": normalized,
            "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 1],
        }));
        let mesh = w.mesh(json!([{"attributes": {"POSITION": position}}]));
        w.root(json!({"mesh": mesh, "scale": [2.0, 2.0, 2.0]}));
        w.doc["extensionsUsed"] = json!(["KHR_mesh_quantization"]);
        w.doc["extensionsRequired"] = json!(["KHR_mesh_quantization"]);
        let mesh = scene_of(&w.glb()).flatten();
        let got: Vec<DVec3> = mesh.vertices.clone();
        let want: Vec<DVec3> = expected
            .iter()
            .map(|p| DVec3::from_array(*p) * 2.0)
            .collect();
        assert_eq!(got, want, "component type {component_type}");
    }
}

#[test]
fn nested_transforms_are_composed_root_first() {
    // root: translation; child: rotation; grandchild: non-uniform scale, holding the mesh.
    let mut w = Writer::new();
    let tri = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 1.0]];
    let mesh = w.triangle_mesh(&tri, &[[0, 1, 2]]);
    let q = DQuat::from_rotation_z(std::f64::consts::FRAC_PI_2);
    w.root(json!({"translation": [1.0, 2.0, 3.0], "children": [1]}));
    w.node(json!({"rotation": [q.x, q.y, q.z, q.w], "children": [2]}));
    w.node(json!({"scale": [2.0, 3.0, 4.0], "mesh": mesh, "name": "leaf"}));
    let scene = scene_of(&w.glb());
    assert_eq!(scene.nodes.len(), 1);
    assert_eq!(scene.nodes[0].name.as_deref(), Some("leaf"));
    // By hand: scale (x, y, z) → (2x, 3y, 4z); a quarter turn about z: (x, y) → (-y, x);
    // then + (1, 2, 3).
    let by_hand = |[x, y, z]: [f64; 3]| DVec3::new(-3.0 * y + 1.0, 2.0 * x + 2.0, 4.0 * z + 3.0);
    let flat = scene.flatten();
    for (got, p) in flat.vertices.iter().zip(tri) {
        let want = by_hand(p.map(f64::from));
        assert!((*got - want).length() < 1e-6, "{got} {want}");
    }
}

#[test]
fn a_mirroring_node_turns_its_triangles_over() {
    let mut w = khronos_box();
    w.doc["nodes"][1]["scale"] = json!([-1.0, 1.0, 1.0]);
    let mesh = scene_of(&w.glb()).flatten();
    // Still a solid facing outwards: the volume stays positive.
    assert!((signed_volume(&mesh) - 1.0).abs() < 1e-12);
    let (welded, _) = weld(&mesh, Weld::Exact);
    assert_eq!(MeshReport::of(&welded).usable_as, Usability::Solid);
}

#[test]
fn units_scale_positions_and_translations_alike() {
    let mut w = khronos_box();
    w.doc["nodes"][1]["translation"] = json!([10.0, 0.0, 0.0]);
    let metres = scene_of(&w.glb()).flatten();
    let mm = read_gltf("b.glb", &w.glb(), Units::Millimetres, &mut NoSideCars)
        .expect("reads")
        .flatten();
    for (a, b) in metres.vertices.iter().zip(&mm.vertices) {
        assert!((*a * 1e-3 - *b).length() < 1e-15, "{a} {b}");
    }
}

#[test]
fn a_file_without_scenes_reads_its_root_nodes() {
    let mut w = khronos_box();
    w.doc.as_object_mut().expect("object").remove("scene");
    w.doc.as_object_mut().expect("object").remove("scenes");
    let scene = scene_of(&w.glb());
    assert_eq!(scene.scene, None);
    assert_eq!(scene.nodes.len(), 1);
    let by_matrix =
        DAffine3::from_cols_array(&[1.0, 0.0, 0.0, 0.0, 0.0, -1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0]);
    assert_eq!(scene.nodes[0].world_from_node, by_matrix);
}
