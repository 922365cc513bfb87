//! Scene files read from disk and their shapes built: the parsing and checking is
//! [`haphe::servo::scene_file`]; here the file is read through the input module, mesh
//! files are loaded, and shapes are built once and shared between objects that name the
//! same shape and size or the same mesh file and units.

use std::path::Path;
use std::sync::Arc;

use anyhow::Context;
use haphe::map::MapOptions;
use haphe::mesh::shapes::Catalog;
use haphe::mesh::{ReadOptions, Units, Weld};
use haphe::scene::{Material, SceneObject, Shape};
use haphe::servo::ObjectMotion;
use haphe::servo::scene_file::{FileEffect, ObjectSource, parse_scene_spec};
use haphe::volume::Cutter;

use crate::input::mesh::{SideCars, UnitsGiven, warn_units};
use crate::input::object::{check_beside, open};

/// One object of a loaded scene file.
pub struct LoadedObject {
    /// A name for reports.
    pub name: String,
    /// The object, ready to insert.
    pub object: SceneObject,
    /// Its scripted motion.
    pub motion: Option<ObjectMotion>,
}

/// The objects of a scene file, its tool's radius when it gives one, and its effects.
pub struct LoadedScene {
    /// The objects, built.
    pub objects: Vec<LoadedObject>,
    /// The file's `tool_radius`, metres, and its place (`FILE: line L: tool_radius`).
    pub tool_radius: Option<(f64, String)>,
    /// The file's `effects` (and, once [`Feel::apply`](crate::args::feel::Feel::apply)
    /// added them, the flags'), each with its place.
    pub effects: Vec<FileEffect>,
    /// The volume of the first object, when it is one (`--volume`, `--mesh` with
    /// `--voxel`): the cutter that owns it and made the object's shape.
    pub cutter: Option<Cutter>,
}

impl From<Vec<LoadedObject>> for LoadedScene {
    /// Objects with no tool radius given (a mesh file, a built-in shape, a glTF file).
    fn from(objects: Vec<LoadedObject>) -> LoadedScene {
        LoadedScene {
            objects,
            tool_radius: None,
            effects: Vec::new(),
            cutter: None,
        }
    }
}

/// Reads a scene file and builds every object (shapes shared between objects that name
/// the same shape and size or the same mesh file).
///
/// A glTF file (`.glb`, `.gltf`) is a scene too: one object per node with a mesh (see
/// [`load_gltf_scene`]).
pub fn load_scene(path: &Path, map: &MapOptions) -> anyhow::Result<LoadedScene> {
    let is_gltf = path
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("glb") || e.eq_ignore_ascii_case("gltf"));
    if is_gltf {
        return load_gltf_scene(path, map).map(LoadedScene::from);
    }
    let text = crate::input::files::read_text(path, crate::input::files::SCENE)?;
    let spec = parse_scene_spec(path, &text)?;
    let mut shapes: Vec<(ObjectSource, Arc<Shape>)> = Vec::new();
    let mut out = Vec::with_capacity(spec.objects.len());
    for entry in spec.objects {
        let shape = match shapes.iter().find(|(k, _)| *k == entry.source) {
            Some((_, s)) => s.clone(),
            None => {
                let s =
                    Arc::new(build_shape(&entry.source, map).with_context(|| entry.place.clone())?);
                shapes.push((entry.source.clone(), s.clone()));
                s
            }
        };
        let mut object = SceneObject::new(entry.id, shape, entry.pose, entry.material);
        object.texture = entry.texture;
        out.push(LoadedObject {
            name: entry.name,
            object,
            motion: entry.motion,
        });
    }
    Ok(LoadedScene {
        objects: out,
        tool_radius: spec.tool_radius,
        effects: spec.effects,
        cutter: None,
    })
}

/// A glTF file as a scene: one object per node of its default scene that holds a mesh, at
/// the node's world pose, named after the node, its material from the node's `extras`
/// (else the default); nodes that use one mesh the same way share one shape.
pub fn load_gltf_scene(path: &Path, map: &MapOptions) -> anyhow::Result<Vec<LoadedObject>> {
    let name = path.display().to_string();
    let bytes = crate::input::files::read_input(path, crate::input::files::MESH)?;
    let scene = haphe::mesh::read_gltf(&name, &bytes, Units::Metres, &mut SideCars(path))?;
    let objects = haphe::scene::gltf_objects(&scene).with_context(|| name.clone())?;
    let built = objects
        .build(Weld::Exact, map, Material::default(), 0)
        .with_context(|| name.clone())?;
    Ok(built
        .into_iter()
        .map(|(name, object)| LoadedObject {
            name,
            object,
            motion: None,
        })
        .collect())
}

fn build_shape(source: &ObjectSource, map: &MapOptions) -> anyhow::Result<Shape> {
    match source {
        ObjectSource::Shape { which, triangles } => shape_of(*which, *triangles, map),
        ObjectSource::Mesh { path, units } => mesh_shape(path, *units, map, UnitsGiven::SceneField),
    }
}

/// A built-in procedural shape with about `triangles` triangles, with its map and its
/// clear zones ([`Shape::from_mesh`]).
pub fn shape_of(which: Catalog, triangles: usize, map: &MapOptions) -> anyhow::Result<Shape> {
    Ok(Shape::from_mesh(
        which.name(),
        which.with_triangles(triangles),
        map,
    )?)
}

/// A shape from a mesh file, with its map and clear zones, warning when its size suggests
/// the wrong unit ([`warn_units`], the unit `given` as a flag or a scene file's field); or
/// from a map file written by `haphe build` (recognised by its header, whatever its name),
/// checked against its source mesh when that is beside it ([`check_beside`]; map files are
/// in metres, `units` applies to mesh files).
pub fn mesh_shape(
    path: &Path,
    units: Units,
    map: &MapOptions,
    given: UnitsGiven,
) -> anyhow::Result<Shape> {
    let read = ReadOptions {
        units,
        ..ReadOptions::default()
    };
    let object = open(path, &read, map)?;
    if object.from_map_file {
        check_beside(path, &object)?;
    } else {
        warn_units(
            &path.display().to_string(),
            object.surface.bounds(),
            units,
            given,
        );
    }
    Ok(Shape::new(object.surface, object.map).with_clear_zones())
}
