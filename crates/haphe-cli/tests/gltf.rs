//! glTF files through the command: a `.gltf` with its buffer in a side-car `.bin` read
//! from its folder, `validate`'s per-node report, `simulate --scene` with one object per
//! mesh node (names and materials from the file), and bad files named with the place.
//! The files are written here by hand; the Python tests read files written by pygltflib.

mod common;

use std::path::Path;

use common::{assert_error, haphe, ok, s, scratch, write};
use serde_json::{Value, json};

/// A closed tetrahedron 0.1 m across (counter-clockwise seen from outside) as one buffer:
/// 12 u32 indices, then 4 f32 positions.
fn tetrahedron_buffer() -> Vec<u8> {
    let indices: [u32; 12] = [0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3];
    let points: [[f32; 3]; 4] = [
        [0.0, 0.0, 0.0],
        [0.1, 0.0, 0.0],
        [0.0, 0.1, 0.0],
        [0.0, 0.0, 0.1],
    ];
    indices
        .iter()
        .flat_map(|i| i.to_le_bytes())
        .chain(points.iter().flatten().flat_map(|v| v.to_le_bytes()))
        .collect()
}

/// A document of one tetrahedron mesh placed by `nodes` (the first is the scene's root),
/// its buffer at `uri`.
fn document(uri: &str, nodes: Value) -> Value {
    json!({
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": nodes,
        "meshes": [{"name": "tetra", "primitives": [{"attributes": {"POSITION": 1}, "indices": 0}]}],
        "accessors": [
            {"bufferView": 0, "componentType": 5125, "count": 12, "type": "SCALAR"},
            {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3",
             "min": [0.0, 0.0, 0.0], "max": [0.1, 0.1, 0.1]},
        ],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 48},
            {"buffer": 0, "byteOffset": 48, "byteLength": 48},
        ],
        "buffers": [{"byteLength": 96, "uri": uri}],
    })
}

/// Three nested nodes sharing the mesh: a translation, a rotation with a material in its
/// `extras`, a non-uniform scale.
fn nested() -> Value {
    let half = std::f64::consts::FRAC_PI_4.sin();
    json!([
        {"name": "base", "mesh": 0, "translation": [0.5, 0.0, 0.0], "children": [1]},
        {"name": "arm", "mesh": 0, "rotation": [0.0, 0.0, half, half], "translation": [0.0, 0.3, 0.0],
         "children": [2], "extras": {"stiffness": 800.0, "friction": 0.4}},
        {"name": "hand", "mesh": 0, "scale": [2.0, 1.0, 0.5], "translation": [0.3, 0.0, 0.0]},
    ])
}

/// Writes `doc` as `dir/name` with the tetrahedron's buffer as `dir/tetra.bin`.
fn write_gltf(dir: &Path, name: &str, doc: &Value) -> String {
    write(dir, "tetra.bin", tetrahedron_buffer());
    write(dir, name, serde_json::to_vec(doc).expect("json"))
}

#[test]
fn a_side_car_gltf_validates_node_by_node() {
    let dir = scratch("gltf-validate");
    let path = write_gltf(&dir, "arm.gltf", &document("tetra.bin", nested()));
    let record: Value =
        serde_json::from_str(&ok(&["validate", "--json", &path])).expect("one JSON line");
    assert_eq!(record["format"], "gltf");
    // Three tetrahedra, flattened in world coordinates: each 0.1³/6 m³, the hand's scaled
    // by 2 × 1 × 0.5.
    assert_eq!(record["triangles"], 12);
    let volume = record["volume"].as_f64().expect("a solid");
    let expected = 0.001 / 6.0 * (1.0 + 1.0 + 1.0);
    assert!((volume - expected).abs() < 1e-9, "{volume} {expected}");
    let nodes = record["gltf"]["nodes"].as_array().expect("nodes");
    let names: Vec<&str> = nodes.iter().filter_map(|n| n["name"].as_str()).collect();
    assert_eq!(names, ["base", "arm", "hand"]);
    assert!(nodes.iter().all(|n| n["closed"] == true && n["mesh"] == 0));
    // The hand's world translation: the base's (0.5, 0, 0), plus the arm's (0, 0.3, 0),
    // plus its own (0.3, 0, 0) turned 90° about z by the arm: (0, 0.3, 0).
    let t: Vec<f64> = nodes[2]["translation"]
        .as_array()
        .expect("translation")
        .iter()
        .filter_map(Value::as_f64)
        .collect();
    for (got, want) in t.iter().zip([0.5, 0.6, 0.0]) {
        assert!((got - want).abs() < 1e-6, "{t:?}");
    }
    let text = ok(&["validate", &path]);
    assert!(
        text.contains("glTF scene 0: 3 node(s) with a mesh"),
        "{text}"
    );
    assert!(
        text.contains("node 1 'arm': mesh 0, 4 triangles, closed"),
        "{text}"
    );
    assert!(
        text.contains("turned 90.0° about [0.0, 0.0, 1.0]"),
        "{text}"
    );
}

#[test]
fn simulate_scene_loads_one_object_per_mesh_node_with_the_file_s_materials() {
    let dir = scratch("gltf-scene");
    let path = write_gltf(&dir, "arm.gltf", &document("tetra.bin", nested()));
    let text = ok(&["simulate", "--scene", &path, "--seconds", "0.05"]);
    assert!(text.contains("scene: 3 object(s), 12 triangles"), "{text}");
    assert!(
        text.contains("  base (id 0, 4 triangles, 500 N/m, friction 0/0)"),
        "{text}"
    );
    assert!(
        text.contains("  arm (id 1, 4 triangles, 800 N/m, friction 0.4/0.4)"),
        "{text}"
    );
    assert!(text.contains("  hand (id 2, 4 triangles"), "{text}");
}

#[test]
fn bad_gltf_scenes_are_named_with_the_place() {
    let dir = scratch("gltf-bad");
    // The side-car file is missing.
    let path = write(
        &dir,
        "gone.gltf",
        serde_json::to_vec(&document("gone.bin", nested())).expect("json"),
    );
    let points = write(&dir, "points.csv", "x,y,z\n0,0,0\n");
    for args in [
        vec!["simulate", "--scene", &path, "--seconds", "0.05"],
        vec!["query", "--inside", &points, &path],
    ] {
        assert_error(&haphe(&args), &["gone.gltf", "buffer 0", "gone.bin"]);
    }
    // A side-car named by an absolute path is not read.
    let bin = dir.join("tetra.bin");
    let absolute = write_gltf(&dir, "abs.gltf", &document(s(&bin), nested()));
    assert_error(
        &haphe(&["simulate", "--scene", &absolute, "--seconds", "0.05"]),
        &["abs.gltf", "buffer 0", "an absolute path"],
    );
    // A node that squashes its mesh flat.
    let mut nodes = nested();
    nodes[2]["scale"] = json!([1.0, 0.0, 1.0]);
    let flat = write_gltf(&dir, "flat.gltf", &document("tetra.bin", nodes));
    assert_error(
        &haphe(&["simulate", "--scene", &flat, "--seconds", "0.05"]),
        &["flat.gltf", "node 2 ('hand')", "singular"],
    );
    // A material the library refuses, named by the node.
    let mut nodes = nested();
    nodes[1]["extras"] = json!({"stiffness": -5.0});
    let soft = write_gltf(&dir, "soft.gltf", &document("tetra.bin", nodes));
    assert_error(
        &haphe(&["simulate", "--scene", &soft, "--seconds", "0.05"]),
        &["soft.gltf", "node 1 ('arm')", "stiffness"],
    );
}
