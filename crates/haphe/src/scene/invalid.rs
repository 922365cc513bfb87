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
    /// A length larger than the scene it is for (a tool radius above the diagonal of the
    /// box bounding the scene's objects: the whole scene would fit inside the tool).
    LargerThanScene {
        /// The parameter.
        param: Param,
        /// The value given, metres.
        value: f64,
        /// The diagonal of the box bounding the scene's objects, metres.
        diagonal: f64,
    },
    /// A texture's bumps steeper than a slope of 1 (`amplitude > wavelength / 2π`): the
    /// force across the surface would outgrow the force into it.
    TooSteep {
        /// The amplitude given, metres.
        amplitude: f64,
        /// The wavelength given, metres.
        wavelength: f64,
    },
    /// A frequency above half the servo rate, which the servo cannot render (it would be
    /// felt as a slower alias).
    AboveHalfRate {
        /// The parameter.
        param: Param,
        /// The frequency given, Hz.
        value: f64,
        /// The servo rate, Hz.
        rate: f64,
    },
}

impl ParamError {
    /// The parameter refused.
    pub fn param(&self) -> Param {
        match *self {
            ParamError::OutOfDomain { param, .. }
            | ParamError::NotFinite { param, .. }
            | ParamError::LargerThanScene { param, .. }
            | ParamError::AboveHalfRate { param, .. } => param,
            ParamError::FrictionOrder { .. } => Param::DynamicFriction,
            ParamError::TooSteep { .. } => Param::TextureAmplitude,
        }
    }

    /// The value refused (a vector's length, or its first non-finite component).
    pub fn value(&self) -> f64 {
        match *self {
            ParamError::OutOfDomain { value, .. }
            | ParamError::NotFinite { value, .. }
            | ParamError::LargerThanScene { value, .. }
            | ParamError::AboveHalfRate { value, .. } => value,
            ParamError::TooSteep { amplitude, .. } => amplitude,
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
            ParamError::LargerThanScene {
                value, diagonal, ..
            } => write!(
                f,
                "{name} must be at most {} m, the diagonal of the box bounding the scene's objects (a larger tool holds the whole scene), not {}",
                Floor4(diagonal),
                Number(value)
            ),
            ParamError::TooSteep {
                amplitude,
                wavelength,
            } => write!(
                f,
                "{name} must be at most the wavelength / 2π ({}, a slope of 1: steeper bumps push sideways harder than into the surface), not {}",
                Floor4(wavelength / std::f64::consts::TAU),
                Number(amplitude)
            ),
            ParamError::AboveHalfRate { value, rate, .. } => write!(
                f,
                "{name} must be at most half the servo rate ({} Hz at {} Hz), not {}",
                Number(rate / 2.0),
                Number(rate),
                Number(value)
            ),
        }
    }
}

/// A positive length shown to four significant digits, rounded down: a limit a message
/// states is then never above the true one (`0.1732` for 0.17320508 m).
struct Floor4(f64);

impl fmt::Display for Floor4 {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if !(self.0.is_finite() && self.0 > 0.0) {
            return write!(f, "{}", Number(self.0));
        }
        let exponent = self.0.log10().floor() as i32;
        let unit = 10f64.powi(exponent - 3);
        let decimals = (3 - exponent).clamp(0, 300) as usize;
        write!(f, "{:.*}", decimals, (self.0 / unit).floor() * unit)
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
