//! Buttons pressed at given times on a simulated device, for the clutch and for tests.

use super::trajectory::TrajectoryError;
use crate::servo::device::Buttons;

/// One press: `button` (bit index) held from `from` until `until`, seconds.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Press {
    button: u32,
    from: f64,
    until: f64,
}

/// The presses of a simulated device, in the order given.
#[derive(Debug, Clone, Default, PartialEq)]
pub(super) struct Presses(Vec<Press>);

impl Presses {
    /// Adds a press of `button` held over `[from, until)`, seconds.
    ///
    /// # Errors
    /// [`TrajectoryError::Press`] for a button beyond 31, a non-finite time or an empty
    /// interval.
    pub(super) fn add(
        &mut self,
        button: u32,
        from: f64,
        until: f64,
    ) -> Result<(), TrajectoryError> {
        if button >= 32 || !from.is_finite() || !until.is_finite() || from >= until {
            return Err(TrajectoryError::Press { button });
        }
        self.0.push(Press {
            button,
            from,
            until,
        });
        Ok(())
    }

    /// The buttons held at `t`, seconds.
    ///
    /// # Real-time
    /// No allocation; one pass over the presses.
    pub(super) fn at(&self, t: f64) -> Buttons {
        Buttons(
            self.0
                .iter()
                .filter(|p| p.from <= t && t < p.until)
                .fold(0, |mask, p| mask | (1 << p.button)),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn held_over_their_intervals() {
        let mut p = Presses::default();
        p.add(0, 0.5, 1.0).expect("valid");
        p.add(3, 0.8, 2.0).expect("valid");
        assert_eq!(p.at(0.4), Buttons(0));
        assert_eq!(p.at(0.5), Buttons(1));
        assert_eq!(p.at(0.9), Buttons(0b1001));
        assert_eq!(p.at(1.0), Buttons(0b1000));
        assert_eq!(p.at(f64::NAN), Buttons(0));
        for (b, from, until) in [(32, 0.0, 1.0), (0, 1.0, 1.0), (0, f64::NAN, 1.0)] {
            assert!(p.add(b, from, until).is_err());
        }
    }
}
