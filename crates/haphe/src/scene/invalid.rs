//! One check for the numbers a user gives a scene — materials, motions, the device's force
//! limit — whichever front end they come from (a scene file, command-line flags, code).

/// A value refused by a check: which one, what it was, what it must be.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{field} must be {expected}, not {value}")]
pub struct InvalidValue {
    /// The value's name as front ends spell it (`stiffness`, `motion frequency`).
    pub field: &'static str,
    /// The value given (a vector's offending component or length).
    pub value: f64,
    /// What it must be, in words.
    pub expected: String,
}

impl InvalidValue {
    /// Checks that `value` is finite and within `low..=high`.
    ///
    /// # Errors
    /// Naming `field`, when it is not.
    pub fn check_range(
        field: &'static str,
        value: f64,
        low: f64,
        high: f64,
    ) -> Result<f64, InvalidValue> {
        if value.is_finite() && (low..=high).contains(&value) {
            Ok(value)
        } else {
            Err(InvalidValue {
                field,
                value,
                expected: if high == f64::MAX {
                    format!("a finite number of at least {low}")
                } else {
                    format!("a finite number from {low} to {high}")
                },
            })
        }
    }

    /// Checks that every component of `v` is finite and its length at most `max`.
    ///
    /// # Errors
    /// Naming `field`, when it is not.
    pub fn check_vector(
        field: &'static str,
        v: glam::DVec3,
        max: f64,
    ) -> Result<glam::DVec3, InvalidValue> {
        if let Some(&bad) = v.to_array().iter().find(|x| !x.is_finite()) {
            return Err(InvalidValue {
                field,
                value: bad,
                expected: "finite in every component".into(),
            });
        }
        if v.length() > max {
            return Err(InvalidValue {
                field,
                value: v.length(),
                expected: format!("at most {max} long"),
            });
        }
        Ok(v)
    }
}

/// The largest maximum force accepted, newtons (no desktop device renders more than a
/// few tens of newtons; larger values are typing mistakes).
pub const MAX_FORCE_LIMIT_N: f64 = 1e4;

/// Checks a device's or proxy's maximum force: finite, from 0 to [`MAX_FORCE_LIMIT_N`].
///
/// # Errors
/// An [`InvalidValue`] naming `max_force`.
pub fn check_max_force(max_force: f64) -> Result<f64, InvalidValue> {
    InvalidValue::check_range("max_force", max_force, 0.0, MAX_FORCE_LIMIT_N)
}
