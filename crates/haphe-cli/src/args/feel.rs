//! The textures and force effects of a session, `--texture` and `--effect` (shared by
//! `simulate`, `run` and `view`): parsed by the library's specifications
//! ([`Texture`], [`Effect`](haphe::scene::Effect)), checked against the servo rate before anything is built, and
//! merged with a scene file's `texture` and `effects` once the objects are loaded.

use anyhow::{anyhow, bail};
use haphe::scene::{MAX_EFFECTS, Texture, Zone};
use haphe::servo::scene_file::FileEffect;

use crate::input::scene::LoadedScene;

/// The flags of a session's textures and effects.
#[derive(clap::Args, Debug, Clone)]
pub struct FeelArgs {
    /// A haptic texture felt on the surface of the --mesh or --shape object, and of each
    /// object of a --scene that has no `texture` of its own: sine:A:L or noise:A:L
    /// (amplitude and wavelength, metres; docs/guide.md, "Textures and effects").
    #[arg(long, value_name = "SPEC")]
    pub texture: Option<String>,
    /// A force effect (repeatable; added to a scene file's `effects`), SI units:
    /// vibration:FREQ:AMPLITUDE, viscosity:B (viscosity:B:inside:ID,
    /// viscosity:B:box:X0:Y0:Z0:X1:Y1:Z1 in a zone), spring:K:X:Y:Z,
    /// magnet:DISTANCE:FORCE, constant:FX:FY:FZ, stick-slip or stick-slip:K:FORCE.
    #[arg(long, value_name = "SPEC")]
    pub effect: Vec<String>,
}

/// The texture and effects of the flags, checked.
#[derive(Debug, Clone)]
pub struct Feel {
    /// `--texture`.
    pub texture: Option<Texture>,
    /// Each `--effect`, its place `--effect`.
    pub effects: Vec<FileEffect>,
}

/// How a flag's effect is named in errors, as a scene file's effect is by its line.
const FLAG: &str = "--effect";

impl FeelArgs {
    /// The flags' texture and effects, each checked against its domains and every
    /// vibration against the servo rate `rate_hz` (`--rate`), before anything is built.
    ///
    /// # Errors
    /// A specification that is not one (an unknown kind, a missing value, a value not a
    /// number, non-finite or out of its domain), a vibration above half the rate, or more
    /// effects than a scene holds, naming the flag and the specification.
    pub fn check(&self, rate_hz: f64) -> anyhow::Result<Feel> {
        let texture = self
            .texture
            .as_deref()
            .map(|t| t.parse::<Texture>().map_err(|e| anyhow!("--texture {e}")))
            .transpose()?;
        if self.effect.len() > MAX_EFFECTS {
            bail!(
                "{FLAG} is given {} times, more than the limit of {MAX_EFFECTS} effects in a scene",
                self.effect.len()
            );
        }
        let mut effects = Vec::with_capacity(self.effect.len());
        for spec in &self.effect {
            let effect = FileEffect {
                effect: spec.parse().map_err(|e| anyhow!("{FLAG} {e}"))?,
                spec: spec.clone(),
                place: FLAG.into(),
            };
            check_rate(&effect, rate_hz)?;
            effects.push(effect);
        }
        Ok(Feel { texture, effects })
    }
}

/// Whether `effect` renders at `rate_hz` (a vibration at most at half of it).
///
/// # Errors
/// Naming where the effect was given and its specification.
fn check_rate(effect: &FileEffect, rate_hz: f64) -> anyhow::Result<()> {
    effect
        .effect
        .check_rate(rate_hz)
        .map_err(|e| anyhow!("{} `{}`: {e}", effect.place, effect.spec))
}

impl Feel {
    /// `loaded` with the flags' texture on each object that has none of its own (a scene
    /// file's `texture` wins), and the effects of the scene file then of the flags, every
    /// one checked against the servo rate `rate_hz` and the objects loaded.
    ///
    /// A zone inside an object that is not a closed solid (an open surface has no inside)
    /// is warned about on stderr.
    ///
    /// # Errors
    /// A scene file's vibration above half the rate (named by its line), more effects
    /// than a scene holds, or a zone inside an object that no object has the id of.
    pub fn apply(self, loaded: &mut LoadedScene, rate_hz: f64) -> anyhow::Result<()> {
        if let Some(texture) = &self.texture {
            for o in &mut loaded.objects {
                o.object.texture.get_or_insert_with(|| texture.clone());
            }
        }
        for e in &loaded.effects {
            check_rate(e, rate_hz)?;
        }
        if loaded.effects.len() + self.effects.len() > MAX_EFFECTS {
            bail!(
                "{} effects from the scene file and {} from {FLAG}, more than the limit of {MAX_EFFECTS} in a scene",
                loaded.effects.len(),
                self.effects.len()
            );
        }
        for e in &self.effects {
            if let Some(Zone::Inside(id)) = e.effect.zone()
                && !loaded.objects.iter().any(|o| o.object.id == id)
            {
                let ids: Vec<String> = loaded
                    .objects
                    .iter()
                    .take(8)
                    .map(|o| o.object.id.0.to_string())
                    .collect();
                let more = if loaded.objects.len() > ids.len() {
                    ", ..."
                } else {
                    ""
                };
                bail!(
                    "{FLAG} `{}`: no object of the scene has id {} (the ids are {}{more})",
                    e.spec,
                    id.0,
                    ids.join(", ")
                );
            }
        }
        loaded.effects.extend(self.effects);
        for e in &loaded.effects {
            if let Some(Zone::Inside(id)) = e.effect.zone()
                && let Some(o) = loaded.objects.iter().find(|o| o.object.id == id)
                && !o.object.shape.is_solid()
            {
                eprintln!(
                    "haphe: warning: {} `{}`: {} (id {}) is not a closed solid, so nothing is inside it: the effect acts nowhere",
                    e.place, e.spec, o.name, id.0
                );
            }
        }
        Ok(())
    }
}
