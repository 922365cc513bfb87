//! Volumes: a grid of values from C arrays, a NIfTI-1 file or a voxelised shape; its
//! values and affine out, and the volume written as NIfTI-1.

use std::ffi::c_char;
use std::io::Read;
use std::path::Path;

use haphe_lib::DVec3;
use haphe_lib::glam::{DAffine3, DMat3};
use haphe_lib::volume::{Volume, VolumeError};

use crate::error::{Failure, HapheStatus, guard};
use crate::shape::{HapheShape, output, shape, text};

/// A volume: a regular grid of values placed by an affine (voxel indices to metres), with
/// material where a value is at least its iso value. Opaque; made by `haphe_volume_new`,
/// `haphe_volume_read_nifti` or `haphe_volume_from_shape`, freed by `haphe_volume_free`.
pub struct HapheVolume {
    pub(crate) inner: Volume,
}

/// The most bytes a volume file may have: 8 GiB, as the command line reads.
const MAX_VOLUME_FILE_BYTES: u64 = 8 << 30;

/// The volume behind a handle.
pub(crate) fn volume<'a>(v: *const HapheVolume) -> Result<&'a HapheVolume, Failure> {
    // SAFETY: a non-null handle comes from this library and is not freed yet (documented).
    unsafe { v.as_ref() }.ok_or_else(|| Failure::argument("volume is null"))
}

/// Hands a new volume to the caller through `out`.
fn give(out: *mut *mut HapheVolume, inner: Volume) -> Result<(), Failure> {
    let handle = Box::into_raw(Box::new(HapheVolume { inner }));
    // SAFETY: `out` was checked non-null by the caller of `give` and points to writable
    // storage for a pointer (documented).
    unsafe { *out = handle };
    Ok(())
}

/// `out` checked non-null.
fn out_pointer<T>(out: *mut *mut T) -> Result<(), Failure> {
    if out.is_null() {
        return Err(Failure::argument("out is null"));
    }
    Ok(())
}

/// A volume error as a failure naming the argument at fault.
fn refused(e: VolumeError) -> Failure {
    let what = match e {
        VolumeError::VoxelSize(_) | VolumeError::VoxelCount { .. } => "voxel",
        VolumeError::NotANumber(_) | VolumeError::Count { .. } => "values",
        VolumeError::Dims(_) => "dims",
        VolumeError::Affine => "affine",
        VolumeError::Iso(_) => "iso",
        _ => "volume",
    };
    Failure::argument(format!("{what}: {e}"))
}

/// A volume of `dims[0] × dims[1] × dims[2]` voxels with the `count` values at `values`
/// (`i` fastest: voxel `(i, j, k)` at `i + nx * (j + ny * k)`), placed by `affine` (16
/// doubles, a 4×4 matrix row by row from voxel indices to metres, last row `0 0 0 1`),
/// with material where a value is at least `iso`. The arrays are borrowed for the call
/// (the values are copied). On success `*out` is a new volume owned by the caller (free it
/// with `haphe_volume_free`).
///
/// Errors: `HAPHE_STATUS_INVALID_ARGUMENT` naming the argument: a null pointer, an empty
/// grid or one of more than 2^31 voxels (`dims`), a `count` other than the voxel count
/// or a NaN value, naming its voxel (`values`), an affine whose last row is not `0 0 0 1`
/// or that is not finite and invertible (`affine`), a non-finite `iso`.
#[unsafe(no_mangle)]
pub extern "C" fn haphe_volume_new(
    dims: *const usize,
    values: *const f32,
    count: usize,
    affine: *const f64,
    iso: f32,
    out: *mut *mut HapheVolume,
) -> HapheStatus {
    guard(|| {
        out_pointer(out)?;
        if dims.is_null() || affine.is_null() || (values.is_null() && count > 0) {
            return Err(Failure::argument("dims, values or affine is null"));
        }
        // SAFETY: non-null `dims` points to 3 readable size_t (documented).
        let dims = unsafe { *dims.cast::<[usize; 3]>() };
        // SAFETY: non-null `affine` points to 16 readable doubles (documented).
        let a = unsafe { *affine.cast::<[f64; 16]>() };
        let values: &[f32] = if count == 0 {
            &[]
        } else {
            // SAFETY: the caller passes `count` readable floats at `values` (documented),
            // non-null and aligned.
            unsafe { std::slice::from_raw_parts(values, count) }
        };
        if a[12..] != [0.0, 0.0, 0.0, 1.0] {
            return Err(Failure::argument("affine: its last row must be 0 0 0 1"));
        }
        let column = |c: usize| DVec3::new(a[c], a[4 + c], a[8 + c]);
        let to_world = DAffine3::from_mat3_translation(
            DMat3::from_cols(column(0), column(1), column(2)),
            column(3),
        );
        let inner = Volume::new(dims, values.to_vec(), to_world, iso).map_err(refused)?;
        give(out, inner)
    })
}

