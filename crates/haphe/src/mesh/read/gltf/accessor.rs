//! Accessors: typed views of a buffer's bytes, read with every range checked (the `gltf`
//! crate's own reader slices without checking, so a hostile file could make it panic).

use gltf::json;
use gltf::json::accessor::{ComponentType, Type};
use gltf::json::validation::Checked;

use super::limits::{MAX_DECODED_ELEMENTS, MAX_UNBACKED_ELEMENTS};
use super::places::{ix, place};
use crate::mesh::GltfPlace;
use crate::mesh::ReadErrorKind;

/// What an accessor must hold to be read as one kind of data.
pub(super) struct Expect {
    /// The name in errors: `POSITION`, `indices`.
    pub what: &'static str,
    /// The accessor type (`VEC3`, `SCALAR`).
    pub kind: Type,
    /// The component types accepted.
    pub components: &'static [ComponentType],
}

/// Floats, or (`KHR_mesh_quantization`) integers of 8 or 16 bits, normalised or not.
const FLOAT_OR_QUANTIZED: &[ComponentType] = &[
    ComponentType::F32,
    ComponentType::I8,
    ComponentType::U8,
    ComponentType::I16,
    ComponentType::U16,
];

/// Positions: floats, or (`KHR_mesh_quantization`) integers, normalised or not.
pub(super) const POSITIONS: Expect = Expect {
    what: "POSITION",
    kind: Type::Vec3,
    components: FLOAT_OR_QUANTIZED,
};

/// Texture coordinates: floats, normalised unsigned bytes or shorts, or
/// (`KHR_mesh_quantization`) other integers, normalised or not.
pub(super) const TEXTURE_COORDS: Expect = Expect {
    what: "TEXCOORD_0",
    kind: Type::Vec2,
    components: FLOAT_OR_QUANTIZED,
};

/// Vertex indices: unsigned integers of any width.
pub(super) const INDICES: Expect = Expect {
    what: "indices",
    kind: Type::Scalar,
    components: &[ComponentType::U8, ComponentType::U16, ComponentType::U32],
};

/// The reader of a document's accessors, over its loaded buffers, keeping count of the
/// elements decoded so far (against [`MAX_DECODED_ELEMENTS`]).
pub(super) struct Accessors<'a> {
    pub root: &'a json::Root,
    pub buffers: &'a [Option<Vec<u8>>],
    pub decoded: u64,
    pub unbacked: u64,
}

fn type_name(kind: Type) -> &'static str {
    match kind {
        Type::Scalar => "SCALAR",
        Type::Vec2 => "VEC2",
        Type::Vec3 => "VEC3",
        Type::Vec4 => "VEC4",
        Type::Mat2 => "MAT2",
        Type::Mat3 => "MAT3",
        Type::Mat4 => "MAT4",
    }
}

fn component_name(c: ComponentType) -> &'static str {
    match c {
        ComponentType::I8 => "BYTE",
        ComponentType::U8 => "UNSIGNED_BYTE",
        ComponentType::I16 => "SHORT",
        ComponentType::U16 => "UNSIGNED_SHORT",
        ComponentType::U32 => "UNSIGNED_INT",
        ComponentType::F32 => "FLOAT",
    }
}

/// One component at `at` of `bytes` (known to be in range), as a number: normalised
/// integers map to [0, 1] or [-1, 1] as the glTF specification says.
fn component(bytes: &[u8], at: usize, c: ComponentType, normalized: bool) -> f64 {
    let b = |i: usize| bytes[at + i];
    let (value, scale) = match c {
        ComponentType::I8 => (f64::from(b(0) as i8), 127.0),
        ComponentType::U8 => (f64::from(b(0)), 255.0),
        ComponentType::I16 => (f64::from(i16::from_le_bytes([b(0), b(1)])), 32767.0),
        ComponentType::U16 => (f64::from(u16::from_le_bytes([b(0), b(1)])), 65535.0),
        ComponentType::U32 => (
            f64::from(u32::from_le_bytes([b(0), b(1), b(2), b(3)])),
            4_294_967_295.0,
        ),
        ComponentType::F32 => (f64::from(f32::from_le_bytes([b(0), b(1), b(2), b(3)])), 1.0),
    };
    if normalized && c != ComponentType::F32 {
        (value / scale).max(-1.0)
    } else {
        value
    }
}

/// A buffer view's bytes and its stride.
struct View<'b> {
    bytes: &'b [u8],
    stride: Option<usize>,
}

