//! Library errors as Python exceptions.

use std::path::Path;

use haphe::scene::{Param, ParamError};
use pyo3::create_exception;
use pyo3::exceptions::{PyFileNotFoundError, PyOSError, PyPermissionError, PyValueError};
use pyo3::prelude::*;

create_exception!(
    haphe,
    HapheError,
    PyValueError,
    "A file or an input haphe cannot use: the message names the file and the place."
);

/// A library error as a [`HapheError`], with its message (which names the file and the
/// place) prefixed by `context` when that is not empty.
pub fn haphe_error(context: &str, e: impl std::fmt::Display) -> PyErr {
    if context.is_empty() {
        HapheError::new_err(e.to_string())
    } else {
        HapheError::new_err(format!("{context}: {e}"))
    }
}

/// A value refused by the library's table of domains as a [`HapheError`], the parameter
/// spelled as the keyword argument that gave it (`friction` for the static coefficient).
pub fn param_error(e: ParamError) -> PyErr {
    let name = match e.param() {
        Param::StaticFriction => "friction",
        Param::VoxelSize => "voxel",
        other => other.name(),
    };
    HapheError::new_err(e.named(name).to_string())
}

/// An I/O error on `path` as the matching `OSError` subclass, naming the file.
pub fn io_error(what: &str, path: &Path, e: &std::io::Error) -> PyErr {
    os_error(e.kind(), format!("cannot {what} {}: {e}", path.display()))
}

/// The `OSError` subclass for an error of `kind`, with `message`.
pub fn os_error(kind: std::io::ErrorKind, message: String) -> PyErr {
    match kind {
        std::io::ErrorKind::NotFound => PyFileNotFoundError::new_err(message),
        std::io::ErrorKind::PermissionDenied => PyPermissionError::new_err(message),
        _ => PyOSError::new_err(message),
    }
}