/// Reads the bytes of the volume file at `path`, within [`MAX_VOLUME_FILE_BYTES`].
fn read(path: &str) -> Result<Vec<u8>, Failure> {
    let io = |e: std::io::Error| Failure(HapheStatus::Io, format!("cannot read {path}: {e}"));
    let file = std::fs::File::open(path).map_err(io)?;
    let mut bytes = Vec::new();
    file.take(MAX_VOLUME_FILE_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(io)?;
    if bytes.len() as u64 > MAX_VOLUME_FILE_BYTES {
        return Err(Failure(
            HapheStatus::Format,
            format!("{path}: a volume file of more than {MAX_VOLUME_FILE_BYTES} bytes"),
        ));
    }
    Ok(bytes)
}

/// Reads a single-file NIfTI-1 volume (`.nii`, or gzip `.nii.gz` told by content; either
/// byte order; integer or float voxels, scaled by `scl_slope`/`scl_inter`), its affine
/// chosen as nibabel's (sform, else qform, else the voxel sizes) and converted to metres
/// from the header's unit. Material is where a value is at least `iso` when `use_iso` is
/// not 0, else at least the midpoint of the finite values' range.
///
/// `path`: NUL-terminated UTF-8, borrowed for the call. On success `*out` is a new volume
/// owned by the caller (free it with `haphe_volume_free`); on failure it is untouched.
/// Errors: `HAPHE_STATUS_IO` (cannot read), `HAPHE_STATUS_FORMAT` naming the file and the
/// header field or voxel (NIfTI-2, not NIfTI-1, bad dimensions or datatype, truncated
/// data, a NaN value), `HAPHE_STATUS_INVALID_ARGUMENT` (a null pointer, a non-finite
/// `iso` with `use_iso`).
#[unsafe(no_mangle)]
pub extern "C" fn haphe_volume_read_nifti(
    path: *const c_char,
    iso: f32,
    use_iso: i32,
    out: *mut *mut HapheVolume,
) -> HapheStatus {
    guard(|| {
        out_pointer(out)?;
        let path = text("path", path)?;
        if use_iso != 0 && !iso.is_finite() {
            return Err(Failure::argument(format!(
                "iso: must be a finite number, not {iso}"
            )));
        }
        let bytes = read(path)?;
        let given = if use_iso != 0 { iso } else { 0.0 };
        let (mut inner, _) = Volume::read_nifti(path, &bytes, given)
            .map_err(|e| Failure(HapheStatus::Format, e.to_string()))?;
        if use_iso == 0 {
            inner
                .set_iso(Volume::midpoint_iso(inner.values()))
                .map_err(refused)?;
        }
        give(out, inner)
    })
}

/// The volume of a closed solid `shape` voxelised with voxels of `voxel` metres (values
/// signed-distance-like, material inside, iso 0). On success `*out` is a new volume owned
/// by the caller (free it with `haphe_volume_free`).
///
/// Errors: `HAPHE_STATUS_INVALID_ARGUMENT` naming `voxel` (outside its domain, above 0
/// and at most 1 m, or making more than 2^31 voxels), a null pointer, or a shape that is
/// not a closed solid.
#[unsafe(no_mangle)]
pub extern "C" fn haphe_volume_from_shape(
    shape: *const HapheShape,
    voxel: f64,
    out: *mut *mut HapheVolume,
) -> HapheStatus {
    guard(|| {
        out_pointer(out)?;
        let s = self::shape(shape)?;
        let inner = Volume::from_shape(&s.inner, voxel).map_err(|e| match e {
            VolumeError::VoxelSize(p) => Failure::argument(p.named("voxel").to_string()),
            e => refused(e),
        })?;
        give(out, inner)
    })
}

/// Frees a volume made by this library (null is ignored); the handle must not be used
/// again.
#[unsafe(no_mangle)]
pub extern "C" fn haphe_volume_free(volume: *mut HapheVolume) {
    let _ = guard(|| {
        if !volume.is_null() {
            // SAFETY: a non-null handle was made by `Box::into_raw` in this library and is
            // freed once (documented).
            drop(unsafe { Box::from_raw(volume) });
        }
        Ok(())
    });
}

/// Writes the number of voxels along each axis, `nx, ny, nz`, to `out` (3 size_t).
/// Errors: `HAPHE_STATUS_INVALID_ARGUMENT` for a null pointer.
#[unsafe(no_mangle)]
pub extern "C" fn haphe_volume_dims(volume: *const HapheVolume, out: *mut usize) -> HapheStatus {
    guard(|| {
        let dims = self::volume(volume)?.inner.dims();
        output("out", out, 3)?.copy_from_slice(&dims);
        Ok(())
    })
}

/// Writes the affine from voxel indices to metres to `out` (16 doubles: a 4×4 matrix row
/// by row, last row `0 0 0 1`) and the iso value to `iso` (either may be null: skipped).
/// Errors: `HAPHE_STATUS_INVALID_ARGUMENT` for a null volume.
#[unsafe(no_mangle)]
pub extern "C" fn haphe_volume_affine(
    volume: *const HapheVolume,
    out: *mut f64,
    iso: *mut f32,
) -> HapheStatus {
    guard(|| {
        let v = &self::volume(volume)?.inner;
        if !out.is_null() {
            let m = v.to_world();
            let cols = [
                m.matrix3.x_axis,
                m.matrix3.y_axis,
                m.matrix3.z_axis,
                m.translation,
            ];
            for (at, o) in output("out", out, 16)?.iter_mut().enumerate() {
                let (r, c) = (at / 4, at % 4);
                *o = if r == 3 {
                    f64::from(u8::from(c == 3))
                } else {
                    cols[c][r]
                };
            }
        }
        if !iso.is_null() {
            output("iso", iso, 1)?[0] = v.iso();
        }
        Ok(())
    })
}

/// Lends the values: `*out` points to `*count` floats, `i` fastest (voxel `(i, j, k)` at
/// `i + nx * (j + ny * k)`), owned by the volume and valid until it is freed.
/// Errors: `HAPHE_STATUS_INVALID_ARGUMENT` for a null pointer.
#[unsafe(no_mangle)]
pub extern "C" fn haphe_volume_values(
    volume: *const HapheVolume,
    out: *mut *const f32,
    count: *mut usize,
) -> HapheStatus {
    guard(|| {
        let values = self::volume(volume)?.inner.values();
        if out.is_null() || count.is_null() {
            return Err(Failure::argument("out or count is null"));
        }
        // SAFETY: both are non-null and point to writable storage (documented).
        unsafe {
            *out = values.as_ptr();
            *count = values.len();
        }
        Ok(())
    })
}

/// Writes the volume to `path` as NIfTI-1 float32 in millimetres (gzip when the name ends
/// in `.gz`), whole: a new file renamed over `path` once written. `path` is borrowed for
/// the call. Errors: `HAPHE_STATUS_IO` (cannot write, naming the path),
/// `HAPHE_STATUS_INVALID_ARGUMENT` (a null pointer, a side of more than 32767 voxels).
#[unsafe(no_mangle)]
pub extern "C" fn haphe_volume_save(
    volume: *const HapheVolume,
    path: *const c_char,
) -> HapheStatus {
    guard(|| {
        let v = &self::volume(volume)?.inner;
        let path = text("path", path)?;
        let bytes = if path.to_ascii_lowercase().ends_with(".gz") {
            v.to_nifti_gz()
        } else {
            v.to_nifti()
        }
        .map_err(|e| Failure::argument(format!("{path}: {e}")))?;
        haphe_files::write_replacing(Path::new(path), &bytes)
            .map_err(|e| Failure(HapheStatus::Io, e.message()))
    })
}
