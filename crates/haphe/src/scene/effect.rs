//! Force effects: forces added to the proxy's, each bounded by the device's maximum, the
//! sum clamped to it (the servo evaluates them every tick, `servo/tick/effects.rs`).

use std::str::FromStr;

use glam::DVec3;

use super::invalid::ParamError;
use super::object::ObjectId;
use super::param::Param;
use super::spec::{Spec, SpecError, number};

/// The kinds an effect specification names.
const KINDS: &str = "`vibration`, `viscosity`, `spring`, `magnet`, `constant`, `stick-slip`";

/// The most effects a scene holds (reserved when it is made).
pub const MAX_EFFECTS: usize = 16;

/// The stick-slip effect's stiffness when the specification gives none, N/m.
const STICK_SLIP_STIFFNESS: f64 = 1000.0;
/// The stick-slip effect's breakaway force when the specification gives none, N.
const STICK_SLIP_BREAKAWAY: f64 = 0.5;

/// Where an effect acts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Zone {
    /// Everywhere.
    Everywhere,
    /// Where the device point is inside the object of this name (a solid).
    Inside(ObjectId),
    /// Where the device point is inside this box (world frame, metres, `min ≤ max`).
    Box {
        /// The lowest corner.
        min: DVec3,
        /// The highest corner.
        max: DVec3,
    },
}

/// A force effect, every value checked. Built by its kind's constructor or parsed from a
/// specification:
///
/// | specification | force on the device |
/// |---|---|
/// | `vibration:FREQ:AMPLITUDE` | in contact, `AMPLITUDE · sin(2π FREQ t)` newtons along the contact normal |
/// | `viscosity:B` | a drag `−B v` (N·s/m) everywhere |
/// | `viscosity:B:inside:ID` | the same where the device point is inside object `ID` |
/// | `viscosity:B:box:X0:Y0:Z0:X1:Y1:Z1` | the same inside that box (world, metres) |
/// | `spring:K:X:Y:Z` | `K (anchor − p)` toward the point (N/m, metres) |
/// | `magnet:DISTANCE:FORCE` | `FORCE` newtons toward the nearest surface within `DISTANCE` metres of the device point, and into it in contact |
/// | `constant:FX:FY:FZ` | that force, newtons |
/// | `stick-slip[:K:FORCE]` | in contact, a spring of `K` N/m across the surface toward an anchor that jumps to the device point when the spring pulls harder than `FORCE` newtons (1000 N/m and 0.5 N by default) |
///
/// All but the vibration are passive: over a closed path they take work from the hand or
/// give back what they took, never more.
///
/// ```
/// use haphe::scene::Effect;
/// let e: Effect = "viscosity:2".parse()?;
/// assert_eq!(e.kind(), "viscosity");
/// assert!("vibration:-150:0.3".parse::<Effect>().is_err());
/// # Ok::<(), haphe::scene::SpecError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Effect {
    pub(crate) kind: EffectKind,
}

/// What an effect is, with its checked values.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum EffectKind {
    Vibration { frequency: f64, amplitude: f64 },
    Viscosity { viscosity: f64, zone: Zone },
    Spring { stiffness: f64, anchor: DVec3 },
    Magnet { distance: f64, force: f64 },
    Constant { force: DVec3 },
    StickSlip { stiffness: f64, breakaway: f64 },
}

impl Effect {
    /// A vibration of `frequency` Hz and `amplitude` newtons along the contact normal,
    /// while in contact (not passive: it is meant to be felt).
    ///
    /// # Errors
    /// [`ParamError`] naming the vibration frequency (above 0, at most 20 kHz) or the
    /// effect force (0 to 100 N). The servo refuses a frequency above half its rate.
    pub fn vibration(frequency: f64, amplitude: f64) -> Result<Effect, ParamError> {
        Ok(Effect {
            kind: EffectKind::Vibration {
                frequency: Param::VibrationFrequency.check(frequency)?,
                amplitude: Param::EffectForce.check(amplitude)?,
            },
        })
    }

    /// A drag of `−viscosity · v` (N·s/m) on the device, in `zone`.
    ///
    /// # Errors
    /// [`ParamError`] naming the viscosity (0 to 1000 N·s/m), or a box corner (a
    /// position) not finite or beyond 10⁹ m. A box whose `min` exceeds its `max` on an
    /// axis is refused as a position too.
    pub fn viscosity(viscosity: f64, zone: Zone) -> Result<Effect, ParamError> {
        let viscosity = Param::Viscosity.check(viscosity)?;
        if let Zone::Box { min, max } = zone {
            Param::Position.check_vector(min.to_array())?;
            Param::Position.check_vector(max.to_array())?;
            if let Some(axis) = (0..3).find(|&a| min[a] > max[a]) {
                return Err(ParamError::OutOfDomain {
                    param: Param::Position,
                    value: min[axis] - max[axis],
                });
            }
        }
        Ok(Effect {
            kind: EffectKind::Viscosity { viscosity, zone },
        })
    }

