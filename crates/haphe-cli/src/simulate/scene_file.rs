//! Scene files: a small TOML format listing objects (a mesh file or a procedural shape),
//! their poses, materials and scripted motions.
//!
//! ```toml
//! [[object]]
//! shape = "blob"              # sphere, torus, box, thin-plate, concave-corner, blob
//! triangles = 20000
//! position = [0.0, 0.0, 0.0]  # metres, world frame
//! rotation = [0.0, 0.0, 90.0] # degrees about x, then y, then z (optional)
//! material = { stiffness = 600.0, damping = 1.0, static_friction = 0.4, dynamic_friction = 0.3 }
//!
//! [[object]]
//! mesh = "part.stl"           # relative to this file
//! units = "mm"                # m (default), mm, cm, in, or metres per unit
//! position = [0.3, 0.0, 0.0]
//! motion = { kind = "oscillating", amplitude = [0.0, 0.0, 0.01], frequency = 0.5 }
//! # or { kind = "linear", velocity = [...] }, { kind = "rotating", axis = [0, 0, 1], rate = 0.5 }
//! ```
//!
//! An object with a `grid` table is repeated on a grid (see [`super::scene_grid`]).
//!
//! Errors name the file, the object and the line.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use anyhow::{Context, anyhow, bail};
use haphe::DVec3;
use haphe::glam::{DQuat, EulerRot};
use haphe::map::MapOptions;
use haphe::mesh::shapes::Catalog;
use haphe::mesh::{ReadOptions, Surface, SurfaceOptions, Units};
use haphe::scene::{Material, ObjectId, Pose, SceneObject, Shape};
use haphe::servo::{Motion, ObjectMotion};
use serde::Deserialize;

