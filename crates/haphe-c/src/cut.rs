//! Cutting: a tool that removes the material of a volume it presses on, each refresh a
//! new version of the volume's shape, given to a scene's object by `haphe_scene_replace`.

use std::ffi::c_char;
use std::sync::Arc;

use haphe_lib::DVec3;
use haphe_lib::map::MapOptions;
use haphe_lib::scene::{EditError, ObjectId, Pose};
use haphe_lib::volume::{CutOptions, Cutter, Layer};

use crate::error::{Failure, HapheStatus, guard};
use crate::scene::{HapheMaterial, HapheScene, scene_mut};
use crate::shape::{HapheShape, shape, text};
use crate::volume::{HapheVolume, volume};

/// A tool cutting into a volume (its own copy). Opaque; made by `haphe_cutter_new`, freed
/// by `haphe_cutter_free`. Used by one thread at a time, never a servo tick's (a refresh
/// allocates and takes milliseconds).
pub struct HapheCutter {
    inner: Cutter,
}

/// The cutter behind a handle.
fn cutter<'a>(c: *mut HapheCutter) -> Result<&'a mut HapheCutter, Failure> {
    // SAFETY: a non-null handle comes from this library, is not freed yet and is not used
    // by another thread during the call (documented).
    unsafe { c.as_mut() }.ok_or_else(|| Failure::argument("cutter is null"))
}

/// Hands a new shape handle to the caller through `out` (checked non-null).
fn give_shape(out: *mut *mut HapheShape, shape: Option<HapheShape>) {
    let handle = shape.map_or(std::ptr::null_mut(), |s| Box::into_raw(Box::new(s)));
    // SAFETY: `out` is non-null and points to writable storage for a pointer (documented).
    unsafe { *out = handle };
}

/// A cutter of a copy of `volume`: a tool of `tool_radius` metres cutting from a contact
/// force of `cut_force` N (0.5 is the library's default), its surface extracted and its
/// first shape built. On success `*out` is a new cutter owned by the caller (free it with
/// `haphe_cutter_free`); the volume stays the caller's.
///
/// Errors: `HAPHE_STATUS_INVALID_ARGUMENT` naming `tool_radius` or `cut_force` outside its
/// domain, or a null pointer; `HAPHE_STATUS_FORMAT` when the volume has no material (no
/// surface to render).
#[unsafe(no_mangle)]
pub extern "C" fn haphe_cutter_new(
    volume: *const HapheVolume,
    tool_radius: f64,
    cut_force: f64,
    out: *mut *mut HapheCutter,
) -> HapheStatus {
    guard(|| {
        let v = self::volume(volume)?;
        if out.is_null() {
            return Err(Failure::argument("out is null"));
        }
        let options = CutOptions::new(tool_radius, cut_force)?;
        let mut inner = Cutter::new("volume", v.inner.clone(), MapOptions::default())?;
        inner.set_options(options)?;
        let handle = Box::into_raw(Box::new(HapheCutter { inner }));
        // SAFETY: `out` is non-null and points to writable storage for a pointer
        // (documented).
        unsafe { *out = handle };
        Ok(())
    })
}

/// Gives the cutter the `count` layers of `layers` (NUL-terminated strings, each
/// `NAME:FROM:RATE:STIFFNESS[:FRICTION[:DYNAMIC]]`: the material's lowest value, the rate
/// it is cut at in m/s, its stiffness in N/m and friction coefficients, e.g.
/// `"enamel:2:0.004:900:0.4"`), replacing those it had: a value takes the layer with the
/// highest FROM at most the value, each is cut at its rate, and each triangle of the
/// surface feels like the material beside it, over the object's material. No layer
/// (`count` 0) gives one material back: the object's, cut at 20 mm/s. The cutter's shape
/// is made again now (get it with `haphe_cutter_shape`): call this before adding it to a
/// scene.
///
/// Errors: `HAPHE_STATUS_INVALID_ARGUMENT` naming `layers` and the first refused
/// specification (its form, a value that is not a number or outside its domain), or a
/// null pointer; the cutter keeps its layers.
#[unsafe(no_mangle)]
pub extern "C" fn haphe_cutter_set_layers(
    cutter: *mut HapheCutter,
    layers: *const *const c_char,
    count: usize,
) -> HapheStatus {
    guard(|| {
        let c = self::cutter(cutter)?;
        if layers.is_null() && count > 0 {
            return Err(Failure::argument("layers is null"));
        }
        let specs: &[*const c_char] = if count == 0 {
            &[]
        } else {
            // SAFETY: `layers` is non-null and points to `count` string pointers
            // (documented).
            unsafe { std::slice::from_raw_parts(layers, count) }
        };
        let parsed = specs
            .iter()
            .map(|&p| {
                let spec = text("layers", p)?;
                spec.parse::<Layer>()
                    .map_err(|e| Failure::argument(format!("layers: {e}")))
            })
            .collect::<Result<Vec<Layer>, Failure>>()?;
        let options = c.inner.options().clone().with_layers(parsed);
        Ok(c.inner.set_options(options)?)
    })
}

