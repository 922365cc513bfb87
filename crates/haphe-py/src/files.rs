//! Files: reading meshes, validating them, saving and loading maps.

use std::path::{Path, PathBuf};
use std::time::Instant;

use haphe::DVec3;
use haphe::map::{check_source, decode, encode};
use haphe::mesh::{ReadOptions, Resolve, Surface, Units, Weld, read_mesh_resolving};
use haphe::query::Validation;
use pyo3::prelude::*;

use crate::errors::{haphe_error, io_error, os_error};

/// The read options for a `units` string (`m`, `mm`, `cm`, `in` or metres per file unit)
/// and a weld tolerance in metres (`None` or 0: exact).
pub fn read_options(units: &str, weld_tolerance: Option<f64>) -> PyResult<ReadOptions> {
    let units: Units = units.parse().map_err(|e| haphe_error("units", e))?;
    let weld = match weld_tolerance {
        None => Weld::Exact,
        Some(0.0) => Weld::Exact,
        Some(t) if t.is_finite() && t > 0.0 => Weld::Tolerance(t),
        Some(t) => {
            return Err(haphe_error(
                "weld_tolerance",
                format!("must be a non-negative distance in metres, not {t}"),
            ));
        }
    };
    Ok(ReadOptions {
        units,
        weld,
        format: None,
    })
}

/// The units warning of a mesh read in `units` with the bounding box `bounds`, when its
/// size suggests the wrong unit (the library's rule, [`haphe::mesh::units_hint`]), with
/// the argument to add spelt for Python; `None` when its size is plausible.
pub fn units_warning(name: &str, bounds: Option<(DVec3, DVec3)>, units: Units) -> Option<String> {
    let (lo, hi) = bounds?;
    let hint = haphe::mesh::units_hint(lo, hi, units)?;
    Some(format!(
        "{name}: {}",
        hint.advice(|u| format!("`units=\"{u}\"`"))
    ))
}

/// Issues `message` (if any) as a Python `UserWarning` pointing at the caller's line.
pub fn warn(py: Python<'_>, message: Option<String>) -> PyResult<()> {
    let Some(message) = message else {
        return Ok(());
    };
    let text = std::ffi::CString::new(message.replace('\0', " "))
        .map_err(|e| haphe_error("", e.to_string()))?;
    let category = py.get_type::<pyo3::exceptions::PyUserWarning>();
    PyErr::warn(py, category.as_any(), &text, 1)
}

/// The most bytes a glTF side-car buffer file may have: 2 GiB, as for a mesh file.
const MAX_SIDE_CAR_BYTES: u64 = 2 << 30;

/// Side-car files of a `.gltf` (its `.bin` buffers), read from its folder: only as many
/// bytes as the buffer declares, within [`MAX_SIDE_CAR_BYTES`] (the reader has refused
/// absolute paths).
pub struct Folder<'a>(pub &'a Path);

impl Folder<'_> {
    /// The folder of the mesh file at `path`.
    pub fn of(path: &Path) -> Folder<'_> {
        Folder(path.parent().unwrap_or(Path::new(".")))
    }
}

impl Resolve for Folder<'_> {
    fn resolve(&mut self, uri: &str, byte_length: u64) -> Result<Vec<u8>, String> {
        use std::io::Read;
        if byte_length > MAX_SIDE_CAR_BYTES {
            return Err(format!(
                "the buffer declares {byte_length} bytes, more than the limit of \
                 {MAX_SIDE_CAR_BYTES}"
            ));
        }
        let file = std::fs::File::open(self.0.join(uri)).map_err(|e| e.to_string())?;
        let mut bytes = Vec::new();
        file.take(byte_length)
            .read_to_end(&mut bytes)
            .map_err(|e| e.to_string())?;
        Ok(bytes)
    }
}

/// Reads the bytes of `path`.
pub fn read_bytes(path: &Path) -> PyResult<Vec<u8>> {
    std::fs::read(path).map_err(|e| io_error("read", path, &e))
}

