//! Deformation: a shape's arrays in the surface's order, an object's vertices moved (all
//! of them or a subset), and the shape an object has now.

use haphe_lib::DVec3;
use haphe_lib::scene::{DeformError, ObjectId};

use crate::error::{Failure, HapheStatus, guard};
use crate::scene::{HapheScene, scene_mut};
use crate::shape::{HapheShape, output, points, shape};

/// Number of vertices of the shape's surface (after welding; 0 for a null handle): the
/// rows of `haphe_shape_arrays` and of `haphe_scene_deform`.
#[unsafe(no_mangle)]
pub extern "C" fn haphe_shape_vertex_count(shape: *const HapheShape) -> usize {
    self::shape(shape).map_or(0, |s| s.inner.surface().vertex_count())
}

/// How many deformations made this shape from the one first built (0 for a shape never
/// deformed, and for a null handle).
#[unsafe(no_mangle)]
pub extern "C" fn haphe_shape_version(shape: *const HapheShape) -> u64 {
    self::shape(shape).map_or(0, |s| s.inner.version())
}

/// Copies the shape's surface out: `vertex_count` vertices (3 doubles each, metres, object
/// frame) to `vertices` and `face_count` triangles (3 vertex indices each,
/// counter-clockwise seen from outside) to `faces`. They are in the surface's own order,
/// the order `haphe_scene_deform` takes: vertices after welding, triangles in the spatial
/// order the library keeps, which may differ from the file's (or the arrays given to
/// `haphe_shape_from_arrays`).
///
/// `vertex_count` must be `haphe_shape_vertex_count(shape)` and `face_count`
/// `haphe_shape_triangle_count(shape)`; a null `vertices` or `faces` skips that array (its
/// count is then not checked). Both arrays are borrowed for the call. Errors:
/// `HAPHE_STATUS_INVALID_ARGUMENT` naming the count that differs, nothing written.
#[unsafe(no_mangle)]
pub extern "C" fn haphe_shape_arrays(
    shape: *const HapheShape,
    vertices: *mut f64,
    vertex_count: usize,
    faces: *mut u32,
    face_count: usize,
) -> HapheStatus {
    guard(|| {
        let surface = self::shape(shape)?.inner.surface();
        let (v, f) = (surface.vertices(), surface.triangles());
        let check = |what: &str, given: usize, has: usize, noun: &str| {
            if given == has {
                Ok(())
            } else {
                Err(Failure::argument(format!(
                    "{what} is {given}, but the shape has {has} {noun}"
                )))
            }
        };
        if !vertices.is_null() {
            check("vertex_count", vertex_count, v.len(), "vertices")?;
        }
        if !faces.is_null() {
            check("face_count", face_count, f.len(), "triangles")?;
        }
        if !vertices.is_null() {
            let out = output("vertices", vertices.cast::<[f64; 3]>(), v.len())?;
            for (o, p) in out.iter_mut().zip(v) {
                *o = p.to_array();
            }
        }
        if !faces.is_null() {
            output("faces", faces.cast::<[u32; 3]>(), f.len())?.copy_from_slice(f);
        }
        Ok(())
    })
}

/// A refused deformation as a failure naming the argument at fault and its row.
fn refused(e: DeformError) -> Failure {
    match e {
        DeformError::UnknownObject(_) => Failure::argument(e.to_string()),
        DeformError::Index { .. } | DeformError::IndicesCount { .. } => {
            Failure::argument(format!("indices: {e}"))
        }
        DeformError::Count { .. } | DeformError::NotFinite { .. } => {
            Failure::argument(format!("xyz: {e}"))
        }
        e => Failure::argument(e.to_string()),
    }
}

/// `count` points (3 doubles each) at `xyz`.
fn positions(xyz: *const f64, count: usize) -> Result<Vec<DVec3>, Failure> {
    Ok(points("xyz", xyz, count)?
        .iter()
        .map(|&p| DVec3::from_array(p))
        .collect())
}

