//! Where a map came from: the source mesh file's name, size and content hash, saved in the
//! map file so that a map is never taken for the map of another mesh.

use serde::{Deserialize, Serialize};

/// Longest file name a map file records, in bytes (longer names are cut at a character
/// boundary when recorded).
pub const MAX_SOURCE_NAME_BYTES: usize = 1024;

/// The mesh file a map was built from: its name (the last component of its path), its size
/// and the XXH3-128 hash of its bytes.
///
/// The hash tells files apart, it does not authenticate them: XXH3 is fast (gigabytes per
/// second) and collisions between different meshes are practically impossible by chance,
/// but anyone can craft one on purpose.
///
/// # Examples
/// ```
/// use haphe::map::Provenance;
/// let p = Provenance::of("meshes/part.stl", b"solid part\nendsolid part\n");
/// assert_eq!((p.file.as_str(), p.bytes), ("part.stl", 25));
/// assert!(p.matches(b"solid part\nendsolid part\n"));
/// assert!(!p.matches(b"solid other\nendsolid other\n"));
/// assert_eq!(p.hash_hex().len(), 32);
/// ```
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Provenance {
    /// The file's name, without its folder.
    pub file: String,
    /// Its size in bytes.
    pub bytes: u64,
    /// XXH3-128 of its bytes, as 32 lowercase hexadecimal digits.
    pub xxh3_128: String,
}

impl Provenance {
    /// The provenance of the mesh file at `path` whose content is `content`.
    pub fn of(path: &str, content: &[u8]) -> Provenance {
        let name = path.rsplit(['/', '\\']).next().unwrap_or(path);
        let mut end = name.len().min(MAX_SOURCE_NAME_BYTES);
        while !name.is_char_boundary(end) {
            end -= 1;
        }
        Provenance {
            file: name[..end].to_string(),
            bytes: content.len() as u64,
            xxh3_128: hex(xxhash_rust::xxh3::xxh3_128(content)),
        }
    }

    /// Whether `content` is the file this records (same size and hash; the name is not
    /// compared, a renamed copy matches).
    pub fn matches(&self, content: &[u8]) -> bool {
        self.bytes == content.len() as u64
            && self.xxh3_128 == hex(xxhash_rust::xxh3::xxh3_128(content))
    }

    /// The hash, 32 hexadecimal digits.
    pub fn hash_hex(&self) -> &str {
        &self.xxh3_128
    }

    /// Why a decoded record cannot be one this crate writes, if it cannot.
    pub(crate) fn problem(&self) -> Option<String> {
        if self.file.len() > MAX_SOURCE_NAME_BYTES {
            return Some(format!(
                "file name of {} bytes, more than {MAX_SOURCE_NAME_BYTES}",
                self.file.len()
            ));
        }
        let digits = self.xxh3_128.as_bytes();
        if digits.len() != 32
            || !digits
                .iter()
                .all(|c| matches!(c, b'0'..=b'9' | b'a'..=b'f'))
        {
            return Some(format!(
                "hash {:?} is not 32 lowercase hexadecimal digits",
                self.xxh3_128
            ));
        }
        None
    }
}

impl std::fmt::Display for Provenance {
    /// `part.stl, 1234 bytes, xxh3-128 0123…`
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{}, {} bytes, xxh3-128 {}",
            self.file, self.bytes, self.xxh3_128
        )
    }
}

/// Why a map file cannot be used as the map of a mesh file: the check every front end
/// makes before it takes a saved map in place of a mesh ([`check_source`]).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum SourceError {
    /// The map records no source, so it cannot be checked.
    #[error(
        "{map} records no source mesh, so it cannot be checked against {mesh}: rebuild it \
         with `haphe build {mesh} -o {map}`"
    )]
    Unrecorded {
        /// The map file.
        map: String,
        /// The mesh file it was checked against.
        mesh: String,
    },
    /// The map was built from other bytes (the mesh changed since, or another mesh).
    #[error(
        "{map} was built from {recorded}, not from {mesh} ({bytes} bytes, xxh3-128 {hash}): \
         rebuild it with `haphe build {mesh} -o {map}`"
    )]
    Stale {
        /// The map file.
        map: String,
        /// The mesh file it was checked against.
        mesh: String,
        /// What the map records.
        recorded: Provenance,
        /// The mesh file's size now.
        bytes: u64,
        /// Its hash now.
        hash: String,
    },
}

/// Checks that the map file `map` (its recorded `provenance`) was built from the mesh file
/// `mesh` whose content is `mesh_bytes`: same size and hash (the name may differ).
///
/// # Errors
/// [`SourceError`], naming both files and how to rebuild the map.
pub fn check_source(
    map: &str,
    provenance: Option<&Provenance>,
    mesh: &str,
    mesh_bytes: &[u8],
) -> Result<(), SourceError> {
    match provenance {
        None => Err(SourceError::Unrecorded {
            map: map.to_owned(),
            mesh: mesh.to_owned(),
        }),
        Some(p) if !p.matches(mesh_bytes) => Err(SourceError::Stale {
            map: map.to_owned(),
            mesh: mesh.to_owned(),
            recorded: p.clone(),
            bytes: mesh_bytes.len() as u64,
            hash: Provenance::of(mesh, mesh_bytes).xxh3_128,
        }),
        Some(_) => Ok(()),
    }
}

fn hex(h: u128) -> String {
    format!("{h:032x}")
}
