//! Reading mesh files from disk: the only place the front end opens mesh paths.

use std::path::Path;
use std::time::{Duration, Instant};

use crate::input::files::{self, read_input};
use haphe::DVec3;
use haphe::mesh::{
    Format, GltfSummary, Mesh, ReadError, ReadOptions, Resolve, Units, WeldStats, read_gltf,
    read_unwelded, units_hint, weld,
};

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
    /// For a glTF file read by [`load_reported`]: its scene's nodes (triangles,
    /// transform, closed) and the primitives skipped.
    pub gltf: Option<GltfSummary>,
}

/// The side-car files of the glTF file at a path (its `.bin` buffers), read from its
/// folder once each, within the mesh file limit (the reader has refused absolute paths).
pub struct SideCars<'a>(pub &'a Path);

impl Resolve for SideCars<'_> {
    fn resolve(&mut self, uri: &str, byte_length: u64) -> Result<Vec<u8>, String> {
        if byte_length > files::MESH.bytes {
            return Err(format!(
                "the buffer declares {byte_length} bytes, more than the {} limit of {} bytes",
                files::MESH.what,
                files::MESH.bytes
            ));
        }
        let folder = self.0.parent().unwrap_or(Path::new("."));
        read_input(&folder.join(uri), files::MESH).map_err(|e| format!("{e:#}"))
    }
}

/// Where a mesh file's unit was given, for the units warning's advice.
#[derive(Debug, Clone, Copy)]
pub enum UnitsGiven {
    /// The `--units` flag.
    Flag,
    /// An object's `units` field in a scene file.
    SceneField,
}

/// Warns, on standard error, when the model of `name`, read in `units` with the bounding
/// box `lo`..`hi`, looks read in the wrong unit (the library's [`units_hint`]), saying
/// what to add.
pub fn warn_units(name: &str, (lo, hi): (DVec3, DVec3), units: Units, given: UnitsGiven) {
    if let Some(hint) = units_hint(lo, hi, units) {
        let advice = hint.advice(|u| match given {
            UnitsGiven::Flag => format!("`--units {u}`"),
            UnitsGiven::SceneField => format!("`units = \"{u}\"` to its object in the scene file"),
        });
        eprintln!("haphe: warning: {name}: {advice}");
    }
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

/// As [`load`], and for a glTF file also the report of its scene's nodes
/// ([`Loaded::gltf`]: each distinct mesh welded and analysed once more).
pub fn load_reported(path: &Path, options: &ReadOptions) -> Result<Loaded, LoadFailure> {
    let bytes = read_input(path, files::MESH).map_err(LoadFailure::Io)?;
    parse(path, &bytes, options, true)
}

/// Parses and welds the bytes of the mesh file at `path` (a `.gltf`'s side-car files are
/// read from its folder).
pub fn load_bytes(path: &Path, bytes: &[u8], options: &ReadOptions) -> Result<Loaded, LoadFailure> {
    parse(path, bytes, options, false)
}

fn parse(
    path: &Path,
    bytes: &[u8],
    options: &ReadOptions,
    report_gltf: bool,
) -> Result<Loaded, LoadFailure> {
    let name = path.display().to_string();
    // Whatever its extension, a map file is recognised by its header in every command
    // (even a damaged one, which is reported as such: the same answer as `query`'s).
    if haphe::map::looks_like_map(bytes, bytes.len() as u64) {
        let map = haphe::map::MapBytes::copy_from_slice(bytes);
        return Err(LoadFailure::Io(
            match crate::input::map::decode_map(path, &map) {
                Ok(_) => anyhow::anyhow!(
                    "{name}: a map file written by `haphe build`, not a mesh file (query, verify, simulate, run, view and scene files read map files)"
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
    let (raw, gltf) = if format == Format::Gltf {
        // Read here rather than by `read_unwelded`: the report needs the nodes apart.
        let scene = read_gltf(&name, bytes, options.units, &mut SideCars(path))
            .map_err(LoadFailure::Read)?;
        let report = report_gltf.then(|| scene.summary(options.weld));
        let mesh = scene.flatten();
        mesh.check_indices_and_finite().map_err(|kind| {
            LoadFailure::Read(ReadError {
                file: name.clone(),
                kind,
            })
        })?;
        (mesh, report)
    } else {
        let raw = read_unwelded(&name, bytes, &options).map_err(LoadFailure::Read)?;
        (raw, None)
    };
    let (mesh, weld) = weld(&raw, options.weld);
    Ok(Loaded {
        mesh,
        format,
        weld,
        elapsed: start.elapsed(),
        gltf,
    })
}
