//! Texture and effect specifications as the front ends spell them (`sine:0.0002:0.002`,
//! `viscosity:2:box:0:0:0:0.1:0.1:0.1`): a kind, then numbers separated by colons.

use super::invalid::ParamError;

/// A texture or effect specification refused, with the text given. Front ends put the
/// flag, the keyword or the scene file's line before it.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SpecError {
    /// The kind (the text before the first colon) is not one of `known`.
    #[error("`{spec}`: unknown kind `{kind}` (expected one of {known})")]
    UnknownKind {
        /// The specification.
        spec: String,
        /// The kind given.
        kind: String,
        /// The kinds there are.
        known: &'static str,
    },
    /// The kind takes other values than those given.
    #[error("`{spec}`: expected {form}")]
    Form {
        /// The specification.
        spec: String,
        /// What it should look like.
        form: &'static str,
    },
    /// A value is not a number.
    #[error("`{spec}`: `{value}` is not a number")]
    NotANumber {
        /// The specification.
        spec: String,
        /// The value given.
        value: String,
    },
    /// A value is outside its parameter's domain.
    #[error("`{spec}`: {error}")]
    Param {
        /// The specification.
        spec: String,
        /// Which parameter and why.
        #[source]
        error: ParamError,
    },
    /// A height image refused: its file (unreadable, not a PNG, no pixels, too large) or
    /// the values given for it.
    #[error("{image}: {reason}")]
    HeightImage {
        /// The image file, or "height image values".
        image: String,
        /// Why.
        reason: String,
    },
    /// An image could not be used.
    #[error("`{spec}`: {path}: {reason}")]
    Image {
        /// The specification.
        spec: String,
        /// The image file.
        path: String,
        /// Why.
        reason: String,
    },
}

/// A specification split at its colons: the kind and the rest.
pub(crate) struct Spec<'a> {
    pub(crate) text: &'a str,
    pub(crate) kind: &'a str,
    pub(crate) values: Vec<&'a str>,
}

impl<'a> Spec<'a> {
    pub(crate) fn split(text: &'a str) -> Spec<'a> {
        let mut parts = text.trim().split(':');
        let kind = parts.next().unwrap_or("").trim();
        Spec {
            text,
            kind,
            values: parts.map(str::trim).collect(),
        }
    }

    /// An error of this specification.
    pub(crate) fn unknown(&self, known: &'static str) -> SpecError {
        SpecError::UnknownKind {
            spec: self.text.to_owned(),
            kind: self.kind.to_owned(),
            known,
        }
    }

    pub(crate) fn form(&self, form: &'static str) -> SpecError {
        SpecError::Form {
            spec: self.text.to_owned(),
            form,
        }
    }

    pub(crate) fn param(&self, error: ParamError) -> SpecError {
        SpecError::Param {
            spec: self.text.to_owned(),
            error,
        }
    }

    /// The values as numbers, exactly `N` of them (else `form`).
    pub(crate) fn numbers<const N: usize>(
        &self,
        form: &'static str,
    ) -> Result<[f64; N], SpecError> {
        if self.values.len() != N {
            return Err(self.form(form));
        }
        let mut out = [0.0; N];
        for (o, v) in out.iter_mut().zip(&self.values) {
            *o = number(self.text, v)?;
        }
        Ok(out)
    }
}

/// `v` as a number (`nan` and `inf` read as such, for the domain to refuse by name).
pub(crate) fn number(spec: &str, v: &str) -> Result<f64, SpecError> {
    v.parse::<f64>().map_err(|_| SpecError::NotANumber {
        spec: spec.to_owned(),
        value: v.to_owned(),
    })
}
