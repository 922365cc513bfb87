//! OBJ reader (to be written).

use crate::mesh::{Mesh, ReadErrorKind};

/// Reads OBJ bytes into a mesh in file units.
pub(super) fn read_obj(_bytes: &[u8]) -> Result<Mesh, ReadErrorKind> {
    Err(ReadErrorKind::UnknownFormat {
        reason: "OBJ reader not written yet".into(),
    })
}

/// True when the bytes look like OBJ statements.
pub(super) fn looks_like_obj(_bytes: &[u8]) -> bool {
    false
}
