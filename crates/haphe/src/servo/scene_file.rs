//! Scene files: a small TOML format listing objects (a mesh file or a procedural shape),
//! their poses, materials and scripted motions.
//!
//! ```toml
//! tool_radius = 0.002         # metres (optional, 0 by default: a point), before any object
//! effects = ["viscosity:2"]   # force effects (optional), before any object
//!
//! [[object]]
//! shape = "blob"              # sphere, torus, box, thin-plate, concave-corner, blob
//! triangles = 20000
//! position = [0.0, 0.0, 0.0]  # metres, world frame
//! rotation = [0.0, 0.0, 90.0] # degrees about x, then y, then z (optional)
//! material = { stiffness = 600.0, damping = 1.0, static_friction = 0.4, dynamic_friction = 0.3 }
//! texture = "sine:0.0002:0.002"   # a haptic texture (optional)
//!
//! [[object]]
//! mesh = "part.stl"           # relative to this file
//! units = "mm"                # m (default), mm, cm, in, or metres per unit
//! position = [0.3, 0.0, 0.0]
//! motion = { kind = "oscillating", amplitude = [0.0, 0.0, 0.01], frequency = 0.5 }
//! # or { kind = "linear", velocity = [...] }, { kind = "rotating", axis = [0, 0, 1], rate = 0.5 }
//! ```
//!
//! An object with a `grid` table is repeated on a grid (see [`grid`]). Textures and
//! effects are the library's specifications ([`Texture`],
//! [`Effect`](crate::scene::Effect); see [`feel`]).
//!
//! `tool_radius` is the radius of the tool, a sphere centred on the proxy (see
//! [`ProxyOptions::with_tool_radius`](crate::proxy::ProxyOptions::with_tool_radius)),
//! checked against its domain here; a front end also checks it against the scene's size
//! ([`Scene::check_tool_radius`](crate::scene::Scene::check_tool_radius)) once the shapes
//! are built. It and `effects` are top-level keys: TOML puts a key written after an
//! `[[object]]` header into that object.
//!
//! Errors name the file, the object and the line.

use std::path::{Path, PathBuf};

use glam::{DQuat, DVec3, EulerRot};
use serde::Deserialize;

