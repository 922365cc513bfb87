//! The table of domains: every number a user gives the library, its unit, its lowest and
//! highest usable value, and whether 0 is one of them. Constructors check against it
//! (`Material::new`, `ProxyOptions::with_max_force`, `Pose::new`, `ServoOptions::new`,
//! `DeviceMapping::new`, `Motion::checked`), and the front ends (the command, Python, C)
//! use those constructors and no checks of their own.
//!
//! Every domain refuses NaN and ±∞. Its upper bound is where a value stops being a
//! setting and becomes a typing mistake (a stiffness above 10⁶ N/m, a force above 100 N):
//! no desktop device renders such values, and a unit mixed up (millimetres for metres,
//! N/mm for N/m) lands there.

use std::fmt;

use super::invalid::ParamError;
use super::number::Number;
use super::param::Param;

/// What is checked of a value: a number, or a vector (finite in every component, its
/// length within the bounds).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DomainKind {
    /// One number.
    Number,
    /// A vector (or quaternion): every component finite, the length within the bounds.
    Vector,
}

/// The usable values of a [`Param`]: finite, from `low` (excluded when `low_open`) to
/// `high` (above it: absurd).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Domain {
    /// The parameter.
    pub param: Param,
    /// A number or a vector's length.
    pub kind: DomainKind,
    /// The unit, SI (empty for a coefficient).
    pub unit: &'static str,
    /// The lowest usable value.
    pub low: f64,
    /// Whether `low` itself is refused (as 0 is for a skin or a scale).
    pub low_open: bool,
    /// The highest usable value; above it a value is absurd (a unit mixed up, a typo).
    pub high: f64,
}

/// The largest force accepted, newtons: desktop devices render a few newtons, the largest
/// arms a few tens.
pub const ABSURD_FORCE_N: f64 = 100.0;
/// The largest force a device renders unless told otherwise, newtons: that of a common
/// desktop device (a 3D Systems Touch renders 3.3 N), inside [`Param::MaxForce`]. The
/// default of the proxy ([`ProxyOptions`](crate::proxy::ProxyOptions)), the simulated
/// devices, the network device, the mouse, the command's `--max-force` and the Python and
/// C bindings.
pub const DEFAULT_MAX_FORCE_N: f64 = 3.3;
/// The largest stiffness accepted, N/m: desktop devices render a few thousand.
pub const ABSURD_STIFFNESS_N_PER_M: f64 = 1e6;
/// The farthest distance from the world origin accepted, metres (positions, centres,
/// workspace radii): far beyond any workspace, small enough that squares stay finite.
pub const ABSURD_DISTANCE_M: f64 = 1e9;

/// The largest tool radius accepted, metres: a hand-held tool, a fingertip or a ball tool
/// is millimetres to centimetres across; a radius of metres is a unit mixed up.
pub(crate) const ABSURD_TOOL_RADIUS_M: f64 = 0.5;

/// Every parameter's domain, in the order of [`Param`].
static TABLE: [Domain; 31] = [
    number(Param::Stiffness, "N/m", 0.0, true, ABSURD_STIFFNESS_N_PER_M),
    number(Param::Damping, "N·s/m", 0.0, false, 1e3),
    number(Param::StaticFriction, "", 0.0, false, 10.0),
    number(Param::DynamicFriction, "", 0.0, false, 10.0),
    number(Param::MaxForce, "N", 0.0, true, ABSURD_FORCE_N),
    number(Param::Skin, "m", 0.0, true, 1e-3),
    number(Param::WorkspaceRadius, "m", 0.0, true, ABSURD_DISTANCE_M),
    number(Param::ToolRadius, "m", 0.0, false, ABSURD_TOOL_RADIUS_M),
    vector(Param::Position, "m", 0.0, false, ABSURD_DISTANCE_M),
    vector(Param::Rotation, "", 0.0, true, f64::MAX),
    number(Param::RateHz, "Hz", 1.0, false, 40_000.0),
    number(Param::RampSeconds, "s", 0.0, false, 60.0),
    number(Param::SpinSeconds, "s", 0.0, false, 1.0),
    number(Param::Scale, "", 0.0, true, 1e6),
    vector(Param::Centre, "m", 0.0, false, ABSURD_DISTANCE_M),
    vector(Param::MotionVelocity, "m/s", 0.0, false, 100.0),
    vector(Param::MotionAmplitude, "m", 0.0, false, 100.0),
    number(Param::MotionFrequency, "Hz", 0.0, false, 500.0),
    vector(Param::MotionAxis, "", 0.0, true, f64::MAX),
    number(Param::MotionRate, "rad/s", -1000.0, false, 1000.0),
    number(Param::TextureAmplitude, "m", 0.0, false, 0.01),
    number(Param::TextureWavelength, "m", 0.0, true, 1.0),
    number(Param::VibrationFrequency, "Hz", 0.0, true, 20_000.0),
    vector(Param::EffectForce, "N", 0.0, false, ABSURD_FORCE_N),
    number(Param::Viscosity, "N·s/m", 0.0, false, 1e3),
    number(
        Param::EffectStiffness,
        "N/m",
        0.0,
        false,
        ABSURD_STIFFNESS_N_PER_M,
    ),
    number(Param::MagnetDistance, "m", 0.0, true, 1.0),
    number(Param::CutForce, "N", 0.0, false, ABSURD_FORCE_N),
    number(Param::CutRate, "m/s", 0.0, true, 10.0),
    number(Param::VoxelSize, "m", 0.0, true, 1.0),
    number(Param::LayerValue, "", -f64::MAX, false, f64::MAX),
];

