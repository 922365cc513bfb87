//! Loading an object for the query commands: a saved map file (surface and map), or a
//! mesh file from which both are built.

use std::path::Path;
use std::time::{Duration, Instant};

use anyhow::{Context, anyhow};
use haphe::map::{MAGIC, MapOptions, VoxelMap, decode};
use haphe::mesh::{ReadOptions, Surface, SurfaceOptions};

use crate::load::load;

/// A surface with its voxel map, and how long it took to get them.
pub struct Object {
    pub surface: Surface,
    pub map: VoxelMap,
    pub elapsed: Duration,
    /// Whether it came from a saved map file.
    pub from_map_file: bool,
}

/// Opens `path`: a map file written by `haphe build` (recognised by its header), or a
/// mesh file, whose surface and map are built now.
pub fn open(path: &Path, read: &ReadOptions, map_options: &MapOptions) -> anyhow::Result<Object> {
    let start = Instant::now();
    let bytes = std::fs::read(path).with_context(|| format!("cannot read {}", path.display()))?;
    if bytes.starts_with(&MAGIC) {
        let (surface, map) = decode(&bytes).with_context(|| format!("{}", path.display()))?;
        return Ok(Object {
            surface,
            map,
            elapsed: start.elapsed(),
            from_map_file: true,
        });
    }
    drop(bytes);
    let loaded = load(path, read).map_err(|e| anyhow!("{e}"))?;
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
