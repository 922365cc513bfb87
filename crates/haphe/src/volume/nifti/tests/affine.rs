//! The affine: sform over qform over nibabel's fall-back, and the spatial unit.

use glam::{DAffine3, DMat3, DVec3};

use super::{Kind, Spec, field_of, read_err, read_ok};

/// The affine read from `spec`'s 2 × 3 × 4 int16 file.
fn affine_of(spec: &Spec) -> (DAffine3, Vec<String>, &'static str) {
    let (v, info) = read_ok(&spec.file(&spec.int16(0..24)));
    (v.to_world(), info.notes, info.affine_from)
}

/// `a` and `b` agree within `tol` in every entry (metres).
fn assert_affine(a: DAffine3, b: DAffine3, tol: f64) {
    let (x, y) = (a.to_cols_array(), b.to_cols_array());
    let worst = x
        .iter()
        .zip(&y)
        .map(|(p, q)| (p - q).abs())
        .fold(0.0, f64::max);
    assert!(worst <= tol, "{a:?}\n vs {b:?}: {worst}");
}

/// The affine of a 3 × 4 matrix in millimetres given by rows, in metres.
fn mm_rows(rows: [[f64; 4]; 3]) -> DAffine3 {
    let col = |j: usize| DVec3::new(rows[0][j], rows[1][j], rows[2][j]) * 1e-3;
    DAffine3::from_mat3_translation(DMat3::from_cols(col(0), col(1), col(2)), col(3))
}

const SROW: [[f32; 4]; 3] = [
    [0.0, -2.0, 0.0, 90.0],
    [1.5, 0.0, 0.0, -126.0],
    [0.0, 0.0, 3.0, -72.0],
];

/// A quaternion of 90° about z, voxels of 2 × 3 × 4 mm, offsets (10, 20, 30) mm.
fn qform_spec() -> Spec {
    let half = std::f32::consts::FRAC_1_SQRT_2;
    Spec {
        qform_code: 1,
        pixdim: [1.0, 2.0, 3.0, 4.0, 1.0, 1.0, 1.0, 1.0],
        quatern: [0.0, 0.0, half, 10.0, 20.0, 30.0],
        ..Spec::default()
    }
}

#[test]
fn sform_wins_when_its_code_is_set() {
    let spec = Spec {
        sform_code: 2,
        srow: SROW,
        ..qform_spec()
    };
    let (affine, notes, from) = affine_of(&spec);
    let expected = mm_rows(SROW.map(|r| r.map(f64::from)));
    assert_affine(affine, expected, 1e-15);
    assert_eq!(from, "sform");
    assert!(notes.is_empty(), "{notes:?}");
}

#[test]
fn qform_by_hand_when_only_it_is_set() {
    // R(90° about z) = [[0, -1, 0], [1, 0, 0], [0, 0, 1]]; times diag(2, 3, 4).
    let expected = mm_rows([
        [0.0, -3.0, 0.0, 10.0],
        [2.0, 0.0, 0.0, 20.0],
        [0.0, 0.0, 4.0, 30.0],
    ]);
    // An sform with code 0 (or an invalid code) is ignored.
    for sform_code in [0, -1, 5] {
        let spec = Spec {
            sform_code,
            srow: SROW,
            ..qform_spec()
        };
        let (affine, _, from) = affine_of(&spec);
        assert_affine(affine, expected, 1e-9);
        assert_eq!(from, "qform");
    }
    // qfac -1 flips the third axis; a qfac other than ±1 is taken as 1, with a note.
    let flipped = Spec {
        pixdim: [-1.0, 2.0, 3.0, 4.0, 1.0, 1.0, 1.0, 1.0],
        ..qform_spec()
    };
    let mut m = expected;
    m.matrix3.z_axis = -m.matrix3.z_axis;
    assert_affine(affine_of(&flipped).0, m, 1e-9);
    let odd = Spec {
        pixdim: [0.0, 2.0, 3.0, 4.0, 1.0, 1.0, 1.0, 1.0],
        ..qform_spec()
    };
    let (affine, notes, _) = affine_of(&odd);
    assert_affine(affine, expected, 1e-9);
    assert_eq!(notes, ["qfac (pixdim[0]) is 0: taken as 1"]);
}