impl<'a> Accessors<'a> {
    fn view(&self, index: usize, at: GltfPlace) -> Result<View<'a>, ReadErrorKind> {
        let at = GltfPlace {
            buffer_view: Some(ix(index)),
            ..at
        };
        let invalid = |message: String| ReadErrorKind::Invalid {
            at: place(at),
            message,
        };
        let views = &self.root.buffer_views;
        let view = views.get(index).ok_or_else(|| {
            invalid(format!(
                "the buffer view does not exist (the file has {} buffer views)",
                views.len()
            ))
        })?;
        let buffer = view.buffer.value();
        let data = self
            .buffers
            .get(buffer)
            .and_then(Option::as_deref)
            .ok_or_else(|| {
                invalid(format!(
                    "buffer {buffer} does not exist (the file has {} buffers)",
                    self.root.buffers.len()
                ))
            })?;
        let start = view.byte_offset.map_or(0, |o| o.0);
        let length = view.byte_length.0;
        match start.checked_add(length) {
            Some(end) if end <= data.len() as u64 => Ok(View {
                bytes: &data[start as usize..end as usize],
                stride: view.byte_stride.map(|s| s.0),
            }),
            _ => Err(invalid(format!(
                "the view's {length} bytes from byte {start} reach past the {} bytes of \
                 buffer {buffer}",
                data.len()
            ))),
        }
    }

    /// Counts `n` more decoded elements against the limits before they are allocated.
    fn take(&mut self, n: u64, unbacked: bool, at: GltfPlace) -> Result<(), ReadErrorKind> {
        let (total, limit, what) = if unbacked {
            (
                &mut self.unbacked,
                MAX_UNBACKED_ELEMENTS,
                "elements without a buffer view (zeros)",
            )
        } else {
            (&mut self.decoded, MAX_DECODED_ELEMENTS, "elements decoded")
        };
        match total.checked_add(n) {
            Some(sum) if sum <= limit => {
                *total = sum;
                Ok(())
            }
            _ => Err(ReadErrorKind::TooLarge {
                at: place(at),
                message: format!(
                    "{n} elements would bring the file's {what} past the limit of {limit}"
                ),
            }),
        }
    }

    /// The elements of accessor `index`, flattened (`count × components` numbers).
    ///
    /// # Errors
    /// Naming the accessor: it does not exist, has another type or component type than
    /// `expect`, reaches past its buffer view, or holds more elements than the limits.
    pub fn read(
        &mut self,
        index: usize,
        expect: &Expect,
        at: GltfPlace,
    ) -> Result<Vec<f64>, ReadErrorKind> {
        let at = GltfPlace {
            accessor: Some((ix(index), expect.what)),
            ..at
        };
        let invalid = |message: String| ReadErrorKind::Invalid {
            at: place(at),
            message,
        };
        let accessors = &self.root.accessors;
        let accessor = accessors.get(index).ok_or_else(|| {
            invalid(format!(
                "the accessor does not exist (the file has {} accessors)",
                accessors.len()
            ))
        })?;
        let (kind, c) = checked_kind(accessor, expect, at)?;
        let components = kind.multiplicity();
        let size = c.size();
        let element = components * size;
        let count = accessor.count.0;
        let normalized = accessor.normalized;
        let mut values = match accessor.buffer_view {
            None => {
                self.take(count, true, at)?;
                vec![0.0; count as usize * components]
            }
            Some(view_index) => {
                let view = self.view(view_index.value(), at)?;
                let stride = view.stride.unwrap_or(element);
                if stride < element {
                    return Err(invalid(format!(
                        "buffer view {}'s byteStride of {stride} is less than the {element} \
                         bytes of an element",
                        view_index.value()
                    )));
                }
                let offset = accessor.byte_offset.map_or(0, |o| o.0);
                let needed = count.checked_sub(1).map_or(Some(0), |last| {
                    last.checked_mul(stride as u64)
                        .and_then(|b| b.checked_add(offset))
                        .and_then(|b| b.checked_add(element as u64))
                });
                match needed {
                    Some(n) if n <= view.bytes.len() as u64 => {}
                    _ => {
                        return Err(invalid(format!(
                            "{count} elements of {element} bytes every {stride} bytes from \
                             byte {offset} reach past the {} bytes of buffer view {}",
                            view.bytes.len(),
                            view_index.value()
                        )));
                    }
                }
                self.take(count, false, at)?;
                let offset = offset as usize;
                let mut values = Vec::with_capacity(count as usize * components);
                for e in 0..count as usize {
                    let start = offset + e * stride;
                    for k in 0..components {
                        values.push(component(view.bytes, start + k * size, c, normalized));
                    }
                }
                values
            }
        };
        if let Some(sparse) = &accessor.sparse {
            self.apply_sparse(sparse, count, c, components, normalized, &mut values, at)?;
        }
        Ok(values)
    }

    /// Replaces the elements a sparse accessor lists.
    #[allow(clippy::too_many_arguments)]
    fn apply_sparse(
        &mut self,
        sparse: &json::accessor::sparse::Sparse,
        count: u64,
        c: ComponentType,
        components: usize,
        normalized: bool,
        values: &mut [f64],
        at: GltfPlace,
    ) -> Result<(), ReadErrorKind> {
        let invalid = |message: String| ReadErrorKind::Invalid {
            at: place(at),
            message,
        };
        let n = sparse.count.0;
        if n > count {
            return Err(invalid(format!(
                "sparse: {n} substitutions for {count} elements"
            )));
        }
        let index_type = match sparse.indices.component_type {
            Checked::Valid(t) => t.0,
            Checked::Invalid => {
                return Err(invalid(
                    "sparse: the indices' componentType is not valid".into(),
                ));
            }
        };
        let section = |this: &Self, view: usize, offset: u64, each: usize, what: &str| {
            let bytes = this.view(view, at)?.bytes;
            let needed = n
                .checked_mul(each as u64)
                .and_then(|b| b.checked_add(offset));
            match needed {
                Some(end) if end <= bytes.len() as u64 => Ok(&bytes[offset as usize..]),
                _ => Err(invalid(format!(
                    "sparse: {n} {what} of {each} bytes from byte {offset} reach past the {} \
                     bytes of buffer view {view}",
                    bytes.len()
                ))),
            }
        };
        let index_size = index_type.size();
        let indices = section(
            self,
            sparse.indices.buffer_view.value(),
            sparse.indices.byte_offset.0,
            index_size,
            "indices",
        )?;
        let value_size = components * c.size();
        let substitutes = section(
            self,
            sparse.values.buffer_view.value(),
            sparse.values.byte_offset.0,
            value_size,
            "values",
        )?;
        self.take(n, false, at)?;
        for k in 0..n as usize {
            let target = component(indices, k * index_size, index_type, false);
            if target >= count as f64 {
                return Err(invalid(format!(
                    "sparse: substitution {k} is for element {target}, past the {count} \
                     elements"
                )));
            }
            let target = target as usize;
            for j in 0..components {
                values[target * components + j] =
                    component(substitutes, k * value_size + j * c.size(), c, normalized);
            }
        }
        Ok(())
    }

    /// Whether accessor `index` exists and has a buffer view (its data is in a buffer,
    /// not all zeros or only in an extension such as Draco's).
    pub fn has_view(&self, index: usize) -> bool {
        self.root
            .accessors
            .get(index)
            .is_some_and(|a| a.buffer_view.is_some() || a.sparse.is_some())
    }
}

