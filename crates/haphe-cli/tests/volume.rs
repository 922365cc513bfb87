//! `haphe validate` on volume files: a NIfTI-1 written by the library's writer, plain and
//! gzip, with and without `--iso`; malformed files refused naming the file.

mod common;

use common::{haphe, scratch, stdout, write};
use haphe::glam::{DAffine3, DMat3, DVec3};
use haphe::volume::Volume;

/// 4 × 3 × 2 voxels of 1 mm valued 0 to 23 (`i` fastest), the grid starting at x = 1 cm.
fn volume() -> Volume {
    let to_world = DAffine3::from_mat3_translation(
        DMat3::from_diagonal(DVec3::splat(1e-3)),
        DVec3::new(0.01, 0.0, 0.0),
    );
    Volume::new(
        [4, 3, 2],
        (0..24).map(|v| v as f32).collect(),
        to_world,
        0.0,
    )
    .expect("a valid volume")
}

#[test]
fn a_written_volume_validates_with_its_grid_affine_and_material() {
    let dir = scratch("volume");
    let v = volume();
    let plain = write(&dir, "grid.nii", v.to_nifti().expect("written"));
    let gz = write(&dir, "grid.nii.gz", v.to_nifti_gz().expect("written"));

    let out = haphe(&["validate", &plain, "--iso", "12"]);
    assert_eq!(out.status.code(), Some(0), "{}", stdout(&out));
    let text = stdout(&out);
    for part in [
        "(NIfTI-1, float32, little-endian; read in",
        "verdict: a volume with material at iso 12",
        "grid: 4 x 3 x 2 voxels (24)",
        "voxel size: 1.000000 x 1.000000 x 1.000000 mm",
        "affine (voxel indices to metres, from the sform):",
        "[  0.001000000  0.000000000  0.000000000  0.010000000 ]",
        "values: 0 .. 23",
        "iso: 12\n",
        "material (value >= iso): 12 of 24 voxels; voxels [0, 0, 1] .. [3, 2, 1]; \
         [0.010000, 0.000000, 0.001000] .. [0.013000, 0.002000, 0.001000] m",
    ] {
        assert!(text.contains(part), "{part:?} missing from:\n{text}");
    }

    // Without --iso: the midpoint of the values, stated.
    let text = stdout(&haphe(&["validate", &gz]));
    assert!(text.contains("float32, little-endian, gzip;"), "{text}");
    assert!(
        text.contains(
            "iso: 11.5 (the default: the midpoint of the finite values; set it with --iso)"
        ),
        "{text}"
    );
    assert!(
        text.contains("material (value >= iso): 12 of 24 voxels"),
        "{text}"
    );

    let out = haphe(&["validate", "--json", &gz, "--iso", "20"]);
    assert_eq!(out.status.code(), Some(0));
    let j: serde_json::Value = serde_json::from_str(stdout(&out).trim()).expect("one JSON object");
    assert_eq!(j["dims"], serde_json::json!([4, 3, 2]));
    assert_eq!(j["gzip"], true);
    assert_eq!(j["byte_order"], "little-endian");
    assert_eq!(j["datatype"], "float32");
    assert_eq!(j["iso_default"], false);
    assert_eq!(j["material_voxels"], 4);
    assert_eq!(j["material_voxels_min"], serde_json::json!([0, 2, 1]));
    assert_eq!(j["affine"][0][3], 0.01);

    // No value reaches the iso value: unusable.
    let out = haphe(&["validate", &plain, "--iso", "100"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stdout(&out).contains("verdict: unusable: no value reaches iso 100"));
}

#[test]
fn malformed_volume_files_exit_2_naming_the_file() {
    let dir = scratch("volume-bad");
    let junk = write(&dir, "junk.nii", vec![7u8; 400]);
    let mut nifti2 = volume().to_nifti().expect("written");
    nifti2[..4].copy_from_slice(&540i32.to_le_bytes());
    let nifti2 = write(&dir, "two.nii", nifti2);
    let mut short = volume().to_nifti().expect("written");
    short.truncate(short.len() - 10);
    let short = write(&dir, "short.nii", short);
    let missing = dir.join("missing.nii").display().to_string();
    for (file, words) in [
        (&junk, "not a NIfTI-1 file: sizeof_hdr is"),
        (&nifti2, "NIfTI-2 is not supported; convert to NIfTI-1"),
        (
            &short,
            "the file ends early: 438 bytes of the 448 its header announces",
        ),
        (&missing, "missing.nii"),
    ] {
        let out = haphe(&["validate", file]);
        assert_eq!(out.status.code(), Some(2), "{file}");
        let text = stdout(&out);
        assert!(
            text.contains(file.as_str()) && text.contains(words),
            "{words:?} missing from:\n{text}"
        );
        assert!(text.contains("verdict: unreadable"), "{text}");
    }
    let out = haphe(&["validate", "--json", &nifti2]);
    let j: serde_json::Value = serde_json::from_str(stdout(&out).trim()).expect("JSON");
    assert!(j["error"].as_str().expect("an error").contains("NIfTI-2"));
}
