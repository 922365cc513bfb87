//! Reading mesh files from disk: the only place the front end opens mesh paths.

use std::path::Path;
use std::time::{Duration, Instant};

use crate::input::files::{self, read_input};
use haphe::mesh::{Format, Mesh, ReadError, ReadOptions, WeldStats, read_unwelded, weld};

/// A mesh read from a file, with what it took.
pub struct Loaded {
    /// The welded mesh.
    pub mesh: Mesh,
    /// The detected format.
    pub format: Format,
    /// What welding did.
    pub weld: WeldStats,
    /// Time to parse and weld.
    pub elapsed: Duration,
}

/// Why a file could not be loaded.
pub enum LoadFailure {
    /// The file could not be opened or read.
    Io(anyhow::Error),
    /// The content is malformed.
    Read(ReadError),
}

impl std::fmt::Display for LoadFailure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            LoadFailure::Io(e) => write!(f, "{e:#}"),
            LoadFailure::Read(e) => write!(f, "{e}"),
        }
    }
}

/// Reads, parses and welds a mesh file (opened once, within [`files::MESH`]).
pub fn load(path: &Path, options: &ReadOptions) -> Result<Loaded, LoadFailure> {
    let bytes = read_input(path, files::MESH).map_err(LoadFailure::Io)?;
    load_bytes(path, &bytes, options)
}

/// Parses and welds the bytes of the mesh file at `path`.
pub fn load_bytes(path: &Path, bytes: &[u8], options: &ReadOptions) -> Result<Loaded, LoadFailure> {
    let name = path.display().to_string();
    // Whatever its extension, a map file is recognised by its header in every command
    // (even a damaged one, which is reported as such: the same answer as `query`'s).
    if haphe::map::looks_like_map(bytes, bytes.len() as u64) {
        let map = haphe::map::MapBytes::copy_from_slice(bytes);
        return Err(LoadFailure::Io(
            match crate::input::map::decode_map(path, &map) {
                Ok(_) => anyhow::anyhow!(
                    "{name}: a map file written by `haphe build`, not a mesh file (query and verify read map files)"
                ),
                Err(e) => e,
            },
        ));
    }
    let start = Instant::now();
    let format = match options.format {
        Some(f) => f,
        None => Format::detect(&name, bytes).map_err(|kind| {
            LoadFailure::Read(ReadError {
                file: name.clone(),
                kind,
            })
        })?,
    };
    let options = ReadOptions {
        format: Some(format),
        ..*options
    };
    let raw = read_unwelded(&name, bytes, &options).map_err(LoadFailure::Read)?;
    let (mesh, weld) = weld(&raw, options.weld);
    Ok(Loaded {
        mesh,
        format,
        weld,
        elapsed: start.elapsed(),
    })
}
