//! Map files' errors in words a user can act on.

use std::path::Path;

use anyhow::anyhow;
use haphe::map::{MapBytes, MapFileError, VoxelMap, decode_in_place};
use haphe::mesh::Surface;

/// Why the map file `path` cannot be used, in words a user can act on: an older or newer
/// format names the version and how to rebuild; anything else is a damaged map, with the
/// byte offset and field (or the section) where the damage was found.
pub fn map_failure(path: &Path, e: &MapFileError) -> anyhow::Error {
    let file = path.display();
    match e {
        MapFileError::UnsupportedVersion { found, supported }
            if (1..*supported).contains(found) =>
        {
            anyhow!(
                "{file}: a map of format version {found}, written by an older haphe; this one \
                 reads version {supported} (which records the source mesh): rebuild it with \
                 `haphe build MESH -o {file}`"
            )
        }
        MapFileError::UnsupportedVersion { found, supported }
            if (*supported + 1..*supported + 100).contains(found) =>
        {
            anyhow!(
                "{file}: a map of format version {found}, written by a newer haphe; this one \
                 reads version {supported}: use that haphe, or rebuild the map with this one \
                 (`haphe build MESH -o {file}`)"
            )
        }
        MapFileError::WrongMagic { found } => anyhow!(
            "damaged map: {file}: byte 0 (magic): {:?} where \"HAPHEMAP\" should be",
            String::from_utf8_lossy(found)
        ),
        _ => match e.place() {
            (Some(at), field) => anyhow!("damaged map: {file}: byte {at} ({field}): {e}"),
            (None, _) => anyhow!("damaged map: {file}: {e}"),
        },
    }
}

/// Decodes the map file `path` whose bytes are `bytes`, its errors in [`map_failure`]'s words.
pub fn decode_map(path: &Path, bytes: &MapBytes) -> anyhow::Result<(Surface, VoxelMap)> {
    decode_in_place(bytes).map_err(|e| map_failure(path, &e))
}