    /// A spring of `stiffness` N/m pulling the device point toward `anchor` (world frame,
    /// metres).
    ///
    /// # Errors
    /// [`ParamError`] naming the effect stiffness (0 to 10⁶ N/m) or the anchor (a
    /// position).
    pub fn spring(stiffness: f64, anchor: DVec3) -> Result<Effect, ParamError> {
        Ok(Effect {
            kind: EffectKind::Spring {
                stiffness: Param::EffectStiffness.check(stiffness)?,
                anchor: DVec3::from_array(Param::Position.check_vector(anchor.to_array())?),
            },
        })
    }

    /// A pull of `force` newtons toward the nearest surface within `distance` metres of
    /// the device point, and into the surface while in contact: the surface holds the
    /// hand until it pulls away harder.
    ///
    /// # Errors
    /// [`ParamError`] naming the magnet distance (above 0, at most 1 m) or the effect
    /// force.
    pub fn magnet(distance: f64, force: f64) -> Result<Effect, ParamError> {
        Ok(Effect {
            kind: EffectKind::Magnet {
                distance: Param::MagnetDistance.check(distance)?,
                force: Param::EffectForce.check(force)?,
            },
        })
    }

    /// A constant force, newtons, world frame.
    ///
    /// # Errors
    /// [`ParamError`] naming the effect force (finite, at most 100 N long).
    pub fn constant(force: DVec3) -> Result<Effect, ParamError> {
        Ok(Effect {
            kind: EffectKind::Constant {
                force: DVec3::from_array(Param::EffectForce.check_vector(force.to_array())?),
            },
        })
    }

    /// Stick-slip: in contact, a spring of `stiffness` N/m across the surface toward an
    /// anchor set where contact began; when it pulls harder than `breakaway` newtons the
    /// anchor jumps to the device point (a slip), and the hand feels a saw-tooth as it
    /// slides.
    ///
    /// # Errors
    /// [`ParamError`] naming the effect stiffness or the effect force.
    pub fn stick_slip(stiffness: f64, breakaway: f64) -> Result<Effect, ParamError> {
        Ok(Effect {
            kind: EffectKind::StickSlip {
                stiffness: Param::EffectStiffness.check(stiffness)?,
                breakaway: Param::EffectForce.check(breakaway)?,
            },
        })
    }

    /// The kind's name, as a specification spells it.
    pub fn kind(&self) -> &'static str {
        match self.kind {
            EffectKind::Vibration { .. } => "vibration",
            EffectKind::Viscosity { .. } => "viscosity",
            EffectKind::Spring { .. } => "spring",
            EffectKind::Magnet { .. } => "magnet",
            EffectKind::Constant { .. } => "constant",
            EffectKind::StickSlip { .. } => "stick-slip",
        }
    }

    /// Where a viscosity acts (`None` for the other kinds, which act everywhere they
    /// apply).
    pub fn zone(&self) -> Option<Zone> {
        match self.kind {
            EffectKind::Viscosity { zone, .. } => Some(zone),
            _ => None,
        }
    }

    /// A spring's anchor, world frame.
    pub fn anchor(&self) -> Option<DVec3> {
        match self.kind {
            EffectKind::Spring { anchor, .. } => Some(anchor),
            _ => None,
        }
    }

    /// Whether the effect is rendered at a servo rate of `rate_hz`: a vibration's
    /// frequency must be at most half of it.
    ///
    /// # Errors
    /// [`ParamError::AboveHalfRate`] naming the vibration frequency.
    pub fn check_rate(&self, rate_hz: f64) -> Result<(), ParamError> {
        match self.kind {
            EffectKind::Vibration { frequency, .. } if frequency > rate_hz / 2.0 => {
                Err(ParamError::AboveHalfRate {
                    param: Param::VibrationFrequency,
                    value: frequency,
                    rate: rate_hz,
                })
            }
            _ => Ok(()),
        }
    }
}

impl FromStr for Effect {
    type Err = SpecError;

