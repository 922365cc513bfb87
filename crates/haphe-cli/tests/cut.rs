//! `haphe simulate` on volumes: a NIfTI-1 block pressed and cut by a tool, the cut volume
//! saved and read back; a mesh voxelised with `--voxel`; flags refused with clear errors.

mod common;

use common::{haphe, scratch, stderr, stdout, write};
use haphe::glam::{DAffine3, DVec3};
use haphe::volume::Volume;

/// A block of 24³ voxels of 1 mm, material (1) inside a margin of 3, air (0) around it.
fn block() -> Volume {
    let n = 24;
    let inside = |i: usize| (3..n - 3).contains(&i);
    let mut values = Vec::with_capacity(n * n * n);
    for k in 0..n {
        for j in 0..n {
            for i in 0..n {
                values.push(f32::from(u8::from(inside(i) && inside(j) && inside(k))));
            }
        }
    }
    Volume::new(
        [n; 3],
        values,
        DAffine3::from_scale(DVec3::splat(1e-3)),
        0.5,
    )
    .expect("a volume")
}

#[test]
fn a_volume_is_pressed_cut_and_saved() {
    let dir = scratch("cut");
    let file = write(
        &dir,
        "block.nii.gz",
        block().to_nifti_gz().expect("written"),
    );
    let saved = dir.join("cut.nii").display().to_string();
    let args = [
        "simulate",
        "--volume",
        &file,
        "--iso",
        "0.5",
        "--path",
        "press",
        "--seconds",
        "1.5",
        "--tool-radius",
        "0.002",
        "--cut",
        "--save-volume",
        &saved,
    ];
    let out = haphe(&args);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}{}",
        stdout(&out),
        stderr(&out)
    );
    let text = stdout(&out);
    for part in [
        "on the volume",
        "cutting: a tool of radius 2.00 mm removes the material it presses on with 0.5 N or more",
        "\ncutting:\n",
        "versions ",
        "volume written to",
    ] {
        assert!(text.contains(part), "{part:?} missing from:\n{text}");
    }
    assert!(
        stderr(&out).contains("a volume of 24 × 24 × 24 voxels"),
        "{}",
        stderr(&out)
    );
    // The saved volume: the same grid and affine, material removed and none added.
    let bytes = std::fs::read(&saved).expect("the saved volume");
    let (after, _) = Volume::read_nifti(&saved, &bytes, 0.5).expect("it reads");
    let before = block();
    assert_eq!(after.dims(), before.dims());
    assert!(
        after
            .to_world()
            .matrix3
            .abs_diff_eq(before.to_world().matrix3, 1e-12)
    );
    let removed = before
        .values()
        .iter()
        .zip(after.values())
        .filter(|(b, a)| **b >= 0.5 && **a < 0.5)
        .count();
    let added = before
        .values()
        .iter()
        .zip(after.values())
        .filter(|(b, a)| **b < 0.5 && **a >= 0.5)
        .count();
    assert!(removed > 0, "the press cut into the block");
    assert_eq!(added, 0);
    // The run repeats, byte for byte, on the simulated clock.
    let again = haphe(&args);
    assert_eq!(
        stdout(&again)
            .lines()
            .filter(|l| l.contains("removed"))
            .collect::<Vec<_>>(),
        text.lines()
            .filter(|l| l.contains("removed"))
            .collect::<Vec<_>>()
    );
}

#[test]
fn a_mesh_is_voxelised_and_without_cut_rests_on_the_surface() {
    let mesh = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../meshes/models/20mm-xyz-cube.stl"
    );
    let out = haphe(&[
        "simulate",
        "--mesh",
        mesh,
        "--units",
        "mm",
        "--voxel",
        "0.001",
        "--path",
        "press",
        "--seconds",
        "1",
        "--tool-radius",
        "0.002",
    ]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}{}",
        stdout(&out),
        stderr(&out)
    );
    let text = stdout(&out);
    assert!(text.contains("on the volume"), "{text}");
    assert!(
        !text.contains("\ncutting:"),
        "no cutting without --cut: {text}"
    );
}

/// Two layers, each felt and cut at its rate: the run says what they are and cuts.
#[test]
fn layers_are_felt_and_cut() {
    let dir = scratch("cut-layers");
    let mut volume = block();
    // Enamel (2) over the upper half of the block.
    let [n, _, _] = volume.dims();
    for (at, v) in volume.values_mut().iter_mut().enumerate() {
        if *v > 0.5 && at / (n * n) >= n / 2 {
            *v = 2.0;
        }
    }
    let file = write(&dir, "tooth.nii", volume.to_nifti().expect("written"));
    let out = haphe(&[
        "simulate",
        "--volume",
        &file,
        "--iso",
        "0.5",
        "--layer",
        "dentin:1:0.02:300",
        "--layer",
        "enamel:2:0.004:900:0.4",
        "--path",
        "press",
        "--seconds",
        "1",
        "--tool-radius",
        "0.002",
        "--cut",
    ]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}{}",
        stdout(&out),
        stderr(&out)
    );
    let err = stderr(&out);
    for part in [
        "dentin from 1: 300 N/m, friction 0/0, cut at 20 mm/s",
        "enamel from 2: 900 N/m, friction 0.4/0.4, cut at 4 mm/s",
    ] {
        assert!(err.contains(part), "{part:?} missing from:\n{err}");
    }
    assert!(stdout(&out).contains("\ncutting:\n"), "{}", stdout(&out));
}

#[test]
fn bad_cutting_flags_are_refused() {
    let dir = scratch("cut-refusals");
    let file = write(&dir, "block.nii", block().to_nifti().expect("written"));
    let mesh = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../meshes/models/20mm-xyz-cube.stl"
    );
    for (args, expected) in [
        (
            vec!["simulate", "--shape", "sphere", "--cut"],
            "--cut needs a volume",
        ),
        (
            vec![
                "simulate",
                "--shape",
                "sphere",
                "--save-volume",
                "/tmp/x.nii",
            ],
            "--save-volume needs a volume",
        ),
        (
            vec![
                "simulate", "--volume", &file, "--cut", "--deform", "breathe",
            ],
            "--cut and --deform cannot be used together",
        ),
        (
            vec!["simulate", "--volume", &file, "--cut", "--cut-force", "-1"],
            "--cut-force",
        ),
        (
            vec!["simulate", "--volume", &file, "--cut", "--cut-refresh", "0"],
            "--cut-refresh",
        ),
        (
            vec![
                "simulate", "--mesh", mesh, "--units", "mm", "--voxel", "-0.001",
            ],
            "voxel size must be",
        ),
        (
            vec!["simulate", "--volume", "/nonexistent.nii"],
            "/nonexistent.nii",
        ),
        (
            vec![
                "simulate",
                "--shape",
                "sphere",
                "--layer",
                "bone:1:0.01:900",
            ],
            "--layer needs a volume",
        ),
        (
            vec!["simulate", "--volume", &file, "--layer", "bone:1:0.01"],
            "--layer: `bone:1:0.01`: expected `NAME:FROM:RATE:STIFFNESS",
        ),
        (
            vec!["simulate", "--volume", &file, "--layer", "bone:1:0:900"],
            "--layer: `bone:1:0:900`: cut rate",
        ),
        (
            vec!["simulate", "--volume", &file, "--layer", "bone:x:0.01:900"],
            "`x` is not a number",
        ),
    ] {
        let out = haphe(&args);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {}", stderr(&out));
        assert!(
            stderr(&out).contains(expected),
            "{args:?}: {}",
            stderr(&out)
        );
    }
}
