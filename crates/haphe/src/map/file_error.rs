//! Why a map file could not be loaded, and where in the file.

use super::file::CHECKSUM_AT;

/// Why a map file could not be loaded.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum MapFileError {
    /// The file does not start with the magic bytes `HAPHEMAP`: not a haphe map file.
    #[error("not a haphe map file: it starts with {found:?}, not \"HAPHEMAP\"", found = String::from_utf8_lossy(found))]
    WrongMagic {
        /// The first eight bytes.
        found: [u8; 8],
    },
    /// A map file of another format version.
    #[error(
        "map file format version {found} is not supported (this build reads version \
         {supported}); rebuild the map from its mesh"
    )]
    UnsupportedVersion {
        /// The version in the file.
        found: u32,
        /// The version this build reads (`FORMAT_VERSION`).
        supported: u32,
    },
    /// The file is shorter than its header says (or than a header).
    #[error("truncated map file: {found} bytes, expected {expected}")]
    Truncated {
        /// Bytes the header promises (or the header's size).
        expected: u64,
        /// Bytes present.
        found: u64,
    },
    /// The file is longer than its header says.
    #[error("map file has {found} bytes, but its header says {expected}: trailing bytes")]
    TrailingBytes {
        /// Bytes the header promises.
        expected: u64,
        /// Bytes present.
        found: u64,
    },
    /// The checksum does not match: the file is damaged.
    #[error(
        "map file checksum mismatch (stored {stored:#018x}, computed {computed:#018x}): the \
         file is damaged"
    )]
    ChecksumMismatch {
        /// The checksum in the header.
        stored: u64,
        /// The checksum of the content.
        computed: u64,
    },
    /// The checksum matches but the content breaks an invariant (a file written by a
    /// faulty or hostile program).
    #[error("invalid map file, section '{section}': {reason}")]
    Invalid {
        /// The section at fault.
        section: &'static str,
        /// What is wrong, with indices.
        reason: String,
    },
}

impl MapFileError {
    /// Where in the file the error was found: a byte offset of the header and the field's
    /// name, or (for [`MapFileError::Invalid`]) the section's name alone.
    pub fn place(&self) -> (Option<u64>, &'static str) {
        match self {
            MapFileError::WrongMagic { .. } => (Some(0), "magic"),
            MapFileError::UnsupportedVersion { .. } => (Some(8), "format version"),
            MapFileError::Truncated { .. } | MapFileError::TrailingBytes { .. } => {
                (Some(16), "file length")
            }
            MapFileError::ChecksumMismatch { .. } => (Some(CHECKSUM_AT as u64), "checksum"),
            MapFileError::Invalid { section, .. } => (None, section),
        }
    }
}

/// Shorthand for an [`MapFileError::Invalid`].
pub(crate) fn invalid(section: &'static str, reason: impl Into<String>) -> MapFileError {
    MapFileError::Invalid {
        section,
        reason: reason.into(),
    }
}
