//! The error of a value refused by the table of domains (`domain.rs`), whichever front end
//! it came from (code, a scene file, command-line flags, Python, C).

use std::fmt;

use super::number::Number;
use super::param::Param;

/// A value refused: which parameter, what it was, what it must be. `Copy`, no allocation.
///
/// Its message names the parameter as the library spells it (`max_force must be a finite
/// number above 0 and at most 100 N, not -1`); [`ParamError::named`] spells it as a front
/// end does (`--max-force`, a keyword argument).
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ParamError {
    /// The value is not finite or outside its parameter's domain.
    OutOfDomain {
        /// The parameter.
        param: Param,
        /// The value given (a vector's length).
        value: f64,
    },
    /// A component of a vector is not finite.
    NotFinite {
        /// The parameter.
        param: Param,
        /// The first component that is not finite.
        value: f64,
    },
    /// The dynamic friction coefficient exceeds the static one (the proxy's friction rule
    /// slips back to the dynamic cone once outside the static one, so it must be the
    /// narrower).
    FrictionOrder {
        /// The static coefficient.
        static_friction: f64,
        /// The dynamic coefficient given.
        dynamic_friction: f64,
    },
}

impl ParamError {
    /// The parameter refused.
    pub fn param(&self) -> Param {
        match *self {
            ParamError::OutOfDomain { param, .. } | ParamError::NotFinite { param, .. } => param,
            ParamError::FrictionOrder { .. } => Param::DynamicFriction,
        }
    }

    /// The value refused (a vector's length, or its first non-finite component).
    pub fn value(&self) -> f64 {
        match *self {
            ParamError::OutOfDomain { value, .. } | ParamError::NotFinite { value, .. } => value,
            ParamError::FrictionOrder {
                dynamic_friction, ..
            } => dynamic_friction,
        }
    }

    /// The message with the parameter spelled `name` (a flag, a keyword argument).
    pub fn named<'a>(&'a self, name: &'a str) -> impl fmt::Display + 'a {
        Named { error: self, name }
    }

    fn write(&self, f: &mut fmt::Formatter<'_>, name: &str) -> fmt::Result {
        match *self {
            ParamError::OutOfDomain { param, value } => {
                write!(
                    f,
                    "{name} must be {}, not {}",
                    param.domain(),
                    Number(value)
                )
            }
            ParamError::NotFinite { value, .. } => {
                write!(
                    f,
                    "{name} must be finite in every component, not {}",
                    Number(value)
                )
            }
            ParamError::FrictionOrder {
                static_friction,
                dynamic_friction,
            } => write!(
                f,
                "{name} must be at most static_friction ({static_friction}), not {dynamic_friction}"
            ),
        }
    }
}

impl fmt::Display for ParamError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.write(f, self.param().name())
    }
}

/// A [`ParamError`] spelled with another name.
struct Named<'a> {
    error: &'a ParamError,
    name: &'a str,
}

impl fmt::Display for Named<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.error.write(f, self.name)
    }
}