#[test]
fn a_quaternion_longer_than_one_is_refused() {
    let spec = Spec {
        quatern: [0.8, 0.8, 0.0, 0.0, 0.0, 0.0],
        ..qform_spec()
    };
    let kind = read_err(&spec.file(&spec.int16(0..24)));
    assert_eq!(field_of(&kind), "quatern_b, quatern_c, quatern_d");
}

#[test]
fn pixdim_fall_back_is_nibabels_base_affine() {
    // nibabel's docstring of get_base_affine: shape (3, 5, 7), zooms (3, 2, 1) give
    // [[-3, 0, 0, 3], [0, 2, 0, -4], [0, 0, 1, -3]].
    let spec = Spec {
        dim: [3, 3, 5, 7, 1, 1, 1, 1],
        pixdim: [1.0, 3.0, 2.0, 1.0, 1.0, 1.0, 1.0, 1.0],
        ..Spec::default()
    };
    let (v, info) = read_ok(&spec.file(&spec.int16(0..105)));
    let expected = mm_rows([
        [-3.0, 0.0, 0.0, 3.0],
        [0.0, 2.0, 0.0, -4.0],
        [0.0, 0.0, 1.0, -3.0],
    ]);
    assert_affine(v.to_world(), expected, 1e-15);
    assert!(info.affine_from.starts_with("pixdim"));
    // Two dimensions: the third is padded with a size of 1 (pixdim[3] unused).
    let flat = Spec {
        dim: [2, 3, 5, 7, 1, 1, 1, 1],
        pixdim: [1.0, 3.0, 2.0, 9.0, 1.0, 1.0, 1.0, 1.0],
        ..Spec::default()
    };
    let (v, _) = read_ok(&flat.file(&flat.int16(0..15)));
    assert_eq!(v.dims(), [3, 5, 1]);
    let expected = mm_rows([
        [-3.0, 0.0, 0.0, 3.0],
        [0.0, 2.0, 0.0, -4.0],
        [0.0, 0.0, 1.0, 0.0],
    ]);
    assert_affine(v.to_world(), expected, 1e-15);
}

#[test]
fn zero_and_negative_voxel_sizes_are_fixed_as_nibabel_fixes_them() {
    let spec = Spec {
        pixdim: [1.0, 0.0, -2.0, 1.0, 1.0, 1.0, 1.0, 1.0],
        ..Spec::default()
    };
    let (affine, notes, _) = affine_of(&spec);
    assert_eq!(
        notes,
        ["pixdim[1] is 0: taken as 1", "pixdim[2] is -2: taken as 2"]
    );
    assert_eq!(affine.matrix3.y_axis, DVec3::new(0.0, 2e-3, 0.0));
}

#[test]
fn spatial_units_are_converted_to_metres() {
    let spec = |xyzt_units| Spec {
        xyzt_units,
        sform_code: 1,
        srow: SROW,
        ..Spec::default()
    };
    let rows = SROW.map(|r| r.map(f64::from));
    for (units, per_mm, note) in [
        (1, 1e3, false),
        (2, 1.0, false),
        (3, 1e-3, false),
        (0, 1.0, true),
    ] {
        // Time bits (seconds: 8) do not change the spatial unit.
        for units in [units, units | 8] {
            let (affine, notes, _) = affine_of(&spec(units));
            assert_affine(affine, mm_rows(rows.map(|r| r.map(|x| x * per_mm))), 1e-12);
            assert_eq!(notes.len(), usize::from(note), "{notes:?}");
        }
    }
    let (_, notes, _) = affine_of(&spec(0));
    assert_eq!(
        notes,
        ["spatial unit unknown (xyzt_units 0): taken as millimetres"]
    );
    let kind = read_err(&spec(5).file(&spec(5).int16(0..24)));
    assert!(
        matches!(
            kind,
            Kind::Header {
                field: "xyzt_units",
                ..
            }
        ),
        "{kind}"
    );
}