/// Writes `bytes` to `path` through a new file renamed over it, so that a reader of the
/// old file never sees a half-written one ([`haphe_files::write_replacing`]).
pub fn write_replacing(path: &Path, bytes: &[u8]) -> PyResult<()> {
    haphe_files::write_replacing(path, bytes).map_err(|e| os_error(e.io().kind(), e.message()))
}

/// Saves a surface and its map as a map file (the format of `haphe build`).
pub fn save_map(path: &Path, surface: &Surface, map: &haphe::map::VoxelMap) -> PyResult<()> {
    write_replacing(path, &encode(surface, map))
}

/// Loads a map file written by `save` or `haphe build`.
pub fn load_map(path: &Path) -> PyResult<(Surface, haphe::map::VoxelMap)> {
    let bytes = read_bytes(path)?;
    decode_map(path, &bytes)
}

/// Decodes the map file at `path` whose content is `bytes` (checked: checksum and
/// invariants), and checks it against its source mesh, the file its provenance names,
/// when that file is beside it: refused when the mesh changed since the map was built.
pub fn decode_map(path: &Path, bytes: &[u8]) -> PyResult<(Surface, haphe::map::VoxelMap)> {
    let name = path.display().to_string();
    let (surface, map) = decode(bytes).map_err(|e| haphe_error(&name, e))?;
    if let Some(p) = map.provenance()
        && let Some(source) = haphe_files::source_beside(path, &p.file)
    {
        let mesh = read_bytes(&source)?;
        check_source(&name, Some(p), &source.display().to_string(), &mesh)
            .map_err(|e| haphe_error("", e))?;
    }
    Ok((surface, map))
}

/// validate(path, units="m", weld_tolerance=None, self_intersections=True)
/// --
///
/// Validates a mesh file (OBJ, STL, PLY, OFF or glTF, told apart by content) and returns the
/// record ``haphe validate --json`` prints: ``file``, ``format``, ``seconds``, ``weld``,
/// the report (``triangles``, ``vertices``, ``closed``, ``usable_as``, ``volume``, …,
/// ``defects``) and ``self_intersections``, ``self_intersections_crossing``,
/// ``self_intersection_pairs`` (``None`` when skipped or the mesh is unusable), plus
/// ``exit_code`` (0 a valid solid, 1 a surface only, 2 unusable).
///
/// Warns (``UserWarning``) when the model spans more than 2 m or less than 5 mm, naming
/// the ``units`` to give.
///
/// Raises ``HapheError`` (naming the file and the place) for an unreadable file and
/// ``OSError`` when the file cannot be read.
#[pyfunction]
#[pyo3(signature = (path, units = "m", weld_tolerance = None, self_intersections = true))]
pub fn validate<'py>(
    py: Python<'py>,
    path: PathBuf,
    units: &str,
    weld_tolerance: Option<f64>,
    self_intersections: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let options = read_options(units, weld_tolerance)?;
    let start = Instant::now();
    let bytes = read_bytes(&path)?;
    let name = path.display().to_string();
    let json = py.detach(|| -> Result<(String, Option<String>), String> {
        let loaded = read_mesh_resolving(&name, &bytes, &options, &mut Folder::of(&path))
            .map_err(|e| e.to_string())?;
        let warning = units_warning(&name, loaded.mesh.bounds(), options.units);
        let validation =
            Validation::of(loaded.mesh, self_intersections).map_err(|e| format!("{name}: {e}"))?;
        let seconds = start.elapsed().as_secs_f64();
        let mut value =
            serde_json::to_value(validation.record(&name, loaded.format, loaded.weld, seconds))
                .map_err(|e| format!("{name}: {e}"))?;
        if let Some(object) = value.as_object_mut() {
            object.insert("exit_code".into(), validation.exit_code().into());
        }
        Ok((value.to_string(), warning))
    });
    let (json, warning) = json.map_err(|e| haphe_error("", e))?;
    warn(py, warning)?;
    // The record goes through Python's json module, so that it is made of plain dicts,
    // lists, numbers and None exactly as `json.loads` of the command's output would be.
    py.import("json")?.getattr("loads")?.call1((json,))
}