use crate::load::load;

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
struct SceneFile {
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
    grid: Option<super::scene_grid::GridSpec>,
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
struct MaterialSpec {
    #[serde(default = "default_stiffness")]
    stiffness: f64,
    #[serde(default)]
    damping: f64,
    #[serde(default)]
    static_friction: f64,
    #[serde(default)]
    dynamic_friction: f64,
}

fn default_stiffness() -> f64 {
    Material::default().stiffness
}

impl Default for MaterialSpec {
    fn default() -> MaterialSpec {
        MaterialSpec {
            stiffness: default_stiffness(),
            damping: 0.0,
            static_friction: 0.0,
            dynamic_friction: 0.0,
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

/// One object of a loaded scene file.
pub struct LoadedObject {
    /// A name for reports.
    pub name: String,
    /// The object, ready to insert.
    pub object: SceneObject,
    /// Its scripted motion.
    pub motion: Option<ObjectMotion>,
}

/// 1-based line of a byte offset.
fn line_of(text: &str, offset: usize) -> usize {
    text[..offset.min(text.len())].matches('\n').count() + 1
}

fn vec3(a: [f64; 3]) -> DVec3 {
    DVec3::from_array(a)
}

/// Reads a scene file and builds every object (shapes shared between objects that name
/// the same shape and size or the same mesh file).
pub fn load_scene(path: &Path, map: &MapOptions) -> anyhow::Result<Vec<LoadedObject>> {
    let file = path.display().to_string();
    let text = crate::files::input::read_text(path, crate::files::input::SCENE)?;
    let parsed: SceneFile = toml::from_str(&text).map_err(|e| {
        let line = e.span().map(|s| line_of(&text, s.start));
        match line {
            Some(line) => anyhow!("{file}: line {line}: {}", e.message()),
            None => anyhow!("{file}: {}", e.message()),
        }
    })?;
    if parsed.object.is_empty() {
        bail!("{file}: no [[object]] in the scene");
    }
    let base = path.parent().unwrap_or(Path::new("."));
    let mut shapes: Vec<(String, Arc<Shape>)> = Vec::new();
    let mut out: Vec<LoadedObject> = Vec::new();
    let mut ids = std::collections::HashSet::new();
    for (i, spanned) in parsed.object.iter().enumerate() {
        let line = line_of(&text, spanned.span().start);
        let place = format!("{file}: object {} (line {line})", i + 1);
        let spec = spanned.get_ref();
        let (key, name) = match (&spec.shape, &spec.mesh) {
            (Some(_), Some(_)) => bail!("{place}: give either `shape` or `mesh`, not both"),
            (None, None) => bail!(
                "{place}: give `shape = \"blob\"` (or another built-in shape) or `mesh = \"FILE\"`"
            ),
            (Some(shape), None) => {
                if spec.units.is_some() {
                    bail!("{place}: `units` applies to a mesh file, not to a built-in shape");
                }
                let n = spec.triangles.unwrap_or(DEFAULT_TRIANGLES);
                Catalog::check_triangles(n).map_err(|e| anyhow!("{place}: {e}"))?;
                (format!("shape {shape} {n}"), shape.clone())
            }
            (None, Some(mesh)) => {
                if spec.triangles.is_some() {
                    bail!("{place}: `triangles` applies to a built-in shape, not to a mesh file");
                }
                let full = base.join(mesh);
                (
                    format!("mesh {} {:?}", full.display(), spec.units),
                    mesh.display().to_string(),
                )
            }
        };
        let shape = match shapes.iter().find(|(k, _)| *k == key) {
            Some((_, s)) => s.clone(),
            None => {
                let s = Arc::new(build_shape(spec, base, map).with_context(|| place.clone())?);
                shapes.push((key, s.clone()));
                s
            }
        };
        for (what, v) in [("position", spec.position), ("rotation", spec.rotation)] {
            if v.iter().any(|x| !x.is_finite()) {
                bail!("{place}: `{what}` must be finite");
            }
        }
        let m = &spec.material;
        let material = Material {
            stiffness: m.stiffness,
            damping: m.damping,
            static_friction: m.static_friction,
            dynamic_friction: m.dynamic_friction,
        }
        .checked()
        .map_err(|e| anyhow!("{place}: material {e}"))?;
        let [rx, ry, rz] = spec.rotation.map(f64::to_radians);
        let pose = Pose::new(
            DQuat::from_euler(EulerRot::ZYX, rz, ry, rx),
            vec3(spec.position),
        );
        let copies = super::scene_grid::copies(spec.grid.as_ref(), &place)?;
        if (out.len() + copies.len()) as u64 > super::scene_grid::MAX_OBJECTS {
            bail!(
                "{place}: more than {} objects in the scene",
                super::scene_grid::MAX_OBJECTS
            );
        }
        let first = spec.id.unwrap_or(out.len() as u32);
        for copy in copies {
            let Some(id) = first.checked_add(copy.index).map(ObjectId) else {
                bail!("{place}: the ids of the grid's copies pass {}", u32::MAX);
            };
            if !ids.insert(id) {
                bail!("{place}: id {} is used by another object", id.0);
            }
            let pose = Pose::new(pose.rotation(), pose.translation() + copy.offset);
            let motion = match &spec.motion {
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
            .map(|motion| motion.checked().map_err(|e| anyhow!("{place}: {e}")))
            .transpose()?
            .map(|motion| ObjectMotion {
                id,
                base: pose,
                motion,
            });
            out.push(LoadedObject {
                name: spec.name.clone().unwrap_or_else(|| name.clone()) + &copy.suffix,
                object: SceneObject::new(id, shape.clone(), pose, material),
                motion,
            });
        }
    }
    Ok(out)
}

/// The units named in a scene file or on the command line.
pub fn parse_units(s: &str) -> anyhow::Result<Units> {
    s.parse::<Units>().map_err(|e| anyhow!("units {s:?}: {e}"))
}

fn build_shape(spec: &ObjectSpec, base: &Path, map: &MapOptions) -> anyhow::Result<Shape> {
    if let Some(name) = &spec.shape {
        let which: Catalog = name.parse().map_err(|e| anyhow!("shape {name:?}: {e}"))?;
        let n = spec.triangles.unwrap_or(DEFAULT_TRIANGLES);
        return shape_of(which, n, map);
    }
    let mesh = spec.mesh.as_deref().unwrap_or(Path::new(""));
    let units = match &spec.units {
        Some(u) => parse_units(u)?,
        None => Units::Metres,
    };
    mesh_shape(&base.join(mesh), units, map)
}

/// A built-in procedural shape with about `triangles` triangles, with its map and its
/// clear zones (see [`ready`]).
pub fn shape_of(which: Catalog, triangles: usize, map: &MapOptions) -> anyhow::Result<Shape> {
    let surface = Surface::new(which.with_triangles(triangles), &SurfaceOptions::default())?;
    Ok(ready(Shape::build(surface, map)?))
}

/// `shape` with every triangle's clear zone computed, here rather than on the servo
/// thread at the first contact with each triangle.
fn ready(shape: Shape) -> Shape {
    shape.prepare_clear_zones();
    shape
}

/// A shape from a mesh file, with its map and clear zones.
pub fn mesh_shape(path: &Path, units: Units, map: &MapOptions) -> anyhow::Result<Shape> {
    let read = ReadOptions {
        units,
        ..ReadOptions::default()
    };
    let loaded = load(path, &read).map_err(|e| anyhow!("{e}"))?;
    let surface = Surface::new(loaded.mesh, &SurfaceOptions::default())
        .with_context(|| path.display().to_string())?;
    let shape = Shape::build(surface, map).with_context(|| path.display().to_string())?;
    Ok(ready(shape))
}
