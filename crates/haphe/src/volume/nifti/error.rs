//! Why a NIfTI-1 file could not be read: the file's name, then the header field, the byte
//! count or the voxel.

use crate::volume::VolumeError;

/// A volume file could not be read: each variant names the file (the name the caller gave
/// for the bytes, usually the path) and the place: the header field, the byte counts, the
/// voxel.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ReadVolumeError {
    /// A NIfTI-2 file (`sizeof_hdr` 540).
    #[error("{file}: NIfTI-2 is not supported; convert to NIfTI-1 (sizeof_hdr is 540)")]
    Nifti2 {
        /// The file.
        file: String,
    },
    /// Not a single-file NIfTI-1 file: `sizeof_hdr` is not 348 or the magic is not `n+1`.
    #[error("{file}: not a NIfTI-1 file: {reason}")]
    NotNifti {
        /// The file.
        file: String,
        /// Which field says so, and its value.
        reason: String,
    },
    /// A header field whose value cannot be used.
    #[error("{file}: header field {field}: {message}")]
    Header {
        /// The file.
        file: String,
        /// The field as the NIfTI-1 standard names it (`dim[0]`, `datatype`, `vox_offset`).
        field: &'static str,
        /// Its value and why it cannot be used.
        message: String,
    },
    /// The file (or its decompressed stream) ends before what its header announces.
    #[error(
        "{file}: the {what} ends early: {available} bytes of the {needed} its header announces"
    )]
    Truncated {
        /// The file.
        file: String,
        /// `"file"`, or `"decompressed stream"` for a gzip file.
        what: &'static str,
        /// The bytes the header announces: `sizeof_hdr`, or up to the end of the first
        /// volume's data (`vox_offset` plus its voxels' bytes).
        needed: u64,
        /// The bytes there are.
        available: u64,
    },
    /// A gzip stream that cannot be decompressed.
    #[error("{file}: gzip: {message}")]
    Gzip {
        /// The file.
        file: String,
        /// What the decompressor found.
        message: String,
    },
    /// The values and the affine do not make a volume (a NaN voxel, a singular affine).
    #[error("{file}: {error}")]
    Volume {
        /// The file.
        file: String,
        /// Why, and where (the voxel).
        error: VolumeError,
    },
}

impl ReadVolumeError {
    /// The error with `name` as its file (the readers below `read_nifti` leave it empty).
    pub(super) fn in_file(mut self, name: &str) -> ReadVolumeError {
        match &mut self {
            ReadVolumeError::Nifti2 { file }
            | ReadVolumeError::NotNifti { file, .. }
            | ReadVolumeError::Header { file, .. }
            | ReadVolumeError::Truncated { file, .. }
            | ReadVolumeError::Gzip { file, .. }
            | ReadVolumeError::Volume { file, .. } => *file = name.to_owned(),
        }
        self
    }
}

impl From<VolumeError> for ReadVolumeError {
    fn from(error: VolumeError) -> ReadVolumeError {
        ReadVolumeError::Volume {
            file: String::new(),
            error,
        }
    }
}

/// A [`ReadVolumeError::NotNifti`] (its file filled in by `read_nifti`).
pub(super) fn not_nifti(reason: String) -> ReadVolumeError {
    ReadVolumeError::NotNifti {
        file: String::new(),
        reason,
    }
}

/// A [`ReadVolumeError::Header`] (its file filled in by `read_nifti`).
pub(super) fn header_error(field: &'static str, message: String) -> ReadVolumeError {
    ReadVolumeError::Header {
        file: String::new(),
        field,
        message,
    }
}

/// A [`ReadVolumeError::Truncated`] (its file filled in by `read_nifti`).
pub(super) fn truncated(what: &'static str, needed: u64, available: u64) -> ReadVolumeError {
    ReadVolumeError::Truncated {
        file: String::new(),
        what,
        needed,
        available,
    }
}
