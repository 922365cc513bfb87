//! The error of a scene file, and the limit on its objects.

/// A scene file that cannot be used: the message names the file, and the object and the
/// line where there is one.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{message}")]
pub struct SceneFileError {
    /// The whole message, starting with the file's name.
    pub message: String,
}

/// 1-based line of a byte offset.
pub(super) fn line_of(text: &str, offset: usize) -> usize {
    text[..offset.min(text.len())].matches('\n').count() + 1
}

pub(super) fn fail(message: String) -> SceneFileError {
    SceneFileError { message }
}

/// Most objects a scene file may hold, its grids' copies included.
pub const MAX_OBJECTS: usize = 1_000_000;
