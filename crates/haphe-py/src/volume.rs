//! `haphe.Volume` and `haphe.Cutter`: a grid of values read from a NIfTI-1 file, made from
//! numpy or voxelised from a shape, its iso-surface as a `Shape`, and the tool that cuts
//! into it, each cut a new version of the object's shape (`Scene.replace`).

use std::io::Read;
use std::path::{Path, PathBuf};

use haphe::DVec3;
use haphe::glam::{DAffine3, DMat3};
use haphe::map::MapOptions;
use std::sync::Arc;

use haphe::volume::{CutOptions, Layer, Volume as Grid, VolumeError};
use numpy::ndarray::{Array2, Array3, ShapeBuilder};
use numpy::{IntoPyArray, PyArray2, PyArray3, PyArrayDyn, PyArrayMethods};
use pyo3::prelude::*;

use crate::errors::{haphe_error, io_error, param_error};
use crate::files::write_replacing;
use crate::shape::Shape;

/// What `__reduce__` gives pickle: the class and its arguments.
type Reduced<'py> = (
    Bound<'py, PyAny>,
    (Bound<'py, PyArray3<f32>>, Bound<'py, PyArray2<f64>>, f32),
);

/// The most bytes a volume file may have: 8 GiB, as the command line reads.
const MAX_VOLUME_FILE_BYTES: u64 = 8 << 30;

/// A regular grid of values placed in the world by an affine (voxel indices to metres),
/// with material where a value is at least ``iso``.
///
/// ``Volume(values, affine, iso=None)``: ``values`` an array of shape ``(nx, ny, nz)``
/// indexed ``[i, j, k]`` (as nibabel's ``get_fdata()``), stored as float32; ``affine`` a
/// 4×4 array from voxel indices to metres (last row ``0 0 0 1``); ``iso`` the material
/// threshold (``None``: the midpoint of the finite values' range). Raises ``HapheError``
/// naming the argument for a NaN value (and its voxel), an affine that is not 4×4,
/// finite and invertible, or a non-finite ``iso``.
#[pyclass(module = "haphe", frozen)]
pub struct Volume {
    pub inner: Grid,
}

/// A `Volume` error as a `HapheError` naming the argument at fault.
fn volume_error(e: VolumeError) -> PyErr {
    match e {
        VolumeError::VoxelSize(p) => param_error(p),
        e @ (VolumeError::NotANumber(_) | VolumeError::Count { .. } | VolumeError::Dims(_)) => {
            haphe_error("values", e)
        }
        e @ VolumeError::Affine => haphe_error("affine", e),
        e @ VolumeError::Iso(_) => haphe_error("iso", e),
        e => haphe_error("", e),
    }
}

/// `iso` checked finite, or the midpoint of `values`' finite range when `None`.
fn iso_or_default(iso: Option<f32>, values: &[f32]) -> PyResult<f32> {
    match iso {
        Some(iso) if iso.is_finite() => Ok(iso),
        Some(iso) => Err(haphe_error(
            "iso",
            format!("must be a finite number, not {iso}"),
        )),
        None => Ok(Grid::midpoint_iso(values)),
    }
}

/// The argument `what` through `numpy.asarray(x, dtype)`, `HapheError` naming it when
/// numpy cannot convert it.
fn as_array<'py, T: numpy::Element>(
    what: &str,
    x: &Bound<'py, PyAny>,
    dtype: &str,
) -> PyResult<Bound<'py, PyArrayDyn<T>>> {
    let numpy = x.py().import("numpy")?;
    let array = numpy
        .getattr("asarray")?
        .call1((x, numpy.getattr(dtype)?))
        .map_err(|e| haphe_error(what, format!("cannot be read as an array of {dtype}: {e}")))?;
    Ok(array.cast_into::<PyArrayDyn<T>>()?)
}

/// A 4×4 affine (voxel indices to metres) read from an array-like.
fn affine_argument(x: &Bound<'_, PyAny>) -> PyResult<DAffine3> {
    let array = as_array::<f64>("affine", x, "float64")?;
    let array = array.readonly();
    let a = array.as_array();
    if a.shape() != [4, 4] {
        return Err(haphe_error(
            "affine",
            format!("expected a 4×4 array, got shape {:?}", a.shape()),
        ));
    }
    if [a[[3, 0]], a[[3, 1]], a[[3, 2]], a[[3, 3]]] != [0.0, 0.0, 0.0, 1.0] {
        return Err(haphe_error("affine", "its last row must be 0 0 0 1"));
    }
    let column = |c: usize| DVec3::new(a[[0, c]], a[[1, c]], a[[2, c]]);
    Ok(DAffine3::from_mat3_translation(
        DMat3::from_cols(column(0), column(1), column(2)),
        column(3),
    ))
}

