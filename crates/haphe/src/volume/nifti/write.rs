//! A volume as a single-file NIfTI-1: float32 values, little-endian, the affine in
//! millimetres as the sform (and as the qform when its matrix is a rotation times voxel
//! sizes).
//!
//! The 348-byte header is written here rather than by the `nifti` crate: its writer writes
//! to a path in place, while the front ends write every output atomically (haphe-files)
//! from bytes, and the library opens no files.

use std::io::Write;

use flate2::write::GzEncoder;
use glam::{DMat3, DQuat};

use super::header::{FIRST_DATA_BYTE, HEADER_BYTES};
use crate::volume::{Volume, VolumeError};

/// The largest side a NIfTI-1 header holds (`dim` is a signed 16-bit number).
const MAX_SIDE: usize = i16::MAX as usize;
/// How far the columns of the affine, divided by their lengths, may be from orthonormal
/// for the qform to hold it: the float32 fields keep about seven digits.
const ROTATION_TOLERANCE: f64 = 1e-6;
/// Millimetres per metre: the header's unit is the millimetre (`xyzt_units` 2).
const MM_PER_M: f64 = 1e3;

impl Volume {
    /// The volume as a single-file NIfTI-1 (`.nii`): float32 values, little-endian;
    /// `sform_code` 1 (scanner) holding the affine in millimetres (`xyzt_units` 2), and
    /// `qform_code` 1 with the same affine as a quaternion when its matrix is a rotation
    /// times voxel sizes (else `qform_code` 0). The header's fields are float32: the affine
    /// keeps about seven digits (exactly, when its entries in millimetres are float32
    /// numbers). The iso value is not stored.
    ///
    /// # Errors
    /// [`VolumeError::NiftiDims`]: a side of more than 32767 voxels.
    pub fn to_nifti(&self) -> Result<Vec<u8>, VolumeError> {
        if self.dims.iter().any(|&d| d > MAX_SIDE) {
            return Err(VolumeError::NiftiDims(self.dims));
        }
        let mut out = Vec::with_capacity(FIRST_DATA_BYTE as usize + 4 * self.values.len());
        out.extend_from_slice(&self.header());
        out.extend_from_slice(&[0; 4]); // no extensions
        for v in &self.values {
            out.extend_from_slice(&v.to_le_bytes());
        }
        Ok(out)
    }

    /// [`Volume::to_nifti`] as a gzip stream (`.nii.gz`).
    ///
    /// # Errors
    /// As [`Volume::to_nifti`].
    pub fn to_nifti_gz(&self) -> Result<Vec<u8>, VolumeError> {
        Ok(gzip(&self.to_nifti()?))
    }

    /// The 348 bytes of the header (little-endian).
    fn header(&self) -> [u8; HEADER_BYTES] {
        let mut h = Header([0; HEADER_BYTES]);
        h.i32(0, HEADER_BYTES as i32);
        let dims = self.dims.map(|d| d as i16);
        for (i, d) in [3, dims[0], dims[1], dims[2], 1, 1, 1, 1]
            .into_iter()
            .enumerate()
        {
            h.i16(40 + 2 * i, d);
        }
        h.i16(70, 16); // datatype: float32
        h.i16(72, 32); // bitpix
        let m = self.to_world.matrix3 * MM_PER_M;
        let t = self.to_world.translation * MM_PER_M;
        let sizes = [m.x_axis.length(), m.y_axis.length(), m.z_axis.length()];
        let (qfac, quaternion) = qform_of(m, sizes);
        h.f32(76, qfac as f32);
        for (i, s) in sizes.into_iter().enumerate() {
            h.f32(80 + 4 * i, s as f32);
        }
        for i in 4..8 {
            h.f32(76 + 4 * i, 1.0);
        }
        h.f32(108, FIRST_DATA_BYTE as f32); // vox_offset
        h.0[123] = 2; // xyzt_units: millimetres
        h.0[148..153].copy_from_slice(b"haphe");
        h.i16(254, 1); // sform_code: scanner
        if let Some(q) = quaternion {
            h.i16(252, 1); // qform_code: scanner
            for (i, v) in [q.x, q.y, q.z, t.x, t.y, t.z].into_iter().enumerate() {
                h.f32(256 + 4 * i, v as f32);
            }
        }
        for row in 0..3 {
            let values = [m.x_axis[row], m.y_axis[row], m.z_axis[row], t[row]];
            for (j, v) in values.into_iter().enumerate() {
                h.f32(280 + 16 * row + 4 * j, v as f32);
            }
        }
        h.0[344..348].copy_from_slice(b"n+1\0");
        h.0
    }
}

/// `qfac` and the quaternion (scalar part at least 0) of the matrix `m` whose columns have
/// lengths `sizes`, when `m` is a rotation (times `qfac` on the third column) times the
/// sizes; `None` for a quaternion when it is not.
fn qform_of(m: DMat3, sizes: [f64; 3]) -> (f64, Option<DQuat>) {
    let qfac = if m.determinant() < 0.0 { -1.0 } else { 1.0 };
    let r = DMat3::from_cols(
        m.x_axis / sizes[0],
        m.y_axis / sizes[1],
        m.z_axis / sizes[2] * qfac,
    );
    let off = (r.transpose() * r - DMat3::IDENTITY).to_cols_array();
    if !off.iter().all(|e| e.abs() <= ROTATION_TOLERANCE) {
        return (qfac, None);
    }
    let q = DQuat::from_mat3(&r).normalize();
    (qfac, Some(if q.w < 0.0 { -q } else { q }))
}

/// `bytes` as a gzip stream.
fn gzip(bytes: &[u8]) -> Vec<u8> {
    let mut encoder = GzEncoder::new(Vec::new(), flate2::Compression::default());
    // Writing to a Vec cannot fail.
    let _ = encoder.write_all(bytes);
    encoder.finish().unwrap_or_default()
}

/// Header bytes being written, little-endian.
struct Header([u8; HEADER_BYTES]);

impl Header {
    fn i16(&mut self, at: usize, v: i16) {
        self.0[at..at + 2].copy_from_slice(&v.to_le_bytes());
    }

    fn i32(&mut self, at: usize, v: i32) {
        self.0[at..at + 4].copy_from_slice(&v.to_le_bytes());
    }

    fn f32(&mut self, at: usize, v: f32) {
        self.0[at..at + 4].copy_from_slice(&v.to_le_bytes());
    }
}
