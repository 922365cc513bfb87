//! What a scene file says of how its objects feel beyond their materials: an object's
//! `texture` and the file's `effects`, parsed by the library's specifications
//! ([`Texture`], [`Effect`]) and refused naming the file and the line.
//!
//! ```toml
//! effects = ["viscosity:2", "spring:100:0:0:0.1"]   # top level, before any object
//!
//! [[object]]
//! shape = "box"
//! texture = "sine:0.0002:0.002"                     # amplitude, wavelength, metres
//! ```

use std::collections::HashSet;

use crate::scene::{Effect, MAX_EFFECTS, ObjectId, Texture, Zone};

use super::error::{SceneFileError, fail, line_of};

/// An effect of a scene file's `effects`, with how it was written and where.
#[derive(Debug, Clone, PartialEq)]
pub struct FileEffect {
    /// The effect, its values checked ([`Effect`]'s domains); the servo rate is the
    /// front end's to check ([`Effect::check_rate`]).
    pub effect: Effect,
    /// The specification as the file writes it.
    pub spec: String,
    /// `FILE: line L: effect`, to name it in later errors (the servo rate).
    pub place: String,
}

/// The texture of an object whose `texture` key is `given`, in the file `file` (its
/// `text`, for the line).
pub(super) fn texture_of(
    given: Option<&toml::Spanned<String>>,
    text: &str,
    file: &str,
) -> Result<Option<Texture>, SceneFileError> {
    given
        .map(|t| {
            t.get_ref().parse::<Texture>().map_err(|e| {
                fail(format!(
                    "{file}: line {}: texture {e}",
                    line_of(text, t.span().start)
                ))
            })
        })
        .transpose()
}

/// The effects of the file `file` (its `text`, for lines), each checked; an effect inside
/// an object must name one of `ids`.
pub(super) fn effects_of(
    given: &[toml::Spanned<String>],
    text: &str,
    file: &str,
    ids: &HashSet<ObjectId>,
) -> Result<Vec<FileEffect>, SceneFileError> {
    if let Some(extra) = given.get(MAX_EFFECTS) {
        return Err(fail(format!(
            "{file}: line {}: effects: {} effects, more than the limit of {MAX_EFFECTS}",
            line_of(text, extra.span().start),
            given.len()
        )));
    }
    given
        .iter()
        .map(|e| {
            let place = format!("{file}: line {}: effect", line_of(text, e.span().start));
            let spec = e.get_ref();
            let effect = spec
                .parse::<Effect>()
                .map_err(|error| fail(format!("{place} {error}")))?;
            if let Some(Zone::Inside(id)) = effect.zone()
                && !ids.contains(&id)
            {
                return Err(fail(format!(
                    "{place} `{spec}`: no object of the file has id {}",
                    id.0
                )));
            }
            Ok(FileEffect {
                effect,
                spec: spec.clone(),
                place,
            })
        })
        .collect()
}
