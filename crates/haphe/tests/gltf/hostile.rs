//! Hostile and broken glTF files: each refused with an error naming the file and the
//! place, never a panic.

use haphe::mesh::{NoSideCars, Place, ReadErrorKind, Units, read_gltf};
use serde_json::json;

use crate::writer::{Files, UNSIGNED_SHORT, Writer, glb, khronos_box};

/// The error message of reading `bytes` as `name`, with `files` as side-cars.
fn error_of(name: &str, bytes: &[u8], files: &mut Files) -> (ReadErrorKind, String) {
    let err = read_gltf(name, bytes, Units::Metres, files).expect_err("refused");
    assert_eq!(err.file, name);
    (err.kind.clone(), err.to_string())
}

/// The error of a `.glb` of the box edited by `edit`.
fn box_error(edit: impl FnOnce(&mut Writer)) -> String {
    let mut w = khronos_box();
    edit(&mut w);
    error_of("box.glb", &w.glb(), &mut Files::default()).1
}

#[test]
fn an_accessor_past_its_buffer_view_is_named() {
    let message = box_error(|w| w.doc["accessors"][2]["count"] = json!(25));
    assert_eq!(
        message,
        "box.glb: mesh 0, primitive 0, accessor 2 (POSITION): 25 elements of 12 bytes every \
         12 bytes from byte 288 reach past the 576 bytes of buffer view 1"
    );
    // A view past its buffer.
    let message = box_error(|w| w.doc["bufferViews"][1]["byteLength"] = json!(4000));
    // The indices take 72 bytes before the view; the buffer ends 576 bytes after them.
    assert_eq!(
        message,
        "box.glb: mesh 0, primitive 0, accessor 2 (POSITION), buffer view 1: the view's 4000 \
         bytes from byte 72 reach past the 648 bytes of buffer 0"
    );
}

