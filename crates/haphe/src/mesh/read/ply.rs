//! PLY reader (to be written).

use crate::mesh::{Mesh, ReadErrorKind};

/// Reads PLY bytes into a mesh in file units.
pub(super) fn read_ply(_bytes: &[u8]) -> Result<Mesh, ReadErrorKind> {
    Err(ReadErrorKind::UnknownFormat {
        reason: "PLY reader not written yet".into(),
    })
}
