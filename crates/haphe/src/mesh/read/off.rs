//! OFF reader (to be written).

use crate::mesh::{Mesh, ReadErrorKind};

/// Reads OFF bytes into a mesh in file units.
pub(super) fn read_off(_bytes: &[u8]) -> Result<Mesh, ReadErrorKind> {
    Err(ReadErrorKind::UnknownFormat {
        reason: "OFF reader not written yet".into(),
    })
}
