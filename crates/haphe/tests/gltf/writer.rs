//! A small glTF writer for the tests: buffers, views and accessors packed by hand, the
//! document as JSON that a test may edit (to make it hostile) before writing it out as a
//! `.glb`, a `.gltf` with a data URI, or a `.gltf` with a side-car `.bin`.

use std::collections::HashMap;

use base64::Engine;
use haphe::mesh::Resolve;
use serde_json::{Value, json};

pub const FLOAT: u32 = 5126;
pub const UNSIGNED_BYTE: u32 = 5121;
pub const SHORT: u32 = 5122;
pub const UNSIGNED_SHORT: u32 = 5123;
pub const UNSIGNED_INT: u32 = 5125;

/// A glTF document under construction, with its one buffer.
#[derive(Default)]
pub struct Writer {
    pub bin: Vec<u8>,
    pub doc: Value,
}

fn push(doc: &mut Value, array: &str, item: Value) -> usize {
    let list = doc[array].as_array_mut().expect("an array");
    list.push(item);
    list.len() - 1
}

impl Writer {
    pub fn new() -> Writer {
        Writer {
            bin: Vec::new(),
            doc: json!({
                "asset": {"version": "2.0", "generator": "haphe tests"},
                "buffers": [],
                "bufferViews": [],
                "accessors": [],
                "meshes": [],
                "nodes": [],
                "scenes": [{"nodes": []}],
                "scene": 0,
            }),
        }
    }

    /// A buffer view over `bytes`, appended to the buffer at a 4-byte boundary.
    pub fn view(&mut self, bytes: &[u8], stride: Option<usize>) -> usize {
        while self.bin.len() % 4 != 0 {
            self.bin.push(0);
        }
        let mut view =
            json!({"buffer": 0, "byteOffset": self.bin.len(), "byteLength": bytes.len()});
        if let Some(s) = stride {
            view["byteStride"] = json!(s);
        }
        self.bin.extend_from_slice(bytes);
        push(&mut self.doc, "bufferViews", view)
    }

    pub fn accessor(&mut self, accessor: Value) -> usize {
        push(&mut self.doc, "accessors", accessor)
    }

    /// Float positions in a view of their own, with the `min` and `max` glTF asks for.
    pub fn positions(&mut self, points: &[[f32; 3]]) -> usize {
        let bytes: Vec<u8> = points
            .iter()
            .flatten()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        let view = self.view(&bytes, None);
        let min: Vec<f32> = (0..3)
            .map(|k| points.iter().map(|p| p[k]).fold(f32::MAX, f32::min))
            .collect();
        let max: Vec<f32> = (0..3)
            .map(|k| points.iter().map(|p| p[k]).fold(f32::MIN, f32::max))
            .collect();
        self.accessor(json!({
            "bufferView": view, "componentType": FLOAT, "count": points.len(), "type": "VEC3",
            "min": min, "max": max,
        }))
    }

    /// Indices of `component_type` (UNSIGNED_BYTE, _SHORT or _INT).
    pub fn indices(&mut self, indices: &[u32], component_type: u32) -> usize {
        let bytes: Vec<u8> = indices
            .iter()
            .flat_map(|&i| match component_type {
                UNSIGNED_BYTE => vec![u8::try_from(i).expect("fits")],
                UNSIGNED_SHORT => u16::try_from(i).expect("fits").to_le_bytes().to_vec(),
                _ => i.to_le_bytes().to_vec(),
            })
            .collect();
        let view = self.view(&bytes, None);
        self.accessor(json!({
            "bufferView": view, "componentType": component_type, "count": indices.len(),
            "type": "SCALAR",
        }))
    }

    pub fn mesh(&mut self, primitives: Value) -> usize {
        push(&mut self.doc, "meshes", json!({"primitives": primitives}))
    }

    /// A mesh of one indexed triangle primitive.
    pub fn triangle_mesh(&mut self, points: &[[f32; 3]], triangles: &[[u32; 3]]) -> usize {
        let position = self.positions(points);
        let flat: Vec<u32> = triangles.iter().flatten().copied().collect();
        let indices = self.indices(&flat, UNSIGNED_INT);
        self.mesh(json!([{"attributes": {"POSITION": position}, "indices": indices}]))
    }

    pub fn node(&mut self, node: Value) -> usize {
        push(&mut self.doc, "nodes", node)
    }

    /// A node listed as a root of the default scene.
    pub fn root(&mut self, node: Value) -> usize {
        let n = self.node(node);
        self.doc["scenes"][0]["nodes"]
            .as_array_mut()
            .expect("nodes")
            .push(json!(n));
        n
    }

    fn with_buffer(&self, uri: Option<String>) -> Value {
        let mut doc = self.doc.clone();
        let mut buffer = json!({"byteLength": self.bin.len()});
        if let Some(uri) = uri {
            buffer["uri"] = json!(uri);
        }
        if !self.bin.is_empty() && doc["buffers"].as_array().is_some_and(Vec::is_empty) {
            doc["buffers"] = json!([buffer]);
        }
        doc
    }

