//! The lengths a generator accepts.

/// True for a length a generator accepts: finite and strictly positive.
pub(super) fn is_positive_length(length_m: f64) -> bool {
    length_m.is_finite() && length_m > 0.0
}
