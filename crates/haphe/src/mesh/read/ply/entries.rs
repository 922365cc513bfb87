//! The entry types `ply-rs-bw` fills: a vertex position, an index list, or nothing.

use ply_rs_bw::ply::{PropertyAccess, PropertyAccessResult};

/// The names of the texture coordinates a `vertex` may have, in pairs `(u, v)`, the first
/// pair the header declares whole being the one read.
pub(super) const TEXTURE_NAMES: [[&str; 2]; 3] =
    [["u", "v"], ["s", "t"], ["texture_u", "texture_v"]];

/// A `vertex` entry: `x`, `y`, `z` and the texture coordinates of any numeric type, as
/// `f64`; the rest is ignored.
pub(super) struct VertexEntry {
    /// The position in file units.
    pub(super) xyz: [f64; 3],
    /// The values of [`TEXTURE_NAMES`], pair after pair (0 for those the header lacks).
    pub(super) texture: [[f64; 2]; 3],
}

impl VertexEntry {
    fn set(&mut self, name: &str, value: f64) -> PropertyAccessResult {
        let axis = match name {
            "x" => 0,
            "y" => 1,
            "z" => 2,
            _ => {
                for (pair, names) in TEXTURE_NAMES.iter().enumerate() {
                    if let Some(k) = names.iter().position(|&n| n == name) {
                        self.texture[pair][k] = value;
                        return PropertyAccessResult::Set;
                    }
                }
                return PropertyAccessResult::Ignored;
            }
        };
        self.xyz[axis] = value;
        PropertyAccessResult::Set
    }
}

impl PropertyAccess for VertexEntry {
    fn new() -> Self {
        VertexEntry {
            xyz: [0.0; 3],
            texture: [[0.0; 2]; 3],
        }
    }
    fn set_char(&mut self, name: &str, value: i8) -> PropertyAccessResult {
        self.set(name, f64::from(value))
    }
    fn set_uchar(&mut self, name: &str, value: u8) -> PropertyAccessResult {
        self.set(name, f64::from(value))
    }
    fn set_short(&mut self, name: &str, value: i16) -> PropertyAccessResult {
        self.set(name, f64::from(value))
    }
    fn set_ushort(&mut self, name: &str, value: u16) -> PropertyAccessResult {
        self.set(name, f64::from(value))
    }
    fn set_int(&mut self, name: &str, value: i32) -> PropertyAccessResult {
        self.set(name, f64::from(value))
    }
    fn set_uint(&mut self, name: &str, value: u32) -> PropertyAccessResult {
        self.set(name, f64::from(value))
    }
    fn set_float(&mut self, name: &str, value: f32) -> PropertyAccessResult {
        self.set(name, f64::from(value))
    }
    fn set_double(&mut self, name: &str, value: f64) -> PropertyAccessResult {
        self.set(name, value)
    }
}

/// A `face` or `tristrips` entry: its `vertex_indices` (or `vertex_index`) list of any
/// integer type, widened to `i64` so negative and out-of-range values can be reported as
/// written.
pub(super) struct IndexList {
    /// The indices as written.
    pub(super) indices: Vec<i64>,
}

impl IndexList {
    fn set(&mut self, name: &str, values: impl Iterator<Item = i64>) -> PropertyAccessResult {
        if name == "vertex_indices" || name == "vertex_index" {
            self.indices.clear();
            self.indices.extend(values);
            PropertyAccessResult::Set
        } else {
            PropertyAccessResult::Ignored
        }
    }
}

impl PropertyAccess for IndexList {
    fn new() -> Self {
        IndexList {
            indices: Vec::new(),
        }
    }
    fn set_list_char(&mut self, name: &str, values: Vec<i8>) -> PropertyAccessResult {
        self.set(name, values.into_iter().map(i64::from))
    }
    fn set_list_uchar(&mut self, name: &str, values: Vec<u8>) -> PropertyAccessResult {
        self.set(name, values.into_iter().map(i64::from))
    }
    fn set_list_short(&mut self, name: &str, values: Vec<i16>) -> PropertyAccessResult {
        self.set(name, values.into_iter().map(i64::from))
    }
    fn set_list_ushort(&mut self, name: &str, values: Vec<u16>) -> PropertyAccessResult {
        self.set(name, values.into_iter().map(i64::from))
    }
    fn set_list_int(&mut self, name: &str, values: Vec<i32>) -> PropertyAccessResult {
        self.set(name, values.into_iter().map(i64::from))
    }
    fn set_list_uint(&mut self, name: &str, values: Vec<u32>) -> PropertyAccessResult {
        self.set(name, values.into_iter().map(i64::from))
    }
}

/// An entry of an element haphe does not use: read (to move past it) and dropped.
pub(super) struct Skip;

impl PropertyAccess for Skip {
    fn new() -> Self {
        Skip
    }
}