const fn number(param: Param, unit: &'static str, low: f64, low_open: bool, high: f64) -> Domain {
    Domain {
        param,
        kind: DomainKind::Number,
        unit,
        low,
        low_open,
        high,
    }
}

const fn vector(param: Param, unit: &'static str, low: f64, low_open: bool, high: f64) -> Domain {
    Domain {
        kind: DomainKind::Vector,
        ..number(param, unit, low, low_open, high)
    }
}

impl Param {
    /// The parameter's domain.
    pub const fn domain(self) -> &'static Domain {
        &TABLE[self as usize]
    }

    /// `value` when it lies in the domain.
    ///
    /// # Errors
    /// [`ParamError::OutOfDomain`] naming this parameter, when it does not.
    pub fn check(self, value: f64) -> Result<f64, ParamError> {
        if self.domain().contains(value) {
            Ok(value)
        } else {
            Err(ParamError::OutOfDomain { param: self, value })
        }
    }

    /// `v` when every component is finite and its length lies in the domain.
    ///
    /// # Errors
    /// [`ParamError::NotFinite`] with the first non-finite component, or
    /// [`ParamError::OutOfDomain`] with the length.
    pub fn check_vector<const N: usize>(self, v: [f64; N]) -> Result<[f64; N], ParamError> {
        if let Some(&value) = v.iter().find(|x| !x.is_finite()) {
            return Err(ParamError::NotFinite { param: self, value });
        }
        // Scaled by the largest component, so that a length near f64::MAX is reported as
        // itself rather than as the infinity its squares overflow to.
        let largest = v.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        let length = if largest > 0.0 {
            largest * v.iter().map(|x| (x / largest).powi(2)).sum::<f64>().sqrt()
        } else {
            0.0
        };
        self.check(length).map(|_| v)
    }
}

impl Domain {
    /// Whether `value` is finite and within the bounds.
    pub fn contains(&self, value: f64) -> bool {
        value.is_finite()
            && value <= self.high
            && if self.low_open {
                value > self.low
            } else {
                value >= self.low
            }
    }

    /// Whether 0 is usable (for a vector: the zero vector).
    pub fn allows_zero(&self) -> bool {
        self.contains(0.0)
    }
}

impl fmt::Display for Domain {
    /// In words: `a finite number above 0 and at most 100 N`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let unit = if self.unit.is_empty() {
            String::new()
        } else {
            format!(" {}", self.unit)
        };
        let what = match self.kind {
            DomainKind::Number => "a finite number",
            DomainKind::Vector => "finite with a length",
        };
        let (low, high) = (Number(self.low), Number(self.high));
        match (self.low_open, self.high == f64::MAX) {
            (true, true) => write!(f, "{what} above {low}{unit}"),
            (false, true) => write!(f, "{what} of at least {low}{unit}"),
            (true, false) => write!(f, "{what} above {low} and at most {high}{unit}"),
            (false, false) if self.low == 0.0 && self.kind == DomainKind::Vector => {
                write!(f, "{what} of at most {high}{unit}")
            }
            (false, false) => write!(f, "{what} from {low} to {high}{unit}"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_maximum_force_is_inside_its_domain() {
        assert_eq!(
            Param::MaxForce.check(DEFAULT_MAX_FORCE_N),
            Ok(DEFAULT_MAX_FORCE_N)
        );
    }

    #[test]
    fn the_table_is_in_the_order_of_the_params() {
        for p in Param::ALL {
            assert_eq!(p.domain().param, p);
        }
    }

    #[test]
    fn domains_read_as_words() {
        assert_eq!(
            Param::MaxForce.domain().to_string(),
            "a finite number above 0 and at most 100 N"
        );
        assert_eq!(
            Param::Damping.domain().to_string(),
            "a finite number from 0 to 1000 N·s/m"
        );
        assert_eq!(
            Param::Position.domain().to_string(),
            "finite with a length of at most 1e9 m"
        );
    }
}