/// Places the cutter's latest shape in `scene` as `haphe_scene_add` does, with the centre
/// of the volume's grid at `position` (3 doubles, metres; null: the origin, where the
/// command line places a volume) and turned by `rotation` about it (x, y, z, w; null:
/// none), with `material` (null: the default; a layered volume's triangles feel like
/// their layers whatever it says). `*id` (may be null) receives the object's id; give it
/// the cutter's new shapes with `haphe_scene_replace`. Presses then take the tool's
/// centre in the volume's frame: the world point less the object's placement.
///
/// Errors: those of `haphe_scene_add`, or a null pointer.
#[unsafe(no_mangle)]
pub extern "C" fn haphe_scene_add_volume(
    scene: *mut HapheScene,
    cutter: *mut HapheCutter,
    position: *const f64,
    rotation: *const f64,
    material: *const HapheMaterial,
    id: *mut u32,
) -> HapheStatus {
    guard(|| {
        let sc = scene_mut(scene)?;
        let c = self::cutter(cutter)?;
        let at = crate::scene::pose(position, rotation)?;
        // The grid's centre at `position`: the object's origin goes to where -centre lands.
        let centre = c.inner.volume().centre();
        let pose = Pose::new(at.rotation(), at.to_world(-centre))?;
        let shape = Arc::clone(c.inner.shape());
        crate::scene::insert(sc, shape, pose, material, id)
    })
}

/// Frees a cutter made by this library (null is ignored); the handle must not be used
/// again. Shapes it made stay valid.
#[unsafe(no_mangle)]
pub extern "C" fn haphe_cutter_free(cutter: *mut HapheCutter) {
    let _ = guard(|| {
        if !cutter.is_null() {
            // SAFETY: a non-null handle was made by `Box::into_raw` in this library and is
            // freed once (documented).
            drop(unsafe { Box::from_raw(cutter) });
        }
        Ok(())
    });
}

/// A new handle to the latest shape the cutter made (the first, or the last refresh's),
/// in the volume's frame: place it in a scene with `haphe_scene_add`. `*out` is owned by
/// the caller: free it with `haphe_shape_free`. Errors: `HAPHE_STATUS_INVALID_ARGUMENT`
/// for a null pointer.
#[unsafe(no_mangle)]
pub extern "C" fn haphe_cutter_shape(
    cutter: *mut HapheCutter,
    out: *mut *mut HapheShape,
) -> HapheStatus {
    guard(|| {
        let c = self::cutter(cutter)?;
        if out.is_null() {
            return Err(Failure::argument("out is null"));
        }
        let inner = c.inner.shape().clone();
        give_shape(out, Some(HapheShape { inner }));
        Ok(())
    })
}

