//! Shapes: from mesh files, arrays or saved maps; batch inside and first-crossing queries.

use std::ffi::{CStr, c_char};
use std::path::Path;
use std::sync::Arc;

use haphe_lib::DVec3;
use haphe_lib::map::{MapOptions, decode, encode};
use haphe_lib::mesh::{Mesh, ReadOptions, Units, Weld, weld};
use haphe_lib::query::{
    BatchError, NonFinite, Side, check_rows, classify_point, first_crossing, for_each_point,
    for_each_segment,
};
use haphe_lib::scene::Shape;

use crate::error::{Failure, HapheStatus, guard};

/// A shape: a mesh's surface and its voxel map, immutable. Opaque; made by
/// `haphe_shape_from_file`, `haphe_shape_from_arrays` or `haphe_shape_load`, freed by
/// `haphe_shape_free`. A scene holding the shape keeps it alive after it is freed.
pub struct HapheShape {
    pub(crate) inner: Arc<Shape>,
}

/// The first crossing of a segment with a surface.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct HapheCrossing {
    /// Parameter along the segment in [0, 1]; NaN when the segment crosses nothing.
    pub t: f64,
    /// The triangle crossed, as the face index of the mesh as given; -1 when none.
    pub triangle: i64,
    /// The crossing point, metres, object frame (NaN when none).
    pub point: [f64; 3],
    /// The unit face normal of the triangle, object frame (NaN when none).
    pub normal: [f64; 3],
    /// 1 when the segment goes from the front to the back of the triangle (into a solid).
    pub entering: u8,
}

/// A string argument as UTF-8.
pub(crate) fn text<'a>(what: &str, s: *const c_char) -> Result<&'a str, Failure> {
    if s.is_null() {
        return Err(Failure::argument(format!("{what} is null")));
    }
    // SAFETY: the caller passes a NUL-terminated string that outlives the call (documented
    // on every function taking one); it was checked non-null.
    let c = unsafe { CStr::from_ptr(s) };
    c.to_str()
        .map_err(|_| Failure::argument(format!("{what} is not UTF-8")))
}

/// `n` points (3 doubles each) at `p`.
pub(crate) fn points<'a>(what: &str, p: *const f64, n: usize) -> Result<&'a [[f64; 3]], Failure> {
    if n == 0 {
        return Ok(&[]);
    }
    if p.is_null() {
        return Err(Failure::argument(format!("{what} is null")));
    }
    // SAFETY: the caller passes 3·n readable doubles at `p` (documented), non-null and
    // aligned for f64; `[f64; 3]` has the layout of three consecutive doubles.
    Ok(unsafe { std::slice::from_raw_parts(p.cast::<[f64; 3]>(), n) })
}

/// A writable array of `n` values at `p`.
pub(crate) fn output<'a, T>(what: &str, p: *mut T, n: usize) -> Result<&'a mut [T], Failure> {
    if n == 0 {
        return Ok(&mut []);
    }
    if p.is_null() {
        return Err(Failure::argument(format!("{what} is null")));
    }
    // SAFETY: the caller passes `n` writable, aligned values at `p` that nothing else
    // accesses during the call (documented).
    Ok(unsafe { std::slice::from_raw_parts_mut(p, n) })
}

/// Hands a new shape to the caller through `out`.
fn give(out: *mut *mut HapheShape, shape: Shape) -> Result<(), Failure> {
    if out.is_null() {
        return Err(Failure::argument("out is null"));
    }
    let handle = Box::into_raw(Box::new(HapheShape {
        inner: Arc::new(shape),
    }));
    // SAFETY: `out` is non-null and points to writable storage for a pointer (documented).
    unsafe { *out = handle };
    Ok(())
}

/// The shape behind a handle.
pub(crate) fn shape<'a>(s: *const HapheShape) -> Result<&'a HapheShape, Failure> {
    // SAFETY: a non-null handle comes from this library and is not freed yet (documented).
    unsafe { s.as_ref() }.ok_or_else(|| Failure::argument("shape is null"))
}

/// The shape of `mesh` ([`Shape::from_mesh`]); errors are prefixed with `name`.
fn build(name: &str, mesh: Mesh) -> Result<Shape, Failure> {
    Shape::from_mesh(name, mesh, &MapOptions::default())
        .map_err(|e| Failure(HapheStatus::Format, e.to_string()))
}

/// Reads the file at `path`.
fn read(path: &str) -> Result<Vec<u8>, Failure> {
    std::fs::read(path).map_err(|e| Failure(HapheStatus::Io, format!("cannot read {path}: {e}")))
}