    /// The document as a `.glb`: the buffer in the BIN chunk.
    pub fn glb(&self) -> Vec<u8> {
        glb(&self.with_buffer(None), &self.bin)
    }

    /// The document as a `.gltf` with the buffer in a base64 data URI.
    pub fn gltf_embedded(&self) -> Vec<u8> {
        let data = base64::engine::general_purpose::STANDARD.encode(&self.bin);
        let uri = format!("data:application/octet-stream;base64,{data}");
        serde_json::to_vec(&self.with_buffer(Some(uri))).expect("json")
    }

    /// The document as a `.gltf` referring to the side-car file `name`, and that file.
    pub fn gltf_with_side_car(&self, name: &str) -> (Vec<u8>, Files) {
        let text = serde_json::to_vec(&self.with_buffer(Some(name.to_owned()))).expect("json");
        (text, Files::from([(name.to_owned(), self.bin.clone())]))
    }
}

/// A `.glb` of a JSON document and a BIN chunk.
pub fn glb(doc: &Value, bin: &[u8]) -> Vec<u8> {
    let mut json = serde_json::to_vec(doc).expect("json");
    while json.len() % 4 != 0 {
        json.push(b' ');
    }
    let mut bin = bin.to_vec();
    while bin.len() % 4 != 0 {
        bin.push(0);
    }
    let length = 12 + 8 + json.len() + if bin.is_empty() { 0 } else { 8 + bin.len() };
    let mut out = Vec::with_capacity(length);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(length as u32).to_le_bytes());
    out.extend_from_slice(&(json.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&json);
    if !bin.is_empty() {
        out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
        out.extend_from_slice(b"BIN\0");
        out.extend_from_slice(&bin);
    }
    out
}

/// Side-car files by name: the resolver of the tests.
#[derive(Default)]
pub struct Files(pub HashMap<String, Vec<u8>>);

impl<const N: usize> From<[(String, Vec<u8>); N]> for Files {
    fn from(files: [(String, Vec<u8>); N]) -> Files {
        Files(HashMap::from(files))
    }
}

impl Resolve for Files {
    fn resolve(&mut self, uri: &str, _byte_length: u64) -> Result<Vec<u8>, String> {
        self.0
            .get(uri)
            .cloned()
            .ok_or_else(|| "No such file or directory".to_owned())
    }
}

/// The Khronos sample `Box`, rebuilt: a unit cube of 24 vertices (split per face, as its
/// normals need), normals and positions in one buffer view, 36 unsigned-short indices, a
/// mesh node under a root whose matrix turns it -90° about x (z up to y up).
pub fn khronos_box() -> Writer {
    let mut w = Writer::new();
    let mut normals: Vec<[f32; 3]> = Vec::new();
    let mut points: Vec<[f32; 3]> = Vec::new();
    let mut indices: Vec<u32> = Vec::new();
    for axis in 0..3 {
        for sign in [1.0f32, -1.0] {
            let mut n = [0.0f32; 3];
            n[axis] = sign;
            // u × v = n: corners counter-clockwise seen from outside.
            let mut u = [0.0f32; 3];
            let mut v = [0.0f32; 3];
            u[(axis + 1) % 3] = 1.0;
            v[(axis + 2) % 3] = sign;
            let base = points.len() as u32;
            for (a, b) in [(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)] {
                points.push(std::array::from_fn(|k| 0.5 * n[k] + a * u[k] + b * v[k]));
                normals.push(n);
            }
            indices.extend([base, base + 1, base + 2, base, base + 2, base + 3]);
        }
    }
    let indices = w.indices(&indices, UNSIGNED_SHORT);
    let bytes: Vec<u8> = normals
        .iter()
        .chain(&points)
        .flatten()
        .flat_map(|v| v.to_le_bytes())
        .collect();
    let view = w.view(&bytes, Some(12));
    let normal = w.accessor(json!({
        "bufferView": view, "byteOffset": 0, "componentType": FLOAT, "count": 24,
        "type": "VEC3", "max": [1, 1, 1], "min": [-1, -1, -1],
    }));
    let position = w.accessor(json!({
        "bufferView": view, "byteOffset": 288, "componentType": FLOAT, "count": 24,
        "type": "VEC3", "max": [0.5, 0.5, 0.5], "min": [-0.5, -0.5, -0.5],
    }));
    w.doc["materials"] = json!([{
        "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.0, 0.0, 1.0], "metallicFactor": 0.0},
        "name": "Red",
    }]);
    let mesh = w.mesh(json!([{
        "attributes": {"NORMAL": normal, "POSITION": position},
        "indices": indices, "mode": 4, "material": 0,
    }]));
    w.doc["meshes"][mesh]["name"] = json!("Mesh");
    // As in the sample: node 0 the root with the matrix, node 1 its child with the mesh.
    w.root(json!({
        "children": [1],
        "matrix": [1.0, 0.0, 0.0, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0],
    }));
    w.node(json!({"mesh": mesh}));
    w
}
