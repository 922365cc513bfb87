//! Loading an object for the query commands: a saved map file (surface and map), or a
//! mesh file from which both are built.

use std::io::Read;
use std::path::Path;
use std::time::{Duration, Instant};

use anyhow::{Context, anyhow};
use haphe::map::{MAGIC, MapBytes, MapOptions, VoxelMap, decode_in_place};
use haphe::mesh::{ReadOptions, Surface, SurfaceOptions};

use crate::files::input::{self, open_input};
use crate::load::load_bytes;
use crate::mapped::map_file;

/// A surface with its voxel map, and how long it took to get them.
pub struct Object {
    pub surface: Surface,
    pub map: VoxelMap,
    pub elapsed: Duration,
    /// Whether it came from a saved map file.
    pub from_map_file: bool,
}

/// Opens `path` once: a map file written by `haphe build` (recognised by its header), or a
/// mesh file, whose surface and map are built now.
pub fn open(path: &Path, read: &ReadOptions, map_options: &MapOptions) -> anyhow::Result<Object> {
    let start = Instant::now();
    let mut input = open_input(path, input::OBJECT)?;
    let mut head = Vec::with_capacity(MAGIC.len());
    (&mut input.file)
        .take(MAGIC.len() as u64)
        .read_to_end(&mut head)
        .with_context(|| format!("cannot read {}", path.display()))?;
    if head == MAGIC {
        let bytes = if input.regular {
            map_file(&input.file).with_context(|| format!("cannot map {}", path.display()))?
        } else {
            head.reserve(1 << 20);
            input.read_rest(input::MAP, &mut head)?;
            MapBytes::copy_from_slice(&head)
        };
        let (surface, map) =
            decode_in_place(&bytes).with_context(|| format!("{}", path.display()))?;
        return Ok(Object {
            surface,
            map,
            elapsed: start.elapsed(),
            from_map_file: true,
        });
    }
    if input.regular && input.file.metadata().map_or(0, |m| m.len()) > input::MESH.bytes {
        // Not a map: the mesh limit applies.
        return Err(anyhow!(
            "cannot read {}: larger than the limit for a {} ({} bytes)",
            path.display(),
            input::MESH.what,
            input::MESH.bytes
        ));
    }
    input.read_rest(input::MESH, &mut head)?;
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
