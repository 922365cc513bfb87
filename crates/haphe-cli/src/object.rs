//! Loading an object for the query commands: a saved map file (surface and map), or a
//! mesh file from which both are built.

use std::path::Path;
use std::time::{Duration, Instant};

use anyhow::{Context, anyhow};
use haphe::map::{MAGIC, MapOptions, VoxelMap, decode_in_place};
use haphe::mesh::{ReadOptions, Surface, SurfaceOptions};

use crate::load::load;
use crate::mapped::map_file;

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
    if starts_with_magic(path)? {
        let bytes = map_file(path)?;
        let (surface, map) =
            decode_in_place(&bytes).with_context(|| format!("{}", path.display()))?;
        return Ok(Object {
            surface,
            map,
            elapsed: start.elapsed(),
            from_map_file: true,
        });
    }
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

/// Whether the file at `path` starts with the map file's [`MAGIC`].
fn starts_with_magic(path: &Path) -> anyhow::Result<bool> {
    use std::io::Read;
    let mut head = [0u8; MAGIC.len()];
    let mut file =
        std::fs::File::open(path).with_context(|| format!("cannot read {}", path.display()))?;
    let mut filled = 0;
    while filled < head.len() {
        match file.read(&mut head[filled..]) {
            Ok(0) => break,
            Ok(n) => filled += n,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
            Err(e) => return Err(e).with_context(|| format!("cannot read {}", path.display())),
        }
    }
    Ok(filled == head.len() && head == MAGIC)
}