#[test]
fn an_index_out_of_range_is_named() {
    let mut w = Writer::new();
    let position = w.positions(&[[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
    let indices = w.indices(&[0, 1, 3], UNSIGNED_SHORT);
    let mesh = w.mesh(json!([{"attributes": {"POSITION": position}, "indices": indices}]));
    w.root(json!({"mesh": mesh}));
    let (kind, message) = error_of("tri.glb", &w.glb(), &mut Files::default());
    assert!(matches!(
        kind,
        ReadErrorKind::IndexOutOfRange {
            index: 3,
            count: 3,
            ..
        }
    ));
    assert_eq!(
        message,
        "tri.glb: mesh 0, primitive 0, accessor 1 (indices): vertex index 3 is out of range \
         (the file has 3 vertices)"
    );
}

#[test]
fn a_buffer_shorter_than_its_byte_length_is_named() {
    let w = khronos_box();
    let mut doc = w.doc.clone();
    doc["buffers"] = json!([{"byteLength": w.bin.len() + 100}]);
    let (kind, message) = error_of("box.glb", &glb(&doc, &w.bin), &mut Files::default());
    assert!(matches!(kind, ReadErrorKind::Truncated { .. }), "{kind:?}");
    assert_eq!(
        message,
        format!(
            "box.glb: buffer 0: the file ends early: the BIN chunk holds {} bytes, fewer than \
             the buffer's byteLength of {}",
            w.bin.len(),
            w.bin.len() + 100
        )
    );
    // A side-car file cut short.
    let (text, mut files) = w.gltf_with_side_car("Box0.bin");
    files.0.get_mut("Box0.bin").expect("file").truncate(100);
    let (_, message) = error_of("Box.gltf", &text, &mut files);
    assert_eq!(
        message,
        format!(
            "Box.gltf: buffer 0: the file ends early: the file 'Box0.bin' holds 100 bytes, \
             fewer than the buffer's byteLength of {}",
            w.bin.len()
        )
    );
}

#[test]
fn a_missing_side_car_file_is_named() {
    let (text, _) = khronos_box().gltf_with_side_car("Box0.bin");
    let (kind, message) = error_of("Box.gltf", &text, &mut Files::default());
    assert!(
        matches!(kind, ReadErrorKind::MissingResource { .. }),
        "{kind:?}"
    );
    assert_eq!(
        message,
        "Box.gltf: buffer 0: cannot read the file 'Box0.bin' it refers to: No such file or directory"
    );
    // Bytes given alone cannot have side-car files at all.
    let err = read_gltf("Box.gltf", &text, Units::Metres, &mut NoSideCars).unwrap_err();
    assert!(err.to_string().contains("'Box0.bin'"), "{err}");
}

#[test]
fn a_cycle_in_the_node_graph_is_named() {
    let message = box_error(|w| w.doc["nodes"][1]["children"] = json!([0]));
    // Node 0 is then a child of node 1 and listed as a root of the scene: the cycle is
    // found first.
    assert_eq!(
        message,
        "box.glb: node 0: a cycle in the node graph: node 1 → node 0 → node 1 (each the parent of the next)"
    );
    let message = box_error(|w| w.doc["nodes"][1]["children"] = json!([1]));
    assert_eq!(
        message,
        "box.glb: node 1: a cycle in the node graph: the node is its own child"
    );
    // Two parents: a graph that would place a node twice.
    let message = box_error(|w| {
        w.node(json!({"children": [1]}));
    });
    assert_eq!(
        message,
        "box.glb: node 1: the node is a child of both node 0 and node 2; a glTF node has one parent at most"
    );
}

#[test]
fn absurd_counts_are_refused_before_allocating() {
    // A count far beyond the data.
    let message = box_error(|w| w.doc["accessors"][2]["count"] = json!(4_000_000_000u64));
    assert!(
        message.contains("4000000000 elements of 12 bytes"),
        "{message}"
    );
    // A count with no data behind it at all (zeros).
    let message = box_error(|w| {
        w.doc["accessors"][0]
            .as_object_mut()
            .expect("object")
            .remove("bufferView");
        w.doc["accessors"][0]["count"] = json!(1u64 << 40);
    });
    assert!(
        message.starts_with("box.glb: mesh 0, primitive 0, accessor 0 (indices): too large:"),
        "{message}"
    );
    // Many nodes placing one large mesh: counted before the triangles are made.
    let mut w = Writer::new();
    let position = w.positions(&[[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]);
    let indices = w.accessor(json!({"componentType": 5125, "count": 3 << 18, "type": "SCALAR"}));
    let mesh = w.mesh(json!([{"attributes": {"POSITION": position}, "indices": indices}]));
    for _ in 0..65 {
        w.root(json!({"mesh": mesh}));
    }
    let (kind, message) = error_of("many.glb", &w.glb(), &mut Files::default());
    assert!(
        matches!(
            kind,
            ReadErrorKind::TooLarge {
                at: Place::Header,
                ..
            }
        ),
        "{kind:?}"
    );
    let placed = 65 * (1usize << 18);
    assert_eq!(
        message,
        format!(
            "many.glb: header: too large: the scene's nodes place {placed} triangles, more than \
             the limit of {}",
            haphe::mesh::read::gltf::MAX_TRIANGLES
        )
    );
}

#[test]
fn required_extensions_haphe_does_not_read_are_refused_by_name() {
    let message =
        box_error(|w| w.doc["extensionsRequired"] = json!(["KHR_draco_mesh_compression"]));
    assert_eq!(
        message,
        "box.glb: header: the file requires KHR_draco_mesh_compression (Draco-compressed \
         geometry), which haphe does not decode; export the file without Draco compression"
    );
    let message = box_error(|w| w.doc["extensionsRequired"] = json!(["EXT_meshopt_compression"]));
    assert_eq!(
        message,
        "box.glb: header: the file requires the extension EXT_meshopt_compression, which haphe \
         does not read"
    );
    // Draco used, not required, with no uncompressed fallback for the positions.
    let message = box_error(|w| {
        w.doc["accessors"][2]
            .as_object_mut()
            .expect("object")
            .remove("bufferView");
        w.doc["meshes"][0]["primitives"][0]["extensions"] =
            json!({"KHR_draco_mesh_compression": {"bufferView": 0, "attributes": {"POSITION": 0}}});
        w.doc["extensionsUsed"] = json!(["KHR_draco_mesh_compression"]);
    });
    assert!(
        message.starts_with("box.glb: mesh 0, primitive 0: the primitive is compressed with KHR_draco_mesh_compression"),
        "{message}"
    );
    // Extensions that change only how the surface looks are no obstacle.
    let mut w = khronos_box();
    w.doc["extensionsRequired"] = json!(["KHR_texture_transform", "KHR_materials_unlit"]);
    assert!(read_gltf("box.glb", &w.glb(), Units::Metres, &mut Files::default()).is_ok());
}

#[test]
fn urls_and_broken_containers_are_refused() {
    let w = khronos_box();
    let mut doc = w.doc.clone();
    doc["buffers"] = json!([{"byteLength": w.bin.len(), "uri": "https://example.com/Box0.bin"}]);
    let text = serde_json::to_vec(&doc).expect("json");
    let (kind, _) = error_of("Box.gltf", &text, &mut Files::default());
    assert!(
        matches!(kind, ReadErrorKind::Unsupported { .. }),
        "{kind:?}"
    );
    // A .glb whose header claims more bytes than there are.
    let mut bytes = w.glb();
    bytes.truncate(bytes.len() - 10);
    let (kind, _) = error_of("box.glb", &bytes, &mut Files::default());
    assert!(matches!(kind, ReadErrorKind::Truncated { .. }), "{kind:?}");
    // A .glb header alone; JSON that is not a glTF document.
    let (kind, _) = error_of("box.glb", b"glTF\x02\0\0\0", &mut Files::default());
    assert!(matches!(kind, ReadErrorKind::Truncated { .. }), "{kind:?}");
    let (kind, message) = error_of("x.gltf", b"{\"meshes\": []}", &mut Files::default());
    assert!(
        matches!(
            kind,
            ReadErrorKind::Syntax {
                at: Place::Line(1),
                ..
            }
        ),
        "{kind:?}"
    );
    assert!(message.contains("asset"), "{message}");
}

#[test]
fn references_to_objects_that_do_not_exist_are_named() {
    for (edit, expected) in [
        (
            json!({"nodes": [{"mesh": 7}]}),
            "r.glb: node 0: its mesh 7 does not exist (the file has 1 meshes)",
        ),
        (
            json!({"scene": 3}),
            "r.glb: scene 3: the default scene does not exist (the file has 1 scenes)",
        ),
        (
            json!({"nodes": [{"children": [9]}]}),
            "r.glb: node 0: its child 9 does not exist (the file has 1 nodes)",
        ),
    ] {
        let mut w = Writer::new();
        let mesh = w.triangle_mesh(&[[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], &[[0, 1, 2]]);
        w.root(json!({"mesh": mesh}));
        for (k, v) in edit.as_object().expect("object") {
            w.doc[k] = v.clone();
        }
        let (_, message) = error_of("r.glb", &w.glb(), &mut Files::default());
        assert_eq!(message, expected);
    }
    // A POSITION accessor that does not exist: the `gltf` crate's own validation would
    // index out of bounds here; haphe does not run it.
    let message =
        box_error(|w| w.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = json!(99));
    assert_eq!(
        message,
        "box.glb: mesh 0, primitive 0, accessor 99 (POSITION): the accessor does not exist (the file has 3 accessors)"
    );
}
