//! Textures and force effects from their specifications (`sine:0.0002:0.002`,
//! `viscosity:2`), refused naming the keyword that gave them.

use haphe::scene::{Effect, MAX_EFFECTS, Scene, Texture};
use pyo3::prelude::*;

use crate::errors::haphe_error;

/// The texture of the specification given as `texture` (`None`, or only blanks: none).
///
/// # Errors
/// `HapheError` naming `texture` and the specification: an unknown kind, a value that is
/// not a number, or outside its domain.
pub fn texture(spec: Option<&str>) -> PyResult<Option<Texture>> {
    match spec {
        Some(s) if !s.trim().is_empty() => {
            s.parse().map(Some).map_err(|e| haphe_error("texture", e))
        }
        _ => Ok(None),
    }
}

/// Adds the effect of the specification `spec` to `scene`.
///
/// # Errors
/// `HapheError` naming `effect` and the specification: an unknown kind, a value that is
/// not a number or outside its domain, or a scene holding `MAX_EFFECTS` effects already.
pub fn add_effect(scene: &mut Scene, spec: &str) -> PyResult<()> {
    let effect: Effect = spec.parse().map_err(|e| haphe_error("effect", e))?;
    scene.add_effect(effect).map_err(|_| {
        haphe_error(
            "effect",
            format!("`{spec}`: the scene holds {MAX_EFFECTS} effects, the most it takes"),
        )
    })
}

/// Whether every effect of `scene` (specified by `specs`, in the same order) renders at
/// `rate_hz`: a vibration at most half of it.
///
/// # Errors
/// `HapheError` naming `effect`, the specification and the rate.
pub fn check_rate(scene: &Scene, specs: &[String], rate_hz: f64) -> PyResult<()> {
    for (effect, spec) in scene.effects().iter().zip(specs) {
        effect
            .check_rate(rate_hz)
            .map_err(|e| haphe_error("effect", format!("`{spec}`: {e}")))?;
    }
    Ok(())
}