/// Reads a mesh file (OBJ, STL, PLY or OFF, told apart by content), welds its vertices
/// exactly, scales it by `metres_per_unit` (1 for metres, 0.001 for millimetres) and
/// builds its voxel map.
///
/// `path`: NUL-terminated UTF-8, borrowed for the call. On success `*out` is a new shape
/// owned by the caller (free it with `haphe_shape_free`); on failure `*out` is untouched.
/// Errors: `HAPHE_STATUS_IO` (cannot read), `HAPHE_STATUS_FORMAT` (the message names the
/// file and the place), `HAPHE_STATUS_INVALID_ARGUMENT`.
#[unsafe(no_mangle)]
pub extern "C" fn haphe_shape_from_file(
    path: *const c_char,
    metres_per_unit: f64,
    out: *mut *mut HapheShape,
) -> HapheStatus {
    guard(|| {
        let path = text("path", path)?;
        if !(metres_per_unit.is_finite() && metres_per_unit > 0.0) {
            return Err(Failure::argument(format!(
                "metres_per_unit must be positive and finite, not {metres_per_unit}"
            )));
        }
        let bytes = read(path)?;
        let options = ReadOptions {
            units: Units::Factor(metres_per_unit),
            weld: Weld::Exact,
            format: None,
        };
        let shape = Shape::read(path, &bytes, &options, &MapOptions::default())
            .map_err(|e| Failure(HapheStatus::Format, e.to_string()))?;
        give(out, shape)
    })
}

/// A shape from arrays: `vertex_count` vertices (3 doubles each, metres) and `face_count`
/// triangles (3 vertex indices each, counter-clockwise seen from outside). Vertices are
/// welded exactly.
///
/// Both arrays are borrowed for the call. On success `*out` is a new shape owned by the
/// caller (free it with `haphe_shape_free`). Errors: `HAPHE_STATUS_FORMAT` naming the
/// vertex or face (index out of range, coordinate not finite, no area),
/// `HAPHE_STATUS_INVALID_ARGUMENT`.
#[unsafe(no_mangle)]
pub extern "C" fn haphe_shape_from_arrays(
    vertices: *const f64,
    vertex_count: usize,
    faces: *const u32,
    face_count: usize,
    out: *mut *mut HapheShape,
) -> HapheStatus {
    guard(|| {
        let v = points("vertices", vertices, vertex_count)?;
        let f: &[[u32; 3]] = if face_count == 0 {
            &[]
        } else if faces.is_null() {
            return Err(Failure::argument("faces is null"));
        } else {
            // SAFETY: the caller passes 3·face_count readable u32 at `faces` (documented),
            // non-null; `[u32; 3]` has the layout of three consecutive u32.
            unsafe { std::slice::from_raw_parts(faces.cast::<[u32; 3]>(), face_count) }
        };
        let mesh = Mesh {
            vertices: v.iter().map(|&p| DVec3::from_array(p)).collect(),
            triangles: f.to_vec(),
        };
        mesh.check_indices_and_finite()
            .map_err(|e| Failure(HapheStatus::Format, format!("arrays: {e}")))?;
        let (mesh, _) = weld(&mesh, Weld::Exact);
        give(out, build("arrays", mesh)?)
    })
}

/// Loads a map file written by `haphe_shape_save` or `haphe build` (checksum and
/// invariants checked). `path` is borrowed for the call; on success `*out` is a new shape
/// owned by the caller. Errors: `HAPHE_STATUS_IO`, `HAPHE_STATUS_FORMAT` (naming the file).
#[unsafe(no_mangle)]
pub extern "C" fn haphe_shape_load(path: *const c_char, out: *mut *mut HapheShape) -> HapheStatus {
    guard(|| {
        let path = text("path", path)?;
        let bytes = read(path)?;
        let (surface, map) =
            decode(&bytes).map_err(|e| Failure(HapheStatus::Format, format!("{path}: {e}")))?;
        give(out, Shape::new(surface, map).with_clear_zones())
    })
}

/// Saves the shape's surface and map as one map file at `path` (a new file renamed over
/// it, so a reader never sees half a file). `path` is borrowed for the call.
/// Errors: `HAPHE_STATUS_IO`.
#[unsafe(no_mangle)]
pub extern "C" fn haphe_shape_save(shape: *const HapheShape, path: *const c_char) -> HapheStatus {
    guard(|| {
        let s = self::shape(shape)?;
        let path = text("path", path)?;
        let bytes = encode(s.inner.surface(), s.inner.map());
        haphe_files::write_replacing(Path::new(path), &bytes)
            .map_err(|e| Failure(HapheStatus::Io, e.message()))
    })
}

/// Frees a shape made by this library (null is ignored). Scenes holding it keep their
/// reference; the handle must not be used again.
#[unsafe(no_mangle)]
pub extern "C" fn haphe_shape_free(shape: *mut HapheShape) {
    let _ = guard(|| {
        if !shape.is_null() {
            // SAFETY: a non-null handle was made by `Box::into_raw` in this library and is
            // freed once (documented).
            drop(unsafe { Box::from_raw(shape) });
        }
        Ok(())
    });
}