/// Reads the bytes of `path`, refusing a file of more than [`MAX_VOLUME_FILE_BYTES`].
fn read_volume_file(path: &Path) -> PyResult<Vec<u8>> {
    let file = std::fs::File::open(path).map_err(|e| io_error("read", path, &e))?;
    let mut bytes = Vec::new();
    file.take(MAX_VOLUME_FILE_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| io_error("read", path, &e))?;
    if bytes.len() as u64 > MAX_VOLUME_FILE_BYTES {
        return Err(haphe_error(
            &path.display().to_string(),
            format!("a volume file of more than {MAX_VOLUME_FILE_BYTES} bytes"),
        ));
    }
    Ok(bytes)
}

#[pymethods]
impl Volume {
    #[new]
    #[pyo3(signature = (values, affine, iso = None))]
    fn new(
        py: Python<'_>,
        values: &Bound<'_, PyAny>,
        affine: &Bound<'_, PyAny>,
        iso: Option<f32>,
    ) -> PyResult<Volume> {
        let to_world = affine_argument(affine)?;
        let array = as_array::<f32>("values", values, "float32")?;
        let array = array.readonly();
        let a = array.as_array();
        let dims: [usize; 3] = a.shape().try_into().map_err(|_| {
            haphe_error(
                "values",
                format!(
                    "expected an array of shape (nx, ny, nz), got {:?}",
                    a.shape()
                ),
            )
        })?;
        // The transposed view iterates with `i` fastest, the volume's order.
        let flat: Vec<f32> = a.t().iter().copied().collect();
        let iso = iso_or_default(iso, &flat)?;
        let inner = py
            .detach(|| Grid::new(dims, flat, to_world, iso))
            .map_err(volume_error)?;
        Ok(Volume { inner })
    }

    /// Volume.from_nifti(path, iso=None)
    /// --
    ///
    /// Reads a single-file NIfTI-1 volume (``.nii``, or gzip ``.nii.gz`` told by content;
    /// either byte order; integer or float voxels, scaled by ``scl_slope``/``scl_inter``)
    /// with its affine chosen as nibabel's ``img.affine`` (sform, else qform, else the voxel
    /// sizes) and converted to metres from the header's unit. Material is where a value is
    /// at least ``iso`` (``None``: the midpoint of the finite values' range).
    ///
    /// Raises ``HapheError`` naming the file and the header field or voxel (NIfTI-2, not
    /// NIfTI-1, bad dimensions or datatype, truncated data, a NaN value), ``OSError`` when
    /// the file cannot be read.
    #[staticmethod]
    #[pyo3(signature = (path, iso = None))]
    fn from_nifti(py: Python<'_>, path: PathBuf, iso: Option<f32>) -> PyResult<Volume> {
        iso_or_default(iso, &[])?;
        let bytes = read_volume_file(&path)?;
        let name = path.display().to_string();
        let (mut inner, _) = py
            .detach(|| Grid::read_nifti(&name, &bytes, iso.unwrap_or(0.0)))
            .map_err(|e| haphe_error("", e))?;
        if iso.is_none() {
            inner
                .set_iso(Grid::midpoint_iso(inner.values()))
                .map_err(volume_error)?;
        }
        Ok(Volume { inner })
    }

    /// Volume.from_mesh(shape, voxel)
    /// --
    ///
    /// The volume of a closed solid ``shape``, voxelised with voxels of ``voxel`` metres
    /// (values: signed distance-like, material inside, iso 0). Raises ``HapheError``
    /// naming ``voxel`` for a size out of its domain or one making too many voxels, and
    /// for a shape that is not a closed solid.
    #[staticmethod]
    fn from_mesh(py: Python<'_>, shape: &Shape, voxel: f64) -> PyResult<Volume> {
        let inner = py
            .detach(|| Grid::from_shape(&shape.inner, voxel))
            .map_err(|e| match e {
                e @ VolumeError::VoxelCount { .. } => haphe_error("voxel", e),
                e @ VolumeError::NotSolid => haphe_error(&shape.name, e),
                e => volume_error(e),
            })?;
        Ok(Volume { inner })
    }

    /// save(path)
    /// --
    ///
    /// Writes the volume as NIfTI-1 float32 in metres, gzip when ``path`` ends in ``.gz``,
    /// whole: a new file renamed over ``path`` once written. Raises ``HapheError`` for a
    /// side of more than 32767 voxels, ``OSError`` when the file cannot be written.
    fn save(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        let gzip = path.to_string_lossy().to_ascii_lowercase().ends_with(".gz");
        let bytes = py
            .detach(|| {
                if gzip {
                    self.inner.to_nifti_gz()
                } else {
                    self.inner.to_nifti()
                }
            })
            .map_err(|e| haphe_error(&path.display().to_string(), e))?;
        write_replacing(&path, &bytes)
    }

