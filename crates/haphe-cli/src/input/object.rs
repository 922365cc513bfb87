//! Loading an object for the query commands: a saved map file (surface and map), or a
//! mesh file from which both are built.

use std::io::Read;
use std::path::Path;
use std::time::{Duration, Instant};

use anyhow::{Context, anyhow};
use haphe::map::{MapBytes, MapOptions, VoxelMap, looks_like_map};
use haphe::mesh::{ReadOptions, Surface, SurfaceOptions};

use crate::input::files::{self, open_input};
use crate::input::map::decode_map;
use crate::input::mapped::map_file;
use crate::input::mesh::load_bytes;

/// A surface with its voxel map, and how long it took to get them.
pub struct Object {
    pub surface: Surface,
    pub map: VoxelMap,
    pub elapsed: Duration,
    /// Whether it came from a saved map file.
    pub from_map_file: bool,
}

/// Bytes of a map file's header: what [`looks_like_map`] reads to tell a map from a mesh.
const MAP_HEADER_BYTES: u64 = 64;

/// Opens `path` once: a map file written by `haphe build` (recognised by its header, even a
/// damaged one: [`looks_like_map`]), or a mesh file, whose surface and map are built now.
pub fn open(path: &Path, read: &ReadOptions, map_options: &MapOptions) -> anyhow::Result<Object> {
    let start = Instant::now();
    let mut input = open_input(path, files::OBJECT)?;
    let mut head = Vec::with_capacity(MAP_HEADER_BYTES as usize);
    (&mut input.file)
        .take(MAP_HEADER_BYTES)
        .read_to_end(&mut head)
        .with_context(|| format!("cannot read {}", path.display()))?;
    let len = if input.regular {
        input.file.metadata().map_or(0, |m| m.len())
    } else {
        // A pipe's length is unknown: the magic alone decides.
        u64::MAX
    };
    if looks_like_map(&head, len) {
        let bytes = if input.regular {
            map_file(&input.file).with_context(|| format!("cannot map {}", path.display()))?
        } else {
            head.reserve(1 << 20);
            input.read_rest(files::MAP, &mut head)?;
            MapBytes::copy_from_slice(&head)
        };
        let (surface, map) = decode_map(path, &bytes)?;
        return Ok(Object {
            surface,
            map,
            elapsed: start.elapsed(),
            from_map_file: true,
        });
    }
    if input.regular && len > files::MESH.bytes {
        // Not a map: the mesh limit applies.
        return Err(anyhow!(
            "cannot read {}: larger than the limit for a {} ({} bytes)",
            path.display(),
            files::MESH.what,
            files::MESH.bytes
        ));
    }
    input.read_rest(files::MESH, &mut head)?;
    let loaded = load_bytes(path, &head, read).map_err(|e| anyhow!("{e}"))?;
    let surface = Surface::new(loaded.mesh, &SurfaceOptions::default())
        .with_context(|| format!("{}", path.display()))?;
    let map =
        VoxelMap::build(&surface, map_options).with_context(|| format!("{}", path.display()))?;
    Ok(Object {
        surface,
        map,
        elapsed: start.elapsed(),
        from_map_file: false,
    })
}

/// With `mesh` given, checks that `object` is a map file built from that mesh file: the
/// map's recorded source must have the mesh's size and content hash (its name may differ).
///
/// # Errors
/// Naming both files: the map records another source or none, the object is a mesh file
/// rather than a map, or the mesh cannot be read.
pub fn check_source(path: &Path, object: &Object, mesh: Option<&Path>) -> anyhow::Result<()> {
    let Some(mesh) = mesh else {
        return Ok(());
    };
    let (map_name, mesh_name) = (path.display(), mesh.display());
    if !object.from_map_file {
        return Err(anyhow!(
            "--mesh {mesh_name}: {map_name} is a mesh file, not a map; --mesh checks a map \
             file's source"
        ));
    }
    let bytes = files::read_input(mesh, files::MESH)?;
    haphe::map::check_source(
        &map_name.to_string(),
        object.map.provenance(),
        &mesh_name.to_string(),
        &bytes,
    )?;
    Ok(())
}

/// A map file opened where a mesh is taken (`simulate`, `run`, `view`, scene files):
/// checked against its source mesh, the file its provenance names, when that file is
/// beside it (refused when the mesh changed since the map was built, as [`check_source`]
/// refuses it), and said on stderr either way.
///
/// # Errors
/// [`check_source`]'s, naming both files and how to rebuild the map.
pub fn check_beside(path: &Path, object: &Object) -> anyhow::Result<()> {
    let map = path.display();
    let Some(p) = object.map.provenance() else {
        eprintln!("haphe: {map}: a map that records no source mesh (not checked)");
        return Ok(());
    };
    match haphe_files::source_beside(path, &p.file) {
        Some(source) => {
            check_source(path, object, Some(&source))?;
            eprintln!("haphe: {map}: a map of {} (checked)", source.display());
        }
        None => eprintln!("haphe: {map}: a map of {p} (that file is not beside it: not checked)"),
    }
    Ok(())
}