/// The type and component type of `accessor`, when they are ones `expect` allows.
///
/// # Errors
/// Naming the accessor (`at`): another type or component type, or one glTF does not define.
fn checked_kind(
    accessor: &json::Accessor,
    expect: &Expect,
    at: GltfPlace,
) -> Result<(Type, ComponentType), ReadErrorKind> {
    let invalid = |message: String| ReadErrorKind::Invalid {
        at: place(at),
        message,
    };
    let kind = match accessor.type_ {
        Checked::Valid(t) if t == expect.kind => t,
        Checked::Valid(t) => {
            return Err(invalid(format!(
                "{} must be {}, not {}",
                expect.what,
                type_name(expect.kind),
                type_name(t)
            )));
        }
        Checked::Invalid => return Err(invalid("the accessor's type is not valid".into())),
    };
    let c = match accessor.component_type {
        Checked::Valid(c) if expect.components.contains(&c.0) => c.0,
        Checked::Valid(c) => {
            let allowed: Vec<_> = expect
                .components
                .iter()
                .map(|&c| component_name(c))
                .collect();
            return Err(invalid(format!(
                "{} cannot have {} components (it may have {})",
                expect.what,
                component_name(c.0),
                allowed.join(", ")
            )));
        }
        Checked::Invalid => {
            return Err(invalid("the accessor's componentType is not valid".into()));
        }
    };
    Ok((kind, c))
}
