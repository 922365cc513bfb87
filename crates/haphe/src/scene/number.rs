//! How a message shows a number.

use std::fmt;

/// A number as a message shows it: plainly (`-5`, `0.001`, `1000000`), or with an exponent
/// when very large or very small (`1e308`, `1e-9`), never three hundred digits.
pub(crate) struct Number(pub(crate) f64);

impl fmt::Display for Number {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let a = self.0.abs();
        if a.is_finite() && (a >= 1e7 || (a < 1e-4 && a != 0.0)) {
            write!(f, "{:e}", self.0)
        } else {
            write!(f, "{}", self.0)
        }
    }
}
