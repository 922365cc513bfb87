//! `to_nifti` then `read_nifti`: the same volume.

use glam::{DAffine3, DMat3, DQuat, DVec3};

use super::{Kind, read_err, read_ok};
use crate::volume::{Volume, VolumeError};

/// A 3 × 4 × 5 volume with awkward values, placed by `to_world`.
fn volume(to_world: DAffine3) -> Volume {
    let mut values: Vec<f32> = (0..60).map(|i| (i as f32 - 29.5) * 0.37).collect();
    values[0] = -0.0;
    values[1] = f32::INFINITY;
    values[2] = f32::MIN_POSITIVE / 8.0;
    values[3] = f32::MAX;
    Volume::new([3, 4, 5], values, to_world, 0.25).expect("a valid volume")
}

/// `a` and `b` within `rel` of the largest entry.
fn assert_close(a: DAffine3, b: DAffine3, rel: f64) {
    let (x, y) = (a.to_cols_array(), b.to_cols_array());
    let scale = y.iter().map(|v| v.abs()).fold(0.0, f64::max);
    for (p, q) in x.iter().zip(&y) {
        assert!((p - q).abs() <= rel * scale, "{a:?}\n vs {b:?}");
    }
}

/// Rotated affines whose entries in millimetres are float32 numbers (0.5 mm voxels, a
/// quarter turn), a mirrored one, and a sheared one.
fn affines() -> Vec<DAffine3> {
    let quarter = DMat3::from_cols(DVec3::Y, -DVec3::X, DVec3::Z);
    vec![
        DAffine3::from_mat3_translation(
            DMat3::from_diagonal(DVec3::splat(5e-4)),
            DVec3::new(-0.01, 0.02, 0.125),
        ),
        DAffine3::from_mat3_translation(
            quarter * DMat3::from_diagonal(DVec3::new(5e-4, 2.5e-4, 1e-3)),
            DVec3::new(0.5, -0.25, 0.0),
        ),
        DAffine3::from_mat3_translation(
            DMat3::from_diagonal(DVec3::new(1e-3, 1e-3, -2e-3)),
            DVec3::ZERO,
        ),
        DAffine3::from_mat3_translation(
            DMat3::from_cols(
                DVec3::X * 1e-3,
                DVec3::new(5e-4, 1e-3, 0.0),
                DVec3::Z * 1e-3,
            ),
            DVec3::ZERO,
        ),
    ]
}

#[test]
fn read_of_to_nifti_is_the_volume() {
    for to_world in affines() {
        let v = volume(to_world);
        for gzip in [false, true] {
            let bytes = if gzip { v.to_nifti_gz() } else { v.to_nifti() }.expect("written");
            let (back, info) = read_ok(&bytes);
            assert_eq!(back.dims(), v.dims());
            let bits = |v: &Volume| v.values().iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&back), bits(&v));
            assert_close(back.to_world(), to_world, 1e-12);
            assert_eq!(info.gzip, gzip);
            assert_eq!(info.datatype, "float32");
            assert_eq!(info.affine_from, "sform");
            assert!(info.notes.is_empty(), "{:?}", info.notes);
        }
    }
}

#[test]
fn the_qform_holds_the_same_affine_when_it_is_a_rotation() {
    let turned = DAffine3::from_mat3_translation(
        DMat3::from_quat(DQuat::from_axis_angle(
            DVec3::new(1.0, 2.0, 3.0).normalize(),
            0.7,
        )) * DMat3::from_diagonal(DVec3::new(1e-3, 2e-3, -5e-4)),
        DVec3::new(0.1, 0.2, 0.3),
    );
    for to_world in affines().into_iter().chain([turned]) {
        let mut bytes = volume(to_world).to_nifti().expect("written");
        let qform_code = i16::from_le_bytes([bytes[252], bytes[253]]);
        let shear = to_world.matrix3.x_axis.dot(to_world.matrix3.y_axis).abs() > 1e-12;
        assert_eq!(qform_code, if shear { 0 } else { 1 }, "{to_world:?}");
        if shear {
            continue;
        }
        // Without the sform, the qform places the grid (float32 fields: seven digits).
        bytes[254..256].copy_from_slice(&0i16.to_le_bytes());
        let (back, info) = read_ok(&bytes);
        assert_eq!(info.affine_from, "qform");
        assert_close(back.to_world(), to_world, 1e-6);
    }
}

#[test]
fn a_side_beyond_32767_is_not_written() {
    let v = Volume::new([40_000, 1, 1], vec![0.0; 40_000], DAffine3::IDENTITY, 0.5).expect("valid");
    assert_eq!(v.to_nifti(), Err(VolumeError::NiftiDims([40_000, 1, 1])));
}

#[test]
fn a_written_file_cut_short_is_refused() {
    let bytes = volume(DAffine3::IDENTITY).to_nifti().expect("written");
    let kind = read_err(&bytes[..bytes.len() - 4]);
    assert!(matches!(kind, Kind::Truncated { .. }), "{kind}");
}
