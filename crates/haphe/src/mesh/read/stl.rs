//! STL reader (to be written).

use crate::mesh::{Mesh, ReadErrorKind};

/// Reads STL bytes into a mesh in file units.
pub(super) fn read_stl(_bytes: &[u8]) -> Result<Mesh, ReadErrorKind> {
    Err(ReadErrorKind::UnknownFormat {
        reason: "STL reader not written yet".into(),
    })
}

/// True when the size matches a binary STL's triangle count.
pub(super) fn looks_binary(_bytes: &[u8]) -> bool {
    false
}