    /// shape(name="volume")
    /// --
    ///
    /// The shape of the iso-surface (a closed triangle surface and its map), in the
    /// volume's frame. Raises ``HapheError`` when no voxel is material.
    #[pyo3(signature = (name = "volume"))]
    fn shape(&self, py: Python<'_>, name: &str) -> PyResult<Shape> {
        let inner = py
            .detach(|| self.inner.shape(name, &MapOptions::default()))
            .map_err(|e| haphe_error("", e))?;
        Ok(Shape {
            inner: inner.into(),
            name: name.to_owned(),
        })
    }

    /// Pickling: ``Volume(values(), affine, iso)``, so that a volume reaches other
    /// processes with its values, affine and iso bit for bit.
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Reduced<'py>> {
        let py = slf.py();
        let volume = slf.get();
        let class = py.get_type::<Volume>().into_any();
        Ok((
            class,
            (volume.values(py)?, volume.affine(py), volume.inner.iso()),
        ))
    }

    /// values()
    /// --
    ///
    /// A float32 copy of the values, of shape ``(nx, ny, nz)``: ``values()[i, j, k]`` is
    /// voxel ``(i, j, k)``.
    fn values<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray3<f32>>> {
        let [nx, ny, nz] = self.inner.dims();
        let array = Array3::from_shape_vec((nx, ny, nz).f(), self.inner.values().to_vec())
            .map_err(|e| haphe_error("values", e))?;
        Ok(array.into_pyarray(py))
    }

    /// The number of voxels along each axis, ``(nx, ny, nz)``.
    #[getter]
    fn dims(&self) -> (usize, usize, usize) {
        let [nx, ny, nz] = self.inner.dims();
        (nx, ny, nz)
    }

    /// The 4×4 affine from voxel indices to metres (float64).
    #[getter]
    fn affine<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let m = self.inner.to_world();
        let cols = [
            m.matrix3.x_axis,
            m.matrix3.y_axis,
            m.matrix3.z_axis,
            m.translation,
        ];
        Array2::from_shape_fn((4, 4), |(r, c)| match r {
            3 => f64::from(u8::from(c == 3)),
            _ => cols[c][r],
        })
        .into_pyarray(py)
    }

    /// Material is where a value is at least this.
    #[getter]
    fn iso(&self) -> f32 {
        self.inner.iso()
    }

    /// The centre of the grid's bounding box, metres.
    #[getter]
    fn centre(&self) -> (f64, f64, f64) {
        self.inner.centre().into()
    }

    fn __repr__(&self) -> String {
        let [nx, ny, nz] = self.inner.dims();
        format!("Volume(dims=({nx}, {ny}, {nz}), iso={})", self.inner.iso())
    }
}

/// A tool that cuts into a volume: told where it pressed and how hard, it removes the
/// material in its reach and makes the next version of the volume's shape.
///
/// ``Cutter(volume, tool_radius, cut_force=0.5, layers=None)``: a copy of ``volume`` cut
/// by a tool of ``tool_radius`` metres from a contact force of ``cut_force`` N.
/// ``layers`` are its materials, each spelled ``"NAME:FROM:RATE:STIFFNESS[:FRICTION[:DYNAMIC]]"``
/// (its lowest value, the rate it is cut at in m/s, N/m, friction coefficients), e.g.
/// ``["dentin:1:0.01:600", "enamel:2:0.002:900:0.4"]``: a value takes the layer with the
/// highest ``FROM`` at most the value, and each triangle of the surface feels like the
/// material beside it. Raises ``HapheError`` naming the parameter out of its domain (or
/// ``layers`` and the specification), or when the volume has no material.
///
/// Place ``cutter.shape`` in a scene (or ``Scene.add_volume(cutter)``); each tick, ``press`` with the proxy's position in
/// the volume's frame and the contact force; now and then ``refresh`` and give the new
/// shape to the object (``Scene.replace``).
#[pyclass(module = "haphe")]
pub struct Cutter {
    inner: haphe::volume::Cutter,
}

