//! The affine of a NIfTI-1 header, chosen as nibabel's `get_best_affine` chooses it: the
//! sform when `sform_code` is set, else the qform (quaternion, offsets, voxel sizes and
//! `qfac`) when `qform_code` is set, else the fall-back affine of the voxel sizes, centred
//! on the grid with `x` flipped (nibabel's `get_base_affine`). Then scaled to metres by the
//! spatial unit of `xyzt_units`.

use glam::{DAffine3, DMat3, DVec3};
use nifti::NiftiHeader;

use super::error::{ReadVolumeError as Kind, header_error};

/// Which transform of the header placed the grid.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Source {
    Sform,
    Qform,
    Pixdim,
}

impl Source {
    /// How reports name it.
    pub fn name(self) -> &'static str {
        match self {
            Source::Sform => "sform",
            Source::Qform => "qform",
            Source::Pixdim => "pixdim (no sform or qform; nibabel's fall-back)",
        }
    }
}

/// How far below zero `1 - (b² + c² + d²)` may be and still be taken as 0 (nibabel's
/// `fillpositive`: three float32 epsilons, for rounding in the stored quaternion).
const QUATERNION_SLACK: f64 = 3.0 * f32::EPSILON as f64;

/// The header's affine from voxel indices to its own units, which transform it came from,
/// and notes on values taken as nibabel's header check takes them.
///
/// # Errors
/// A quaternion whose `b² + c² + d²` exceeds 1.
pub(super) fn file_affine(
    header: &NiftiHeader,
    dims: [usize; 3],
    notes: &mut Vec<String>,
) -> Result<(DAffine3, Source), Kind> {
    // nibabel ignores codes outside the standard's 1..=4 (its check sets them to 0).
    let valid = |code: i16| (1..=4).contains(&code);
    if valid(header.sform_code) {
        return Ok((sform(header), Source::Sform));
    }
    let zooms = zooms(header, notes);
    if valid(header.qform_code) {
        return Ok((qform(header, zooms, notes)?, Source::Qform));
    }
    Ok((base_affine(header, dims, zooms), Source::Pixdim))
}

/// The rows `srow_x`, `srow_y`, `srow_z`.
fn sform(h: &NiftiHeader) -> DAffine3 {
    let column = |j: usize| DVec3::new(h.srow_x[j].into(), h.srow_y[j].into(), h.srow_z[j].into());
    DAffine3::from_mat3_translation(DMat3::from_cols(column(0), column(1), column(2)), column(3))
}

/// `pixdim[1..=3]` as nibabel's header check leaves them: 0 taken as 1, a negative size as
/// its magnitude (each with a note).
fn zooms(h: &NiftiHeader, notes: &mut Vec<String>) -> DVec3 {
    let mut zooms = [0.0f64; 3];
    for (i, z) in zooms.iter_mut().enumerate() {
        let p = f64::from(h.pixdim[i + 1]);
        *z = if p == 0.0 {
            notes.push(format!("pixdim[{}] is 0: taken as 1", i + 1));
            1.0
        } else if p < 0.0 {
            notes.push(format!("pixdim[{}] is {p}: taken as {}", i + 1, -p));
            -p
        } else {
            p
        };
    }
    DVec3::from_array(zooms)
}

/// The quaternion's rotation, the voxel sizes (the third times `qfac`) and the offsets.
fn qform(h: &NiftiHeader, zooms: DVec3, notes: &mut Vec<String>) -> Result<DAffine3, Kind> {
    let [b, c, d] = [h.quatern_b, h.quatern_c, h.quatern_d].map(f64::from);
    let w2 = 1.0 - (b * b + c * c + d * d);
    if w2 < -QUATERNION_SLACK {
        return Err(header_error(
            "quatern_b, quatern_c, quatern_d",
            format!("({b}, {c}, {d}) has a length beyond 1: not a rotation"),
        ));
    }
    let a = w2.max(0.0).sqrt();
    let qfac = match h.pixdim[0] {
        -1.0 => -1.0,
        1.0 => 1.0,
        other => {
            notes.push(format!("qfac (pixdim[0]) is {other}: taken as 1"));
            1.0
        }
    };
    let scale = DVec3::new(zooms.x, zooms.y, zooms.z * qfac);
    let offset = DVec3::new(h.quatern_x.into(), h.quatern_y.into(), h.quatern_z.into());
    Ok(DAffine3::from_mat3_translation(
        rotation_of_quaternion(a, b, c, d) * DMat3::from_diagonal(scale),
        offset,
    ))
}

/// The rotation of the quaternion `(a, b, c, d)` (`a` the scalar part), normalised first
/// (nibabel's `quat2mat`).
pub(super) fn rotation_of_quaternion(a: f64, b: f64, c: f64, d: f64) -> DMat3 {
    let n = a * a + b * b + c * c + d * d;
    if n < f64::EPSILON {
        return DMat3::IDENTITY;
    }
    let s = 2.0 / n;
    let (x, y, z) = (b * s, c * s, d * s);
    let (wx, wy, wz) = (a * x, a * y, a * z);
    let (xx, xy, xz) = (b * x, b * y, b * z);
    let (yy, yz, zz) = (c * y, c * z, d * z);
    DMat3::from_cols(
        DVec3::new(1.0 - (yy + zz), xy + wz, xz - wy),
        DVec3::new(xy - wz, 1.0 - (xx + zz), yz + wx),
        DVec3::new(xz + wy, yz - wx, 1.0 - (xx + yy)),
    )
}

/// nibabel's fall-back: the voxel sizes on the diagonal, `x` flipped (the radiological
/// convention of Analyze), the grid's centre at the origin.
fn base_affine(h: &NiftiHeader, dims: [usize; 3], zooms: DVec3) -> DAffine3 {
    // Beyond dim[0] nibabel pads the shape and the sizes with 1.
    let dim0 = usize::from(h.dim[0]);
    let zoom = |i: usize| if i < dim0 { zooms[i] } else { 1.0 };
    let scale = DVec3::new(-zoom(0), zoom(1), zoom(2));
    let centre = DVec3::from_array(dims.map(|n| (n as f64 - 1.0) / 2.0));
    DAffine3::from_mat3_translation(DMat3::from_diagonal(scale), -centre * scale)
}

/// Metres per unit of `xyzt_units`' spatial code (mm when unknown, with a note).
///
/// # Errors
/// Codes 4 to 7, which the standard does not define for space.
pub(super) fn metres_per_unit(xyzt_units: u8, notes: &mut Vec<String>) -> Result<f64, Kind> {
    match xyzt_units & 0o7 {
        0 => {
            notes.push("spatial unit unknown (xyzt_units 0): taken as millimetres".to_owned());
            Ok(1e-3)
        }
        1 => Ok(1.0),
        2 => Ok(1e-3),
        3 => Ok(1e-6),
        code => Err(header_error(
            "xyzt_units",
            format!("{xyzt_units}: spatial code {code} is not metre (1), mm (2) or micron (3)"),
        )),
    }
}

/// The affine scaled from file units to metres.
pub(super) fn in_metres(affine: DAffine3, metres_per_unit: f64) -> DAffine3 {
    DAffine3::from_mat3_translation(
        affine.matrix3 * metres_per_unit,
        affine.translation * metres_per_unit,
    )
}
