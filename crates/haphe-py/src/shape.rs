//! `haphe.Shape`: a closed solid or open surface with its voxel map, and the batch
//! queries against it (object frame, metres).

use std::path::PathBuf;
use std::sync::Arc;

use haphe::DVec3;
use haphe::map::{MapFileError, MapOptions, decode, encode, looks_like_map};
use haphe::mesh::{Mesh, Units, read_mesh_resolving};
use haphe::query::{
    first_crossing, first_crossing_brute_force, for_each_point, for_each_segment, inside_batch,
    nearest_within,
};
use haphe::scene;
use haphe::verify::{SegmentKind, segments};
use numpy::ndarray::{Array1, Array2};
use numpy::{IntoPyArray, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict};

use crate::arrays::{self, batch_error, rows, rows_argument};
use crate::errors::haphe_error;
use crate::files::{
    Folder, decode_map, load_map, read_bytes, read_options, save_map, units_warning, warn,
};

/// A shape: a mesh's surface (topology, normals) and its voxel map, immutable and shared
/// by every scene it is placed in. Build it from a mesh file (``Shape.from_file``), from
/// arrays (``Shape.from_arrays``) or from a saved map (``Shape.load``).
///
/// All coordinates are metres in the shape's own (object) frame. Triangle indices are
/// those of the faces as given (the file's face order, or the rows of ``faces``).
#[pyclass(module = "haphe", frozen)]
pub struct Shape {
    pub inner: Arc<scene::Shape>,
    /// Where it came from, for messages.
    pub name: String,
}