#[pymethods]
impl Cutter {
    #[new]
    #[pyo3(signature = (volume, tool_radius, cut_force = CutOptions::DEFAULT_CUT_FORCE, layers = None))]
    fn new(
        py: Python<'_>,
        volume: &Volume,
        tool_radius: f64,
        cut_force: f64,
        layers: Option<Vec<String>>,
    ) -> PyResult<Cutter> {
        let layers = layers
            .unwrap_or_default()
            .iter()
            .map(|spec| spec.parse::<Layer>().map_err(|e| haphe_error("layers", e)))
            .collect::<PyResult<Vec<Layer>>>()?;
        let options = CutOptions::new(tool_radius, cut_force)
            .map_err(param_error)?
            .with_layers(layers);
        let grid = volume.inner.clone();
        let inner = py
            .detach(|| {
                let mut inner = haphe::volume::Cutter::new("volume", grid, MapOptions::default())?;
                inner.set_options(options)?;
                Ok::<_, haphe::volume::CutError>(inner)
            })
            .map_err(|e| haphe_error("", e))?;
        Ok(Cutter { inner })
    }

    /// layers()
    /// --
    ///
    /// The layers, sorted by their lowest value, as ``(name, from, rate, stiffness,
    /// static_friction, dynamic_friction)``; one default layer when none was given.
    fn layers(&self) -> Vec<(String, f32, f64, f64, f64, f64)> {
        self.inner
            .options()
            .layers()
            .iter()
            .map(|l| {
                let m = &l.material;
                let friction = (m.static_friction(), m.dynamic_friction());
                (
                    l.name.clone(),
                    l.from,
                    l.rate,
                    m.stiffness(),
                    friction.0,
                    friction.1,
                )
            })
            .collect()
    }

    /// press(centre, force, dt)
    /// --
    ///
    /// One tick of the tool centred at ``centre`` (metres, the volume's frame) pressing
    /// with a contact force of ``force`` N for ``dt`` seconds: below the cut force nothing
    /// happens, else the voxels in reach progress and those done are removed. Returns how
    /// many were removed. Raises ``HapheError`` naming a non-finite argument.
    fn press(&mut self, centre: [f64; 3], force: f64, dt: f64) -> PyResult<usize> {
        let centre = DVec3::from_array(centre);
        if !centre.is_finite() {
            return Err(haphe_error("centre", format!("{centre} is not finite")));
        }
        for (what, x) in [("force", force), ("dt", dt)] {
            if !x.is_finite() {
                return Err(haphe_error(what, format!("{x} is not finite")));
            }
        }
        Ok(self.inner.press(centre, force, dt))
    }

    /// refresh()
    /// --
    ///
    /// The next version of the shape, made from the chunks changed since the last
    /// refresh (without the GIL), or ``None`` when nothing changed. Raises ``HapheError``
    /// once no material is left.
    fn refresh(&mut self, py: Python<'_>) -> PyResult<Option<Shape>> {
        let inner = &mut self.inner;
        let shape = py
            .detach(|| inner.refresh())
            .map_err(|e| haphe_error("", e))?;
        Ok(shape.map(|inner| Shape {
            inner,
            name: "volume".to_owned(),
        }))
    }

    /// The latest shape made (what ``refresh`` last returned, or the first).
    #[getter]
    fn shape(&self) -> Shape {
        Shape {
            inner: self.inner.shape().clone(),
            name: "volume".to_owned(),
        }
    }

    /// A copy of the volume as cut so far.
    #[getter]
    fn volume(&self) -> Volume {
        Volume {
            inner: self.inner.volume().clone(),
        }
    }

    /// How many voxels it removed.
    #[getter]
    fn removed(&self) -> u64 {
        self.inner.removed()
    }

    /// The tool's radius, metres.
    #[getter]
    fn tool_radius(&self) -> f64 {
        self.inner.options().tool_radius()
    }

    /// The contact force from which it cuts, N.
    #[getter]
    fn cut_force(&self) -> f64 {
        self.inner.options().cut_force()
    }
}

/// The shape of `volume` (a `Cutter`: its latest shape; a `Volume`: its iso-surface) and
/// the centre of its grid, in the volume's frame.
///
/// # Errors
/// `TypeError` for anything else; `HapheError` when a volume has no material.
pub(crate) fn surface_of(
    py: Python<'_>,
    volume: &Bound<'_, PyAny>,
) -> PyResult<(Arc<haphe::scene::Shape>, DVec3)> {
    if let Ok(cutter) = volume.cast::<Cutter>() {
        let cutter = cutter.borrow();
        let inner = &cutter.inner;
        return Ok((Arc::clone(inner.shape()), inner.volume().centre()));
    }
    if let Ok(v) = volume.cast::<Volume>() {
        let v = v.get();
        let shape = py
            .detach(|| v.inner.shape("volume", &MapOptions::default()))
            .map_err(|e| haphe_error("volume", e))?;
        return Ok((Arc::new(shape), v.inner.centre()));
    }
    Err(pyo3::exceptions::PyTypeError::new_err(
        "add_volume takes a haphe.Cutter or a haphe.Volume",
    ))
}