/// One tick of the tool centred at `centre` (3 doubles, metres, the volume's frame)
/// pressing with a contact force of `force` N for `dt` seconds: below the cut force
/// nothing happens, else the voxels in its reach progress and those done are removed.
/// Writes how many were removed to `removed` (null: skipped). Allocates little (the
/// voxels in progress); call it from the thread that refreshes, with each tick's output.
///
/// Errors: `HAPHE_STATUS_INVALID_ARGUMENT` naming `centre`, `force` or `dt` when not
/// finite, or a null pointer.
#[unsafe(no_mangle)]
pub extern "C" fn haphe_cutter_press(
    cutter: *mut HapheCutter,
    centre: *const f64,
    force: f64,
    dt: f64,
    removed: *mut usize,
) -> HapheStatus {
    guard(|| {
        let c = self::cutter(cutter)?;
        if centre.is_null() {
            return Err(Failure::argument("centre is null"));
        }
        // SAFETY: non-null `centre` points to 3 readable doubles (documented).
        let centre = DVec3::from_array(unsafe { *centre.cast::<[f64; 3]>() });
        if !centre.is_finite() {
            return Err(Failure::argument(format!("centre: {centre} is not finite")));
        }
        for (what, x) in [("force", force), ("dt", dt)] {
            if !x.is_finite() {
                return Err(Failure::argument(format!("{what}: {x} is not finite")));
            }
        }
        let n = c.inner.press(centre, force, dt);
        if !removed.is_null() {
            // SAFETY: non-null `removed` points to a writable size_t (documented).
            unsafe { *removed = n };
        }
        Ok(())
    })
}

/// The next version of the shape, from the chunks changed since the last refresh:
/// `*out` is a new shape handle owned by the caller (free it with `haphe_shape_free`;
/// give it to the object with `haphe_scene_replace`), or null when nothing changed.
/// Runs on the calling thread (milliseconds; it allocates).
///
/// Errors: `HAPHE_STATUS_FORMAT` once no material is left (no surface), or when the new
/// surface cannot be mapped; `HAPHE_STATUS_INVALID_ARGUMENT` for a null pointer.
#[unsafe(no_mangle)]
pub extern "C" fn haphe_cutter_refresh(
    cutter: *mut HapheCutter,
    out: *mut *mut HapheShape,
) -> HapheStatus {
    guard(|| {
        let c = self::cutter(cutter)?;
        if out.is_null() {
            return Err(Failure::argument("out is null"));
        }
        let shape = c.inner.refresh()?;
        give_shape(out, shape.map(|inner| HapheShape { inner }));
        Ok(())
    })
}

/// How many voxels the cutter removed (0 for a null handle).
#[unsafe(no_mangle)]
pub extern "C" fn haphe_cutter_removed(cutter: *mut HapheCutter) -> u64 {
    self::cutter(cutter).map_or(0, |c| c.inner.removed())
}

/// A new handle to a copy of the volume as cut so far (to save it): `*out` is owned by
/// the caller (free it with `haphe_volume_free`). Errors: `HAPHE_STATUS_INVALID_ARGUMENT`
/// for a null pointer.
#[unsafe(no_mangle)]
pub extern "C" fn haphe_cutter_volume(
    cutter: *mut HapheCutter,
    out: *mut *mut HapheVolume,
) -> HapheStatus {
    guard(|| {
        let c = self::cutter(cutter)?;
        if out.is_null() {
            return Err(Failure::argument("out is null"));
        }
        let handle = Box::into_raw(Box::new(HapheVolume {
            inner: c.inner.volume().clone(),
        }));
        // SAFETY: `out` is non-null and points to writable storage for a pointer
        // (documented).
        unsafe { *out = handle };
        Ok(())
    })
}

/// Gives object `id` a new version of its shape: one `haphe_cutter_refresh` made from the
/// object's, or a shape with the same counts of vertices and triangles. In force from the
/// next tick (a proxy resting on the surface rides it). The scene keeps its own reference:
/// the caller still frees `shape`. Allocates nothing.
///
/// Errors, the scene then unchanged: `HAPHE_STATUS_INVALID_ARGUMENT` for an unknown id
/// (`no object 7 in the scene`), a shape that is not a version of the object's (`shape:
/// the shape is not a new version …`) or a null pointer.
#[unsafe(no_mangle)]
pub extern "C" fn haphe_scene_replace(
    scene: *mut HapheScene,
    id: u32,
    shape: *const HapheShape,
) -> HapheStatus {
    guard(|| {
        let sc = scene_mut(scene)?;
        let s = self::shape(shape)?;
        match sc.inner.replace(ObjectId(id), s.inner.clone()) {
            Ok(_) => Ok(()),
            Err(EditError::UnknownObject) => {
                Err(Failure::argument(format!("no object {id} in the scene")))
            }
            Err(e) => Err(Failure::argument(format!("shape: {e}"))),
        }
    })
}
