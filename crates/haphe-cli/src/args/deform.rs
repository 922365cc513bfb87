//! The deformation of a session, `--deform` and `--deform-rate` (shared by `simulate`,
//! `run` and `view`): which of the library's deformations moves the scene's first object,
//! and how often a deformer thread refreshes its shape; checked before anything is built.

use anyhow::{anyhow, bail};
use haphe::verify::Deformation;

/// Refreshes a second when `--deform-rate` is not given.
pub const DEFAULT_DEFORM_RATE_HZ: f64 = 100.0;

/// The lowest `--deform-rate`, Hz: one refresh every ten seconds.
pub const MIN_DEFORM_RATE_HZ: f64 = 0.1;

/// The highest `--deform-rate`, Hz. A refresh remakes the shape's frames, map cells and
/// clear zones where it moved (milliseconds on a shape of 20 000 triangles), and a hand
/// feels no difference above a few hundred refreshes a second; nor may it be above the
/// servo rate, whose ticks are the only ones to see a refresh.
pub const MAX_DEFORM_RATE_HZ: f64 = 1000.0;

/// The flags of a session's deformation.
#[derive(clap::Args, Debug, Clone)]
pub struct DeformArgs {
    /// Deform the object (a scene file's first object) while it is touched: breathe
    /// (scales by 0.85 to 1.15 at 2 Hz), dent (an 8 mm dent travelling round it), breathe-dent
    /// (both) or twist (the top turning ±0.5 rad at 0.5 Hz). A deformer thread makes each
    /// new shape and hands it to the servo wait-free (docs/guide.md, "Deformation").
    #[arg(long, value_name = "KIND")]
    pub deform: Option<String>,
    /// With --deform: refreshes of the shape a second, Hz (default 100; from 0.1 to 1000,
    /// and at most the servo rate).
    // Negative numbers are values, so that `-5` is refused naming the flag.
    #[arg(
        long,
        value_name = "HZ",
        allow_negative_numbers = true,
        requires = "deform"
    )]
    pub deform_rate: Option<f64>,
}

/// A checked deformation: what moves the object, and how often it is refreshed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Deform {
    pub kind: Deformation,
    pub rate_hz: f64,
}

impl DeformArgs {
    /// The flags' deformation, when `--deform` is given, its rate checked against the
    /// servo rate `servo_rate_hz` (`--rate`).
    ///
    /// # Errors
    /// An unknown kind, or a rate that is not a finite number from
    /// [`MIN_DEFORM_RATE_HZ`] to [`MAX_DEFORM_RATE_HZ`] and at most the servo rate, naming
    /// the flag.
    pub fn check(&self, servo_rate_hz: f64) -> anyhow::Result<Option<Deform>> {
        let Some(kind) = &self.deform else {
            return Ok(None);
        };
        let kind: Deformation = kind.parse().map_err(|e| anyhow!("--deform: {e}"))?;
        let rate_hz = self.deform_rate.unwrap_or(DEFAULT_DEFORM_RATE_HZ);
        let high = MAX_DEFORM_RATE_HZ.min(servo_rate_hz);
        if !(rate_hz.is_finite() && (MIN_DEFORM_RATE_HZ..=high).contains(&rate_hz)) {
            let servo = if servo_rate_hz < MAX_DEFORM_RATE_HZ {
                format!(" (the servo rate, --rate {servo_rate_hz})")
            } else {
                String::new()
            };
            bail!(
                "--deform-rate must be a finite number from {MIN_DEFORM_RATE_HZ} to {high} Hz{servo}, not {rate_hz}"
            );
        }
        Ok(Some(Deform { kind, rate_hz }))
    }
}
