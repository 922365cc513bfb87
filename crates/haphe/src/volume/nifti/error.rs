//! Why a NIfTI-1 file could not be read: the file's name, then the header field, the byte
//! count or the voxel.

use crate::volume::VolumeError;

/// A volume file could not be read: the file's name and what went wrong where.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{file}: {kind}")]
pub struct ReadVolumeError {
    /// The name the caller gave for the bytes (usually the path).
    pub file: String,
    /// What went wrong, and where.
    pub kind: ReadVolumeErrorKind,
}

/// What went wrong while reading a volume file, and where.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ReadVolumeErrorKind {
    /// A NIfTI-2 file (`sizeof_hdr` 540).
    #[error("NIfTI-2 is not supported; convert to NIfTI-1 (sizeof_hdr is 540)")]
    Nifti2,
    /// Not a single-file NIfTI-1 file: `sizeof_hdr` is not 348 or the magic is not `n+1`.
    #[error("not a NIfTI-1 file: {reason}")]
    NotNifti {
        /// Which field says so, and its value.
        reason: String,
    },
    /// A header field whose value cannot be used.
    #[error("header field {field}: {message}")]
    Header {
        /// The field as the NIfTI-1 standard names it (`dim[0]`, `datatype`, `vox_offset`).
        field: &'static str,
        /// Its value and why it cannot be used.
        message: String,
    },
    /// The file (or its decompressed stream) ends before the data the header announces.
    #[error("the {what} ends early: {available} bytes of the {needed} its header announces")]
    Truncated {
        /// `"file"`, or `"decompressed stream"` for a gzip file.
        what: &'static str,
        /// The bytes the header announces: `sizeof_hdr`, or up to the end of the first
        /// volume's data (`vox_offset` plus its voxels' bytes).
        needed: u64,
        /// The bytes there are.
        available: u64,
    },
    /// A gzip stream that cannot be decompressed.
    #[error("gzip: {message}")]
    Gzip {
        /// What the decompressor found.
        message: String,
    },
    /// The values and the affine do not make a volume (a NaN voxel, a singular affine).
    #[error("{0}")]
    Volume(#[from] VolumeError),
}