/// Deforms object `id`: its vertices move to `xyz` (`count` points, 3 doubles each,
/// metres, object frame: one per vertex, in the order of `haphe_shape_arrays`), its
/// triangles stay. Other objects sharing the shape keep it as it was. Only what the moved
/// triangles touch is recomputed, on the calling thread (it allocates: call it between
/// ticks, not from a tick callback); the deformation is in force from the next tick: a
/// proxy resting on the surface rides it, and a surface that moved over the proxy pushes
/// it out. `xyz` is borrowed for the call.
///
/// Errors, the scene then unchanged: `HAPHE_STATUS_INVALID_ARGUMENT` for an unknown id
/// (`no object 7 in the scene`), a `count` other than the shape's vertex count, or a
/// coordinate that is NaN, infinite or beyond the largest a mesh may have, naming the
/// first such row (`xyz: row 12: a coordinate is not a finite number …`), or a deformed
/// surface that leaves its map's grid so far that a grown grid would be too large.
#[unsafe(no_mangle)]
pub extern "C" fn haphe_scene_deform(
    scene: *mut HapheScene,
    id: u32,
    xyz: *const f64,
    count: usize,
) -> HapheStatus {
    guard(|| {
        let sc = scene_mut(scene)?;
        let p = positions(xyz, count)?;
        sc.inner.deform(ObjectId(id), &p).map_err(refused)
    })
}

/// `haphe_scene_deform` for a subset: vertex `indices[k]` moves to `xyz[3k..3k+3]` for `k`
/// below `count`, the other vertices stay. Both arrays are borrowed for the call.
///
/// Errors, the scene then unchanged: those of `haphe_scene_deform`, and
/// `HAPHE_STATUS_INVALID_ARGUMENT` naming the first index out of range (`indices: row 3:
/// vertex index 900 is out of range (the shape has 642 vertices)`).
#[unsafe(no_mangle)]
pub extern "C" fn haphe_scene_deform_at(
    scene: *mut HapheScene,
    id: u32,
    indices: *const u32,
    xyz: *const f64,
    count: usize,
) -> HapheStatus {
    guard(|| {
        let sc = scene_mut(scene)?;
        let which: &[u32] = if count == 0 {
            &[]
        } else if indices.is_null() {
            return Err(Failure::argument("indices is null"));
        } else {
            // SAFETY: the caller passes `count` readable u32 at `indices` (documented),
            // non-null and aligned.
            unsafe { std::slice::from_raw_parts(indices, count) }
        };
        let p = positions(xyz, count)?;
        sc.inner.deform_at(ObjectId(id), which, &p).map_err(refused)
    })
}

/// A new handle to the shape object `id` has now (deformed, if it was; its
/// `haphe_shape_version` counts the deformations), for the queries of a shape
/// (`haphe_shape_inside`, `haphe_shape_arrays`, …). On success `*out` is owned by the
/// caller: free it with `haphe_shape_free` (the scene keeps its own reference). Errors:
/// `HAPHE_STATUS_INVALID_ARGUMENT` for an unknown id or a null argument.
#[unsafe(no_mangle)]
pub extern "C" fn haphe_scene_shape(
    scene: *mut HapheScene,
    id: u32,
    out: *mut *mut HapheShape,
) -> HapheStatus {
    guard(|| {
        let sc = scene_mut(scene)?;
        if out.is_null() {
            return Err(Failure::argument("out is null"));
        }
        let i = sc
            .inner
            .index_of(ObjectId(id))
            .ok_or_else(|| Failure::argument(format!("no object {id} in the scene")))?;
        let handle = Box::into_raw(Box::new(HapheShape {
            inner: sc.inner.objects()[i].shape.clone(),
        }));
        // SAFETY: `out` is non-null and points to writable storage for a pointer
        // (documented).
        unsafe { *out = handle };
        Ok(())
    })
}