    /// One of the specifications of the table in [`Effect`].
    fn from_str(text: &str) -> Result<Effect, SpecError> {
        let spec = Spec::split(text);
        let made = match spec.kind {
            "vibration" => {
                let [f, a] = spec.numbers("`vibration:FREQUENCY:AMPLITUDE` (Hz, N)")?;
                Effect::vibration(f, a)
            }
            "viscosity" => return viscosity(&spec),
            "spring" => {
                let [k, x, y, z] = spec.numbers("`spring:K:X:Y:Z` (N/m, metres)")?;
                Effect::spring(k, DVec3::new(x, y, z))
            }
            "magnet" => {
                let [d, f] = spec.numbers("`magnet:DISTANCE:FORCE` (metres, N)")?;
                Effect::magnet(d, f)
            }
            "constant" => {
                let [x, y, z] = spec.numbers("`constant:FX:FY:FZ` (N)")?;
                Effect::constant(DVec3::new(x, y, z))
            }
            "stick-slip" => {
                let [k, f] = if spec.values.is_empty() {
                    [STICK_SLIP_STIFFNESS, STICK_SLIP_BREAKAWAY]
                } else {
                    spec.numbers("`stick-slip` or `stick-slip:K:FORCE` (N/m, N)")?
                };
                Effect::stick_slip(k, f)
            }
            _ => return Err(spec.unknown(KINDS)),
        };
        made.map_err(|e| spec.param(e))
    }
}

/// `viscosity:B`, `viscosity:B:inside:ID` or `viscosity:B:box:X0:Y0:Z0:X1:Y1:Z1`.
fn viscosity(spec: &Spec<'_>) -> Result<Effect, SpecError> {
    const FORM: &str =
        "`viscosity:B`, `viscosity:B:inside:ID` or `viscosity:B:box:X0:Y0:Z0:X1:Y1:Z1`";
    let (b, rest) = match spec.values.split_first() {
        Some((b, rest)) => (number(spec.text, b)?, rest),
        None => return Err(spec.form(FORM)),
    };
    let zone = match rest {
        [] => Zone::Everywhere,
        ["inside", id] => Zone::Inside(ObjectId(id.parse::<u32>().map_err(|_| spec.form(FORM))?)),
        ["box", corners @ ..] if corners.len() == 6 => {
            let mut c = [0.0; 6];
            for (v, s) in c.iter_mut().zip(corners) {
                *v = number(spec.text, s)?;
            }
            Zone::Box {
                min: DVec3::new(c[0], c[1], c[2]),
                max: DVec3::new(c[3], c[4], c[5]),
            }
        }
        _ => return Err(spec.form(FORM)),
    };
    Effect::viscosity(b, zone).map_err(|e| spec.param(e))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn specifications_are_read_as_the_constructors_build() {
        let cases: [(&str, Result<Effect, ParamError>); 8] = [
            ("vibration:150:0.3", Effect::vibration(150.0, 0.3)),
            ("viscosity:2", Effect::viscosity(2.0, Zone::Everywhere)),
            (
                "viscosity:2:inside:7",
                Effect::viscosity(2.0, Zone::Inside(ObjectId(7))),
            ),
            (
                "viscosity:2:box:0:0:0:0.1:0.2:0.3",
                Effect::viscosity(
                    2.0,
                    Zone::Box {
                        min: DVec3::ZERO,
                        max: DVec3::new(0.1, 0.2, 0.3),
                    },
                ),
            ),
            ("spring:100:0:0.1:0", Effect::spring(100.0, 0.1 * DVec3::Y)),
            ("magnet:0.01:1", Effect::magnet(0.01, 1.0)),
            ("constant:0:0:-1", Effect::constant(-DVec3::Z)),
            ("stick-slip", Effect::stick_slip(1000.0, 0.5)),
        ];
        for (text, built) in cases {
            assert_eq!(text.parse::<Effect>().ok(), built.ok(), "{text}");
        }
    }

    #[test]
    fn bad_specifications_say_what_is_wrong() {
        for (text, says) in [
            ("wobble:1", "unknown kind `wobble`"),
            ("vibration:150", "expected `vibration:FREQUENCY:AMPLITUDE`"),
            ("vibration:-150:0.3", "vibration frequency must be"),
            ("viscosity:nan", "viscosity must be"),
            ("viscosity:-1", "viscosity must be"),
            ("viscosity:1:box:1:0:0:0:1:1", "position must be"),
            ("viscosity:1:inside:x", "expected `viscosity:B`"),
            ("spring:10:0:0", "expected `spring:K:X:Y:Z`"),
            ("magnet:0:1", "magnet distance must be"),
            ("constant:0:0:inf", "effect force must be finite"),
            ("stick-slip:1000", "expected `stick-slip`"),
            ("constant:a:0:0", "`a` is not a number"),
        ] {
            let e = text.parse::<Effect>().unwrap_err().to_string();
            assert!(e.contains(says), "{text}: {e}");
            assert!(e.starts_with(&format!("`{text}`")), "{e}");
        }
        let e = Effect::vibration(600.0, 0.3).unwrap();
        let refused = e.check_rate(1000.0).unwrap_err().to_string();
        assert!(
            refused.contains("at most half the servo rate (500 Hz"),
            "{refused}"
        );
        assert!(e.check_rate(1200.0).is_ok());
    }
}