use crate::mesh::Units;
use crate::mesh::shapes::Catalog;
use crate::scene::{Material, ObjectId, Param, Pose, Texture};
use crate::servo::{Motion, ObjectMotion};

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
struct SceneFile {
    tool_radius: Option<toml::Spanned<f64>>,
    #[serde(default)]
    effects: Vec<toml::Spanned<String>>,
    #[serde(default)]
    object: Vec<toml::Spanned<ObjectSpec>>,
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
struct ObjectSpec {
    name: Option<String>,
    id: Option<u32>,
    shape: Option<String>,
    triangles: Option<usize>,
    mesh: Option<PathBuf>,
    units: Option<String>,
    #[serde(default)]
    position: [f64; 3],
    #[serde(default)]
    rotation: [f64; 3],
    #[serde(default)]
    material: MaterialSpec,
    motion: Option<MotionSpec>,
    grid: Option<grid::GridSpec>,
    texture: Option<toml::Spanned<String>>,
}

/// A material table: each field missing takes [`Material::DEFAULT`]'s.
#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
struct MaterialSpec {
    #[serde(default = "default_stiffness")]
    stiffness: f64,
    #[serde(default = "default_damping")]
    damping: f64,
    #[serde(default = "default_static_friction")]
    static_friction: f64,
    #[serde(default = "default_dynamic_friction")]
    dynamic_friction: f64,
}

fn default_stiffness() -> f64 {
    Material::DEFAULT.stiffness()
}

fn default_damping() -> f64 {
    Material::DEFAULT.damping()
}

fn default_static_friction() -> f64 {
    Material::DEFAULT.static_friction()
}

fn default_dynamic_friction() -> f64 {
    Material::DEFAULT.dynamic_friction()
}

impl Default for MaterialSpec {
    fn default() -> MaterialSpec {
        let m = Material::DEFAULT;
        MaterialSpec {
            stiffness: m.stiffness,
            damping: m.damping,
            static_friction: m.static_friction,
            dynamic_friction: m.dynamic_friction,
        }
    }
}

#[derive(Deserialize, Debug)]
#[serde(tag = "kind", rename_all = "lowercase", deny_unknown_fields)]
enum MotionSpec {
    Linear { velocity: [f64; 3] },
    Oscillating { amplitude: [f64; 3], frequency: f64 },
    Rotating { axis: [f64; 3], rate: f64 },
}

/// Triangles of a procedural shape when the file does not say.
pub const DEFAULT_TRIANGLES: usize = 20_000;

/// Where an object's shape comes from.
#[derive(Debug, Clone, PartialEq)]
pub enum ObjectSource {
    /// A built-in procedural shape with about `triangles` triangles.
    Shape {
        /// Which shape.
        which: Catalog,
        /// Its size in triangles (checked by [`Catalog::check_triangles`]).
        triangles: usize,
    },
    /// A mesh file, its path joined to the scene file's folder.
    Mesh {
        /// The mesh file.
        path: PathBuf,
        /// The unit of its numbers.
        units: Units,
    },
}

/// One object of a scene file, every value checked; the shape is not built yet.
#[derive(Debug, Clone)]
pub struct SceneEntry {
    /// A name for reports (the `name` field, else the shape or mesh name).
    pub name: String,
    /// The object's id (the `id` field, else its place in the file from 0).
    pub id: ObjectId,
    /// Where its shape comes from.
    pub source: ObjectSource,
    /// `world_from_object` at the start.
    pub pose: Pose,
    /// How it feels (checked by [`MaterialBuilder::build`](crate::scene::MaterialBuilder::build)).
    pub material: Material,
    /// Its scripted motion (checked by [`Motion::checked`]).
    pub motion: Option<ObjectMotion>,
    /// Its texture (the `texture` key).
    pub texture: Option<Texture>,
    /// `FILE: object N (line L)`, to name the object in later errors (building its shape).
    pub place: String,
}

/// Returns a [`SceneFileError`] with the formatted message.
macro_rules! bail {
    ($($message:tt)*) => {
        return Err(fail(format!($($message)*)))
    };
}

mod error;
pub mod feel;
mod grid;

pub use error::{MAX_OBJECTS, SceneFileError};
use error::{fail, line_of};
pub use feel::FileEffect;

fn vec3(a: [f64; 3]) -> DVec3 {
    DVec3::from_array(a)
}

/// A scene file read and checked: its objects, and its tool's radius when it gives one.
#[doc(hidden)]
#[derive(Debug, Clone)]
pub struct SceneSpec {
    /// The objects, as [`parse_scene`] returns them.
    pub objects: Vec<SceneEntry>,
    /// The `tool_radius` key, metres, checked against its domain, and its place
    /// (`FILE: line L: tool_radius`) to name it in later errors (the scene's size).
    pub tool_radius: Option<(f64, String)>,
    /// The `effects` key's, in order, each with its place.
    pub effects: Vec<FileEffect>,
}

/// Parses and checks the text of the scene file at `path` (used for messages and as the
/// folder that mesh paths are relative to; nothing is read from disk).
///
/// # Errors
/// A [`SceneFileError`] naming the file, and the object and line where there is one: TOML
/// syntax, unknown fields, both or neither of `shape` and `mesh`, an unknown shape or
/// unit, a triangle count out of range, a non-finite pose, an unusable material, motion or
/// texture, a repeated id, no object or more than [`MAX_OBJECTS`].
pub fn parse_scene(path: &Path, text: &str) -> Result<Vec<SceneEntry>, SceneFileError> {
    parse_scene_spec(path, text).map(|spec| spec.objects)
}

/// [`parse_scene`] with the file's `tool_radius` (metres, checked against its domain) and
/// its `effects`.
///
/// # Errors
/// Those of [`parse_scene`], a `tool_radius` outside its domain, and an effect that is
/// not one ([`Effect`](crate::scene::Effect)'s specifications), more than 16 of them, or a zone inside an object the file does not have, naming its line.
#[doc(hidden)]
pub fn parse_scene_spec(path: &Path, text: &str) -> Result<SceneSpec, SceneFileError> {
    let file = path.display().to_string();
    let parsed: SceneFile = toml::from_str(text).map_err(|e| {
        let line = e.span().map(|s| line_of(text, s.start));
        // A top-level key written after an `[[object]]` header belongs to that object.
        let hint = ["tool_radius", "effects"]
            .into_iter()
            .find(|key| e.message().contains(&format!("unknown field `{key}`")))
            .map_or(String::new(), |key| {
                format!(" (`{key}` is a top-level key: write it before the first [[object]])")
            });
        fail(match line {
            Some(line) => format!("{file}: line {line}: {}{hint}", e.message()),
            None => format!("{file}: {}{hint}", e.message()),
        })
    })?;
    let tool_radius = match &parsed.tool_radius {
        None => None,
        Some(r) => {
            let place = format!(
                "{file}: line {}: tool_radius",
                line_of(text, r.span().start)
            );
            match Param::ToolRadius.check(*r.get_ref()) {
                Ok(metres) => Some((metres, place)),
                Err(e) => bail!("{}", e.named(&place)),
            }
        }
    };
    if parsed.object.is_empty() {
        bail!("{file}: no [[object]] in the scene");
    }
    if parsed.object.len() > MAX_OBJECTS {
        bail!(
            "{file}: {} objects, more than the limit of {MAX_OBJECTS}",
            parsed.object.len()
        );
    }
    let base = path.parent().unwrap_or(Path::new("."));
    let objects = entries_of(&parsed.object, text, &file, base)?;
    let ids = objects.iter().map(|o| o.id).collect();
    Ok(SceneSpec {
        effects: feel::effects_of(&parsed.effects, text, &file, &ids)?,
        objects,
        tool_radius,
    })
}

/// The checked entries of the objects of the scene file `file` (its `text`, for lines),
/// mesh paths joined to `base`.
fn entries_of(
    objects: &[toml::Spanned<ObjectSpec>],
    text: &str,
    file: &str,
    base: &Path,
) -> Result<Vec<SceneEntry>, SceneFileError> {
    let mut out: Vec<SceneEntry> = Vec::new();
    let mut ids = std::collections::HashSet::new();
    for (i, spanned) in objects.iter().enumerate() {
        let line = line_of(text, spanned.span().start);
        let place = format!("{file}: object {} (line {line})", i + 1);
        let spec = spanned.get_ref();
        let (source, name) = object_source(spec, base, &place)?;
        for (what, v) in [("position", spec.position), ("rotation", spec.rotation)] {
            if v.iter().any(|x| !x.is_finite()) {
                bail!("{place}: `{what}` must be finite");
            }
        }
        let m = &spec.material;
        let material = match Material::builder()
            .stiffness(m.stiffness)
            .damping(m.damping)
            .friction(m.static_friction, m.dynamic_friction)
            .build()
        {
            Ok(material) => material,
            Err(e) => bail!("{place}: material {e}"),
        };
        let [rx, ry, rz] = spec.rotation.map(f64::to_radians);
        let pose = Pose::new(
            DQuat::from_euler(EulerRot::ZYX, rz, ry, rx),
            vec3(spec.position),
        )
        .map_err(|e| fail(format!("{place}: {e}")))?;
        let copies = grid::copies(spec.grid.as_ref(), &place)?;
        if out.len() + copies.len() > MAX_OBJECTS {
            bail!("{place}: more than {MAX_OBJECTS} objects in the scene");
        }
        let first = spec.id.unwrap_or(out.len() as u32);
        let motion = motion_of(spec, &place)?;
        let texture = feel::texture_of(spec.texture.as_ref(), text, file)?;
        for copy in copies {
            let Some(id) = first.checked_add(copy.index).map(ObjectId) else {
                bail!("{place}: the ids of the grid's copies pass {}", u32::MAX);
            };
            if !ids.insert(id) {
                bail!("{place}: id {} is used by another object", id.0);
            }
            let pose = Pose::new(pose.rotation(), pose.translation() + copy.offset)
                .map_err(|e| fail(format!("{place}: {e}")))?;
            out.push(SceneEntry {
                name: spec.name.clone().unwrap_or_else(|| name.clone()) + &copy.suffix,
                id,
                source: source.clone(),
                pose,
                material,
                motion: motion.map(|motion| ObjectMotion {
                    id,
                    base: pose,
                    motion,
                }),
                texture: texture.clone(),
                place: place.clone(),
            });
        }
    }
    Ok(out)
}

/// Where object `spec` comes from (a built-in shape or a mesh file, relative to `base`)
/// and the name it gets by default; `place` names it in messages.
fn object_source(
    spec: &ObjectSpec,
    base: &Path,
    place: &str,
) -> Result<(ObjectSource, String), SceneFileError> {
    Ok(match (&spec.shape, &spec.mesh) {
        (Some(_), Some(_)) => bail!("{place}: give either `shape` or `mesh`, not both"),
        (None, None) => bail!(
            "{place}: give `shape = \"blob\"` (or another built-in shape) or `mesh = \"FILE\"`"
        ),
        (Some(shape), None) => {
            if spec.units.is_some() {
                bail!("{place}: `units` applies to a mesh file, not to a built-in shape");
            }
            let which: Catalog = match shape.parse() {
                Ok(which) => which,
                Err(e) => bail!("{place}: shape {shape:?}: {e}"),
            };
            let n = spec.triangles.unwrap_or(DEFAULT_TRIANGLES);
            if let Err(e) = Catalog::check_triangles(n) {
                bail!("{place}: {e}");
            }
            (
                ObjectSource::Shape {
                    which,
                    triangles: n,
                },
                shape.clone(),
            )
        }
        (None, Some(mesh)) => {
            if spec.triangles.is_some() {
                bail!("{place}: `triangles` applies to a built-in shape, not to a mesh file");
            }
            let units = match &spec.units {
                Some(u) => match u.parse::<Units>() {
                    Ok(units) => units,
                    Err(e) => bail!("{place}: units {u:?}: {e}"),
                },
                None => Units::Metres,
            };
            (
                ObjectSource::Mesh {
                    path: base.join(mesh),
                    units,
                },
                mesh.display().to_string(),
            )
        }
    })
}

/// The checked motion of object `spec`, if it has one; `place` names it in messages.
fn motion_of(spec: &ObjectSpec, place: &str) -> Result<Option<Motion>, SceneFileError> {
    match &spec.motion {
        None => None,
        Some(MotionSpec::Linear { velocity }) => Some(Motion::Linear {
            velocity: vec3(*velocity),
        }),
        Some(MotionSpec::Oscillating {
            amplitude,
            frequency,
        }) => Some(Motion::Oscillating {
            amplitude: vec3(*amplitude),
            frequency: *frequency,
        }),
        Some(MotionSpec::Rotating { axis, rate }) => Some(Motion::Rotating {
            axis: vec3(*axis),
            rate: *rate,
        }),
    }
    .map(|motion| motion.checked().map_err(|e| fail(format!("{place}: {e}"))))
    .transpose()
}

#[cfg(test)]
mod tests;