/// What `__reduce__` gives pickle: `Shape.from_bytes` and its arguments.
type Reduced<'py> = (Bound<'py, PyAny>, (Bound<'py, PyBytes>, String));

/// An `(N, 3)` array of points handed to Python.
type Points<'py> = Bound<'py, numpy::PyArray2<f64>>;

#[pymethods]
impl Shape {
    /// Shape.from_file(path, units="m", weld_tolerance=None)
    /// --
    ///
    /// Reads a mesh file (OBJ, STL, PLY, OFF or glTF, told apart by content; a glTF's
    /// default scene flattened into one mesh in world coordinates, a ``.gltf``'s ``.bin``
    /// files read from its folder), welds it (exactly,
    /// or within ``weld_tolerance`` metres), scales it to metres (``units``: ``"m"``,
    /// ``"mm"``, ``"cm"``, ``"in"`` or metres per file unit) and builds its voxel map.
    ///
    /// Warns (``UserWarning``) when the model spans more than 2 m or less than 5 mm, the
    /// mark of a wrong unit, naming the ``units`` to give ("looks like millimetres: add
    /// ``units="mm"``").
    ///
    /// A map file written by ``haphe build`` or ``shape.save`` (recognised by its header,
    /// whatever its name) is loaded as ``Shape.load`` loads it, in metres: checked, and
    /// refused when the mesh it was built from is beside it and has changed since.
    ///
    /// Raises ``HapheError`` naming the file and the place for bad content, ``OSError``
    /// when the file cannot be read.
    #[staticmethod]
    #[pyo3(signature = (path, units = "m", weld_tolerance = None))]
    fn from_file(
        py: Python<'_>,
        path: PathBuf,
        units: &str,
        weld_tolerance: Option<f64>,
    ) -> PyResult<Shape> {
        let options = read_options(units, weld_tolerance)?;
        let bytes = read_bytes(&path)?;
        let name = path.display().to_string();
        if looks_like_map(&bytes, bytes.len() as u64) {
            if options.units != Units::default() {
                return Err(haphe_error(
                    "units",
                    format!("{name} is a map file, in metres: units apply to mesh files"),
                ));
            }
            let (surface, map) = decode_map(&path, &bytes)?;
            let inner = py.detach(|| scene::Shape::new(surface, map).with_clear_zones());
            return Ok(Shape {
                inner: Arc::new(inner),
                name,
            });
        }
        let (inner, warning) = py
            .detach(|| {
                let loaded = read_mesh_resolving(&name, &bytes, &options, &mut Folder::of(&path))
                    .map_err(|e| e.to_string())?;
                let warning = units_warning(&name, loaded.mesh.bounds(), options.units);
                scene::Shape::from_mesh(&name, loaded.mesh, &MapOptions::default())
                    .map(|shape| (shape, warning))
                    .map_err(|e| e.to_string())
            })
            .map_err(|e| haphe_error("", e))?;
        warn(py, warning)?;
        Ok(Shape {
            inner: Arc::new(inner),
            name,
        })
    }

    /// Shape.from_arrays(vertices, faces)
    /// --
    ///
    /// A shape from a ``(V, 3)`` float array of vertex positions (metres) and an
    /// ``(F, 3)`` integer array of triangles (vertex indices, counter-clockwise seen from
    /// outside). Vertices are welded exactly.
    ///
    /// Raises ``HapheError`` naming the vertex or face for a non-finite coordinate or an
    /// index out of range.
    #[staticmethod]
    fn from_arrays(
        py: Python<'_>,
        vertices: &Bound<'_, PyAny>,
        faces: PyReadonlyArray2<'_, i64>,
    ) -> PyResult<Shape> {
        let vertices = rows_argument("vertices", vertices)?;
        let v = rows(&vertices);
        let f = faces.as_array();
        if f.ncols() != 3 {
            return Err(haphe_error(
                "faces",
                format!("expected an array of shape (F, 3), got {:?}", f.shape()),
            ));
        }
        let count = v.len();
        let mut triangles = Vec::with_capacity(f.nrows());
        for (face, row) in f.rows().into_iter().enumerate() {
            let mut t = [0u32; 3];
            for (slot, &i) in t.iter_mut().zip(row.iter()) {
                *slot = u32::try_from(i)
                    .ok()
                    .filter(|&i| (i as usize) < count)
                    .ok_or_else(|| {
                        haphe_error(
                            "faces",
                            format!(
                                "face {face}: vertex index {i} is out of range (there are {count} vertices)"
                            ),
                        )
                    })?;
            }
            triangles.push(t);
        }
        let mesh = Mesh {
            vertices: v.iter().map(|&p| DVec3::from_array(p)).collect(),
            triangles,
        };
        mesh.check_indices_and_finite()
            .map_err(|e| haphe_error("arrays", e))?;
        let name = "arrays".to_owned();
        let (mesh, _) = haphe::mesh::weld(&mesh, haphe::mesh::Weld::Exact);
        let inner = py
            .detach(|| scene::Shape::from_mesh(&name, mesh, &MapOptions::default()))
            .map_err(|e| haphe_error("", e))?;
        Ok(Shape {
            inner: Arc::new(inner),
            name,
        })
    }

    /// Shape.load(path)
    /// --
    ///
    /// Loads a map file saved by ``shape.save`` or ``haphe build`` (checked: checksum and
    /// invariants; and against the mesh it was built from, when that file is beside it).
    /// Raises ``HapheError`` naming the file for a damaged or foreign file, and naming
    /// both files for a map whose mesh has changed since it was built.
    #[staticmethod]
    fn load(py: Python<'_>, path: PathBuf) -> PyResult<Shape> {
        let (surface, map) = load_map(&path)?;
        let name = path.display().to_string();
        let inner = py.detach(|| scene::Shape::new(surface, map).with_clear_zones());
        Ok(Shape {
            inner: Arc::new(inner),
            name,
        })
    }

    /// save(path)
    /// --
    ///
    /// Saves the surface and its map as one file (the format of ``haphe build``), written
    /// to a new file renamed over ``path``.
    fn save(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        let inner = &self.inner;
        py.detach(|| save_map(&path, inner.surface(), inner.map()))
    }

    /// to_bytes()
    /// --
    ///
    /// The shape as the bytes of its map file (the format of ``shape.save`` and ``haphe
    /// build``: the surface and its voxel map), for ``Shape.from_bytes``. Pickling a shape
    /// sends these bytes.
    fn to_bytes<'py>(&self, py: Python<'py>) -> Bound<'py, PyBytes> {
        let inner = &self.inner;
        let bytes = py.detach(|| encode(inner.surface(), inner.map()));
        PyBytes::new(py, &bytes)
    }

    /// Shape.from_bytes(data, name="bytes")
    /// --
    ///
    /// A shape from the bytes of a map file (``shape.to_bytes()``, or a file written by
    /// ``shape.save`` or ``haphe build``), checked as ``Shape.load`` checks a file
    /// (checksum and invariants) and used without rebuilding the map: the answers are those
    /// of the shape that wrote them, bit for bit. ``name`` is shown in messages and
    /// ``repr``. Raises ``HapheError`` naming ``name`` for damaged or foreign bytes.
    #[staticmethod]
    #[pyo3(signature = (data, name = None))]
    fn from_bytes(py: Python<'_>, data: &[u8], name: Option<String>) -> PyResult<Shape> {
        let name = name.unwrap_or_else(|| "bytes".to_owned());
        let inner = py
            .detach(|| -> Result<scene::Shape, MapFileError> {
                let (surface, map) = decode(data)?;
                Ok(scene::Shape::new(surface, map).with_clear_zones())
            })
            .map_err(|e: MapFileError| haphe_error(&name, e))?;
        Ok(Shape {
            inner: Arc::new(inner),
            name,
        })
    }

    /// Pickling: ``Shape.from_bytes(shape.to_bytes(), name)``, so that a shape reaches
    /// other processes (``multiprocessing``, Dask, Ray) with its map, not rebuilt there.
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Reduced<'py>> {
        let py = slf.py();
        let shape = slf.get();
        let from_bytes = py.get_type::<Shape>().getattr("from_bytes")?;
        Ok((from_bytes, (shape.to_bytes(py), shape.name.clone())))
    }

    /// A shape is immutable: a copy is the shape itself.
    fn __copy__(slf: Bound<'_, Self>) -> Bound<'_, Self> {
        slf
    }

    /// A shape is immutable: a deep copy is the shape itself.
    fn __deepcopy__<'py>(slf: Bound<'py, Self>, _memo: &Bound<'py, PyAny>) -> Bound<'py, Self> {
        slf
    }

    /// inside(points, nonfinite="error")
    /// --
    ///
    /// Whether each point of an ``(N, 3)`` array (metres; anything
    /// ``numpy.asarray(points, dtype=float64)`` takes: lists, float32, any strides) is
    /// inside the solid: an ``(N,)`` bool array. Always ``False`` for an open surface.
    /// Runs without the GIL.
    ///
    /// A row with a NaN or infinite coordinate raises ``HapheError`` naming the first
    /// such row, unless ``nonfinite="skip"``: then it answers ``False``.
    #[pyo3(signature = (points, nonfinite = "error"))]
    fn inside<'py>(
        &self,
        py: Python<'py>,
        points: &Bound<'py, PyAny>,
        nonfinite: &str,
    ) -> PyResult<Bound<'py, numpy::PyArray1<bool>>> {
        let nonfinite = arrays::nonfinite(nonfinite)?;
        let array = rows_argument("points", points)?;
        let p = rows(&array);
        let shape = &*self.inner;
        let out = py
            .detach(|| {
                let mut out = vec![false; p.len()];
                inside_batch(shape.surface(), shape.map(), &p[..], nonfinite, &mut out)
                    .map(|()| out)
            })
            .map_err(batch_error)?;
        Ok(Array1::from_vec(out).into_pyarray(py))
    }

    /// first_crossing(p0, p1, brute_force=False, nonfinite="error")
    /// --
    ///
    /// The first place where each segment ``p0[i] → p1[i]`` (two ``(N, 3)`` arrays, metres,
    /// converted as ``numpy.asarray(x, dtype=float64)`` does) crosses the surface, found
    /// watertight (a segment through an edge or a corner meets exactly one triangle).
    /// Returns a dict of arrays: ``t`` (N,) parameter along the segment (NaN where none),
    /// ``triangle`` (N,) the file's face index (-1 where none), ``point`` (N, 3) and
    /// ``normal`` (N, 3) the crossing and the unit face normal (NaN where none),
    /// ``entering`` (N,) bool (the segment goes from the front to the back of the triangle:
    /// into a solid). Runs without the GIL.
    ///
    /// ``brute_force=True`` tests every triangle instead of walking the map: the oracle of
    /// ``haphe verify`` (the same answers, thousands of times slower on large meshes).
    ///
    /// A segment with a NaN or infinite coordinate raises ``HapheError`` naming the first
    /// such row (of ``p0``, then of ``p1``), unless ``nonfinite="skip"``: then it answers
    /// "no crossing".
    #[pyo3(signature = (p0, p1, brute_force = false, nonfinite = "error"))]
    fn first_crossing<'py>(
        &self,
        py: Python<'py>,
        p0: &Bound<'py, PyAny>,
        p1: &Bound<'py, PyAny>,
        brute_force: bool,
        nonfinite: &str,
    ) -> PyResult<Bound<'py, PyDict>> {
        let nonfinite = arrays::nonfinite(nonfinite)?;
        let (a, b) = (rows_argument("p0", p0)?, rows_argument("p1", p1)?);
        let (a, b) = (rows(&a), rows(&b));
        let n = a.len();
        let shape = &*self.inner;
        let (t, triangle, point, normal, entering) = py
            .detach(|| {
                let mut t = Array1::from_elem(n, f64::NAN);
                let mut triangle = Array1::from_elem(n, -1i64);
                let mut point = Array2::from_elem((n, 3), f64::NAN);
                let mut normal = Array2::from_elem((n, 3), f64::NAN);
                let mut entering = Array1::from_elem(n, false);
                let surface = shape.surface();
                for_each_segment(&a[..], &b[..], nonfinite, |i, q0, q1| {
                    let hit = if brute_force {
                        first_crossing_brute_force(surface, q0, q1)
                    } else {
                        first_crossing(surface, shape.map(), q0, q1)
                    };
                    if let Some(c) = hit {
                        t[i] = c.t;
                        triangle[i] = i64::from(surface.source_triangle(c.triangle));
                        for k in 0..3 {
                            point[[i, k]] = c.point[k];
                            normal[[i, k]] = c.face_normal[k];
                        }
                        entering[i] = c.entering;
                    }
                })
                .map(|()| (t, triangle, point, normal, entering))
            })
            .map_err(batch_error)?;
        let d = PyDict::new(py);
        d.set_item("t", t.into_pyarray(py))?;
        d.set_item("triangle", triangle.into_pyarray(py))?;
        d.set_item("point", point.into_pyarray(py))?;
        d.set_item("normal", normal.into_pyarray(py))?;
        d.set_item("entering", entering.into_pyarray(py))?;
        Ok(d)
    }

    /// nearest(points, max_distance, nonfinite="error")
    /// --
    ///
    /// The nearest surface point to each point of an ``(N, 3)`` array (converted as
    /// ``numpy.asarray(points, dtype=float64)`` does) among those within ``max_distance``
    /// metres, exact for any ``max_distance`` (the map's cells are searched ring by ring
    /// out to the nearest surface found, or every triangle is tested when that is less
    /// work). Returns a dict of arrays: ``distance`` (N,) metres (inf where none),
    /// ``triangle`` (N,) the file's face index (-1 where none), ``point`` (N, 3) (NaN where
    /// none). Runs without the GIL.
    ///
    /// A row with a NaN or infinite coordinate raises ``HapheError`` naming the first
    /// such row, unless ``nonfinite="skip"``: then it answers "none within the radius".
    #[pyo3(signature = (points, max_distance, nonfinite = "error"))]
    fn nearest<'py>(
        &self,
        py: Python<'py>,
        points: &Bound<'py, PyAny>,
        max_distance: f64,
        nonfinite: &str,
    ) -> PyResult<Bound<'py, PyDict>> {
        let nonfinite = arrays::nonfinite(nonfinite)?;
        let array = rows_argument("points", points)?;
        let p = rows(&array);
        if !(max_distance.is_finite() && max_distance >= 0.0) {
            return Err(haphe_error(
                "max_distance",
                format!("must be a non-negative distance in metres, not {max_distance}"),
            ));
        }
        let n = p.len();
        let shape = &*self.inner;
        let (distance, triangle, point) = py
            .detach(|| {
                let mut distance = Array1::from_elem(n, f64::INFINITY);
                let mut triangle = Array1::from_elem(n, -1i64);
                let mut point = Array2::from_elem((n, 3), f64::NAN);
                let surface = shape.surface();
                for_each_point("points", &p[..], nonfinite, |i, q| {
                    if let Some(near) = nearest_within(surface, shape.map(), q, max_distance) {
                        distance[i] = near.distance;
                        triangle[i] = i64::from(surface.source_triangle(near.triangle));
                        for k in 0..3 {
                            point[[i, k]] = near.closest.point[k];
                        }
                    }
                })
                .map(|()| (distance, triangle, point))
            })
            .map_err(batch_error)?;
        let d = PyDict::new(py);
        d.set_item("distance", distance.into_pyarray(py))?;
        d.set_item("triangle", triangle.into_pyarray(py))?;
        d.set_item("point", point.into_pyarray(py))?;
        Ok(d)
    }

    /// sample_segments(kind, n, seed=1)
    /// --
    ///
    /// ``n`` segments of one of the kinds ``haphe verify`` tests, deterministic for a
    /// ``seed``: ``random`` (in the box grown by a fifth), ``through_vertex``,
    /// ``through_edge``, ``in_face_plane``, ``along_edge``, ``short`` (1 nm to 10 µm through
    /// a surface point), ``long`` (a thousand to a million object sizes). Returns
    /// ``(p0, p1)``, two ``(n, 3)`` arrays.
    #[pyo3(signature = (kind, n, seed = 1))]
    fn sample_segments<'py>(
        &self,
        py: Python<'py>,
        kind: &str,
        n: usize,
        seed: u64,
    ) -> PyResult<(Points<'py>, Points<'py>)> {
        let kind = match kind {
            "random" => SegmentKind::Random,
            "through_vertex" => SegmentKind::ThroughVertex,
            "through_edge" => SegmentKind::ThroughEdge,
            "in_face_plane" => SegmentKind::InFacePlane,
            "along_edge" => SegmentKind::AlongEdge,
            "short" => SegmentKind::Short,
            "long" => SegmentKind::Long,
            other => {
                return Err(haphe_error(
                    "kind",
                    format!(
                        "unknown segment kind {other:?} (random, through_vertex, through_edge, in_face_plane, along_edge, short, long)"
                    ),
                ));
            }
        };
        let shape = &*self.inner;
        let (a, b) = py.detach(|| {
            let s = segments(shape.surface(), kind, n, seed);
            let mut a = Array2::zeros((s.len(), 3));
            let mut b = Array2::zeros((s.len(), 3));
            for (i, (p, q)) in s.iter().enumerate() {
                for k in 0..3 {
                    a[[i, k]] = p[k];
                    b[[i, k]] = q[k];
                }
            }
            (a, b)
        });
        Ok((a.into_pyarray(py), b.into_pyarray(py)))
    }

    /// arrays()
    /// --
    ///
    /// The surface as arrays: ``(vertices, faces)``, a ``(V, 3)`` float64 array of vertex
    /// positions (metres, object frame) and an ``(F, 3)`` int64 array of triangles (vertex
    /// indices, counter-clockwise seen from outside). They are in the surface's own order,
    /// the order ``Scene.deform`` takes: vertices after welding, triangles in the spatial
    /// order the library keeps, which may differ from the file's (or the rows given to
    /// ``from_arrays``).
    fn arrays<'py>(&self, py: Python<'py>) -> (Points<'py>, Bound<'py, numpy::PyArray2<i64>>) {
        let surface = self.inner.surface();
        let vertices = surface.vertices();
        let triangles = surface.triangles();
        let v = Array2::from_shape_fn((vertices.len(), 3), |(i, k)| vertices[i][k]);
        let f = Array2::from_shape_fn((triangles.len(), 3), |(i, k)| i64::from(triangles[i][k]));
        (v.into_pyarray(py), f.into_pyarray(py))
    }

    /// How many deformations made this shape from the one first built (0 for a shape never
    /// deformed; ``scene.shape(id).version`` after ``scene.deform``).
    #[getter]
    fn version(&self) -> u64 {
        self.inner.version()
    }

    /// Number of triangles of the surface.
    #[getter]
    fn triangles(&self) -> usize {
        self.inner.surface().triangle_count()
    }

    /// Number of vertices of the surface (after welding).
    #[getter]
    fn vertices(&self) -> usize {
        self.inner.surface().vertex_count()
    }

    /// Whether the shape is a closed, consistently oriented solid (it has an inside).
    #[getter]
    fn is_solid(&self) -> bool {
        self.inner.is_solid()
    }

    /// The axis-aligned bounding box ``((xmin, ymin, zmin), (xmax, ymax, zmax))``, metres.
    #[getter]
    fn bounds(&self) -> ([f64; 3], [f64; 3]) {
        let (lo, hi) = self.inner.surface().bounds();
        (lo.to_array(), hi.to_array())
    }

    fn __repr__(&self) -> String {
        format!(
            "Shape({:?}, triangles={}, solid={})",
            self.name,
            self.inner.surface().triangle_count(),
            self.inner.is_solid()
        )
    }
}
