//! How the glTF reader names a place in a file.

use crate::mesh::{GltfPlace, Place};

/// An index of the file's arrays as a place names it (an index beyond `u32::MAX`, which
/// no array of a file within the size limits has, is named as `u32::MAX`).
pub(super) fn ix(index: usize) -> u32 {
    u32::try_from(index).unwrap_or(u32::MAX)
}

pub(super) fn place(at: GltfPlace) -> Place {
    Place::Gltf(at)
}
