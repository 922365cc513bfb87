//! The error of a scene file, and the limit on its objects.

/// A scene file that cannot be used: the message names the file, and the object and the
/// line where there is one.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{message}")]
pub struct SceneFileError {
    /// The whole message, starting with the file's name.
    pub message: String,
}

pub(super) fn fail(message: String) -> SceneFileError {
    SceneFileError { message }
}

/// Most objects a scene file may hold, its grids' copies included.
pub const MAX_OBJECTS: usize = 1_000_000;