/// Number of triangles of the shape's surface (0 for a null handle).
#[unsafe(no_mangle)]
pub extern "C" fn haphe_shape_triangle_count(shape: *const HapheShape) -> usize {
    self::shape(shape).map_or(0, |s| s.inner.surface().triangle_count())
}

/// A flag of the batch queries (`haphe_shape_inside`, `haphe_shape_first_crossing`): a row
/// with a NaN or infinite coordinate answers "nothing found" (not inside, no crossing)
/// instead of failing the call.
pub const HAPHE_SKIP_NONFINITE: u32 = 1;

/// The batch queries' `flags` as the library's option; unknown bits are refused.
fn nonfinite(flags: u32) -> Result<NonFinite, Failure> {
    match flags {
        0 => Ok(NonFinite::Error),
        HAPHE_SKIP_NONFINITE => Ok(NonFinite::Skip),
        other => Err(Failure::argument(format!(
            "flags: unknown bits {other:#x} (the known flag is HAPHE_SKIP_NONFINITE = 1)"
        ))),
    }
}

/// A refused batch as a failure naming the argument and the row.
fn refused(e: BatchError) -> Failure {
    Failure::argument(e.to_string())
}

/// Whether each of `n` points (3 doubles each, metres, object frame) is inside the solid:
/// `inside[i]` is 1 or 0 (always 0 for an open surface). Both arrays are borrowed for the
/// call. Allocates nothing.
///
/// A point with a NaN or infinite coordinate fails the call with
/// `HAPHE_STATUS_INVALID_ARGUMENT`, `haphe_last_error()` naming the first such row
/// (`points: row 17 is not finite (…)`) and nothing written to `inside`; with `flags`
/// `HAPHE_SKIP_NONFINITE` such a row answers 0 instead. `flags` is 0 or
/// `HAPHE_SKIP_NONFINITE`.
#[unsafe(no_mangle)]
pub extern "C" fn haphe_shape_inside(
    shape: *const HapheShape,
    points: *const f64,
    n: usize,
    flags: u32,
    inside: *mut u8,
) -> HapheStatus {
    guard(|| {
        let s = self::shape(shape)?;
        let nonfinite = nonfinite(flags)?;
        let p = self::points("points", points, n)?;
        let out = output("inside", inside, n)?;
        check_rows("points", p, nonfinite).map_err(refused)?;
        out.fill(0);
        let (surface, map) = (s.inner.surface(), s.inner.map());
        for_each_point("points", p, nonfinite, |i, q| {
            out[i] = u8::from(classify_point(surface, map, q).0 == Side::Inside);
        })
        .map_err(refused)
    })
}

/// The first crossing of each of `n` segments `p0[i] → p1[i]` (3 doubles each, metres,
/// object frame) with the surface, found watertight (a segment through an edge or corner
/// meets exactly one triangle), written to `out[i]`. All arrays are borrowed for the call.
/// Allocates nothing.
///
/// A segment with a NaN or infinite coordinate fails the call with
/// `HAPHE_STATUS_INVALID_ARGUMENT`, `haphe_last_error()` naming the first such row (of
/// `p0`, then of `p1`) and nothing written to `out`; with `flags` `HAPHE_SKIP_NONFINITE`
/// such a row answers "no crossing" (`t` NaN, `triangle` -1) instead. `flags` is 0 or
/// `HAPHE_SKIP_NONFINITE`.
#[unsafe(no_mangle)]
pub extern "C" fn haphe_shape_first_crossing(
    shape: *const HapheShape,
    p0: *const f64,
    p1: *const f64,
    n: usize,
    flags: u32,
    out: *mut HapheCrossing,
) -> HapheStatus {
    guard(|| {
        let s = self::shape(shape)?;
        let nonfinite = nonfinite(flags)?;
        let a = points("p0", p0, n)?;
        let b = points("p1", p1, n)?;
        let out = output("out", out, n)?;
        check_rows("p0", a, nonfinite).map_err(refused)?;
        check_rows("p1", b, nonfinite).map_err(refused)?;
        let none = HapheCrossing {
            t: f64::NAN,
            triangle: -1,
            point: [f64::NAN; 3],
            normal: [f64::NAN; 3],
            entering: 0,
        };
        out.fill(none);
        let (surface, map) = (s.inner.surface(), s.inner.map());
        for_each_segment(a, b, nonfinite, |i, q0, q1| {
            if let Some(c) = first_crossing(surface, map, q0, q1) {
                out[i] = HapheCrossing {
                    t: c.t,
                    triangle: i64::from(surface.source_triangle(c.triangle)),
                    point: c.point.to_array(),
                    normal: c.face_normal.to_array(),
                    entering: u8::from(c.entering),
                };
            }
        })
        .map_err(refused)
    })
}
