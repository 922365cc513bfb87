//! Scene files read from disk and their shapes built: the parsing and checking is
//! [`haphe::servo::scene_file`]; here the file is read through the input module, mesh
//! files are loaded, and shapes are built once and shared between objects that name the
//! same shape and size or the same mesh file and units.

use std::path::Path;
use std::sync::Arc;

use anyhow::{Context, anyhow};
use haphe::map::MapOptions;
use haphe::mesh::shapes::Catalog;
use haphe::mesh::{ReadOptions, Units};
use haphe::scene::{SceneObject, Shape};
use haphe::servo::ObjectMotion;
use haphe::servo::scene_file::{ObjectSource, parse_scene};

use crate::input::mesh::load;

/// One object of a loaded scene file.
pub struct LoadedObject {
    /// A name for reports.
    pub name: String,
    /// The object, ready to insert.
    pub object: SceneObject,
    /// Its scripted motion.
    pub motion: Option<ObjectMotion>,
}

/// Reads a scene file and builds every object (shapes shared between objects that name
/// the same shape and size or the same mesh file).
pub fn load_scene(path: &Path, map: &MapOptions) -> anyhow::Result<Vec<LoadedObject>> {
    let text = crate::input::files::read_text(path, crate::input::files::SCENE)?;
    let entries = parse_scene(path, &text)?;
    let mut shapes: Vec<(ObjectSource, Arc<Shape>)> = Vec::new();
    let mut out = Vec::with_capacity(entries.len());
    for entry in entries {
        let shape = match shapes.iter().find(|(k, _)| *k == entry.source) {
            Some((_, s)) => s.clone(),
            None => {
                let s =
                    Arc::new(build_shape(&entry.source, map).with_context(|| entry.place.clone())?);
                shapes.push((entry.source.clone(), s.clone()));
                s
            }
        };
        out.push(LoadedObject {
            name: entry.name,
            object: SceneObject::new(entry.id, shape, entry.pose, entry.material),
            motion: entry.motion,
        });
    }
    Ok(out)
}

fn build_shape(source: &ObjectSource, map: &MapOptions) -> anyhow::Result<Shape> {
    match source {
        ObjectSource::Shape { which, triangles } => shape_of(*which, *triangles, map),
        ObjectSource::Mesh { path, units } => mesh_shape(path, *units, map),
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

/// A shape from a mesh file, with its map and clear zones.
pub fn mesh_shape(path: &Path, units: Units, map: &MapOptions) -> anyhow::Result<Shape> {
    let read = ReadOptions {
        units,
        ..ReadOptions::default()
    };
    let loaded = load(path, &read).map_err(|e| anyhow!("{e}"))?;
    Ok(Shape::from_mesh(
        &path.display().to_string(),
        loaded.mesh,
        map,
    )?)
}
