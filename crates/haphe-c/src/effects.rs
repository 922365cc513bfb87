//! Textures and force effects of a scene, from their specifications (`sine:0.0002:0.002`,
//! `viscosity:2`), refused naming the parameter that gave them.

use std::ffi::c_char;

use haphe_lib::scene::{Effect, MAX_EFFECTS, ObjectId, Scene, Texture};

use crate::error::{Failure, HapheStatus, guard};
use crate::scene::{HapheScene, scene_mut};
use crate::shape::text;

/// Gives object `id` of `scene` the texture of the specification `texture`
/// (NUL-terminated): `"sine:A:L"`, a solid sine of amplitude `A` and wavelength `L` metres
/// in the object's frame, or `"noise:A:L"`, band-limited noise; null or `""` for none.
/// The proxy feels it from the next tick. Errors: `HAPHE_STATUS_INVALID_ARGUMENT`, the
/// object keeping its texture, for an unknown id or a refused specification:
/// `haphe_last_error()` names `texture` and the specification (an unknown kind, a value
/// not a number, non-finite or outside its domain, bumps steeper than a slope of 1).
#[unsafe(no_mangle)]
pub extern "C" fn haphe_scene_set_texture(
    scene: *mut HapheScene,
    id: u32,
    texture: *const c_char,
) -> HapheStatus {
    guard(|| {
        let sc = scene_mut(scene)?;
        let spec = if texture.is_null() {
            ""
        } else {
            text("texture", texture)?
        };
        let felt = if spec.trim().is_empty() {
            None
        } else {
            Some(
                spec.parse::<Texture>()
                    .map_err(|e| Failure::argument(format!("texture: {e}")))?,
            )
        };
        if sc.inner.set_texture(ObjectId(id), felt) {
            Ok(())
        } else {
            Err(Failure::argument(format!("no object {id} in the scene")))
        }
    })
}

/// Adds to `scene` the force effect of the specification `effect` (NUL-terminated):
///
/// - `"vibration:FREQ:AMPLITUDE"`: in contact, `AMPLITUDE · sin(2π FREQ t)` newtons along
///   the contact normal (FREQ in Hz, at most half the servo's rate);
/// - `"viscosity:B"`: a drag `−B v` (N·s/m) everywhere; `"viscosity:B:inside:ID"` where the
///   device point is inside object `ID`; `"viscosity:B:box:X0:Y0:Z0:X1:Y1:Z1"` inside that
///   box (world, metres);
/// - `"spring:K:X:Y:Z"`: `K (anchor − p)` toward the point (N/m, metres);
/// - `"magnet:DISTANCE:FORCE"`: `FORCE` newtons toward the nearest surface within
///   `DISTANCE` metres of the device point;
/// - `"constant:FX:FY:FZ"`: that force, newtons;
/// - `"stick-slip"` or `"stick-slip:K:FORCE"`: in contact, a spring of `K` N/m across the
///   surface to an anchor that slips when it pulls harder than `FORCE` newtons (1000 N/m
///   and 0.5 N by default).
///
/// Each is bounded by the device's maximum force, added to the surface's force and the
/// sum clamped. The servo loop (`haphe_run`) renders them; `haphe_proxy_tick` renders the
/// surfaces and their textures only. Errors: `HAPHE_STATUS_INVALID_ARGUMENT` for a refused
/// specification, `haphe_last_error()` naming `effect` and the specification (an unknown
/// kind, a value not a number, non-finite or outside its domain); `HAPHE_STATUS_FULL` when
/// the scene holds 16 effects. `haphe_run` refuses a vibration above half its rate.
#[unsafe(no_mangle)]
pub extern "C" fn haphe_scene_add_effect(
    scene: *mut HapheScene,
    effect: *const c_char,
) -> HapheStatus {
    guard(|| {
        let sc = scene_mut(scene)?;
        let spec = text("effect", effect)?;
        let made: Effect = spec
            .parse()
            .map_err(|e| Failure::argument(format!("effect: {e}")))?;
        sc.inner.add_effect(made).map_err(|_| {
            Failure(
                HapheStatus::Full,
                format!(
                    "effect: `{spec}`: the scene holds {MAX_EFFECTS} effects, the most it takes"
                ),
            )
        })?;
        sc.effects.push(spec.to_owned());
        Ok(())
    })
}

/// Removes every force effect of `scene`. Errors: `HAPHE_STATUS_INVALID_ARGUMENT` for a
/// null scene.
#[unsafe(no_mangle)]
pub extern "C" fn haphe_scene_clear_effects(scene: *mut HapheScene) -> HapheStatus {
    guard(|| {
        let sc = scene_mut(scene)?;
        sc.inner.clear_effects();
        sc.effects.clear();
        Ok(())
    })
}

/// Whether every effect of `world` (specified by `specs`, in the same order) renders at
/// `rate_hz`: a vibration at most half of it.
///
/// # Errors
/// `HAPHE_STATUS_INVALID_ARGUMENT` naming `effect`, the specification and the rate.
pub(crate) fn check_rate(world: &Scene, specs: &[String], rate_hz: f64) -> Result<(), Failure> {
    for (effect, spec) in world.effects().iter().zip(specs) {
        effect
            .check_rate(rate_hz)
            .map_err(|e| Failure::argument(format!("effect: `{spec}`: {e}")))?;
    }
    Ok(())
}
