//! Models in the wrong unit: a 100 mm cube written in millimetres and read as metres is
//! warned about, with the flag to add, by every command that reads a mesh (`validate`,
//! `simulate`, `run`, a scene file's object), and the summary flags the hand speeds and
//! depths no hand on a device reaches.

mod common;

use common::{haphe, s, scratch, stderr, stdout, write};
use haphe::mesh::{LARGEST_LIKELY_SPAN_M, Units};

/// A closed cube of side `side` (in the file's numbers) with a corner at the origin,
/// triangles counter-clockwise seen from outside.
fn cube_obj(side: f64) -> String {
    let mut text = String::new();
    for i in 0..8 {
        let c = |bit: u32| if i & (1 << bit) != 0 { side } else { 0.0 };
        text += &format!("v {} {} {}\n", c(0), c(1), c(2));
    }
    // Corners numbered 1 + x + 2y + 4z; each face as two triangles, outward.
    for [a, b, c, d] in [
        [1, 3, 4, 2], // z = 0, seen from below
        [5, 6, 8, 7], // z = side
        [1, 2, 6, 5], // y = 0
        [3, 7, 8, 4], // y = side
        [1, 5, 7, 3], // x = 0
        [2, 4, 8, 6], // x = side
    ] {
        text += &format!("f {a} {b} {c}\nf {a} {c} {d}\n");
    }
    text
}

const ADVICE: &str = "looks like millimetres: add `--units mm`";

#[test]
fn a_millimetre_cube_read_as_metres_is_warned_in_validate_and_simulate() {
    let dir = scratch("units-mm");
    let cube = write(&dir, "cube_mm.obj", cube_obj(100.0));
    // The cube is valid: the warning is about its size alone.
    let validate = haphe(&["validate", &cube]);
    assert_eq!(validate.status.code(), Some(0), "{}", stdout(&validate));
    // 100 file units read as metres span 100 m, above the largest likely span.
    const { assert!(100.0 > LARGEST_LIKELY_SPAN_M) };
    let short = ["--seconds", "0.2"];
    for (what, out) in [
        ("validate", validate),
        (
            "simulate",
            haphe(&[&["simulate", "--mesh", &cube][..], &short[..]].concat()),
        ),
        (
            "run",
            haphe(
                &[
                    &["run", "--device", "hand", "--mesh", &cube][..],
                    &short[..],
                ]
                .concat(),
            ),
        ),
    ] {
        let err = stderr(&out);
        assert!(out.status.success(), "{what}: {err}");
        assert!(err.contains("warning"), "{what}: {err}");
        assert!(err.contains("spans 100 m"), "{what}: {err}");
        assert!(err.contains(ADVICE), "{what}: {err}");
    }
    // Read in millimetres, it is a 0.1 m cube: no warning.
    for args in [
        vec!["validate", &cube, "--units", "mm"],
        vec![
            "simulate",
            "--mesh",
            &cube,
            "--units",
            "mm",
            "--seconds",
            "0.2",
        ],
    ] {
        let out = haphe(&args);
        assert!(out.status.success(), "{args:?}: {}", stderr(&out));
        assert!(
            !stderr(&out).contains("warning"),
            "{args:?}: {}",
            stderr(&out)
        );
    }
    // A scene file's object is told the field to add.
    let scene = write(
        &dir,
        "s.toml",
        format!("[[object]]\nmesh = {:?}\n", s(&dir.join("cube_mm.obj"))),
    );
    let out = haphe(&["simulate", "--scene", &scene, "--seconds", "0.2"]);
    assert!(
        stderr(&out).contains("looks like millimetres: add `units = \"mm\"` to its object"),
        "{}",
        stderr(&out)
    );
}

#[test]
fn the_repositorys_millimetre_cube_is_warned_about_too() {
    // meshes/models/20mm-xyz-cube.stl is a 20 mm calibration cube written in millimetres.
    let cube = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../meshes/models/20mm-xyz-cube.stl"
    );
    let out = haphe(&["validate", cube]);
    assert!(stderr(&out).contains(ADVICE), "{}", stderr(&out));
    assert!(stderr(&out).contains("spans 20 m"), "{}", stderr(&out));
    let out = haphe(&["validate", cube, "--units", &Units::Millimetres.to_string()]);
    assert!(!stderr(&out).contains("warning"), "{}", stderr(&out));
}

/// The first number of the summary line starting with `label`, and the line.
fn figure<'a>(text: &'a str, label: &str) -> (f64, &'a str) {
    let line = text
        .lines()
        .find(|l| l.trim_start().starts_with(label))
        .unwrap_or_else(|| panic!("no line {label:?} in:\n{text}"));
    let value = line.trim_start()[label.len()..]
        .split_whitespace()
        .find_map(|w| w.parse::<f64>().ok())
        .unwrap_or_else(|| panic!("no number in {line:?}"));
    (value, line)
}

#[test]
fn impossible_hand_speeds_and_depths_are_flagged() {
    use haphe_cli_limits::{MAX_HAND_SPEED_M_S, MAX_PENETRATION_MM};
    let dir = scratch("units-flags");
    let cube = write(&dir, "cube_mm.obj", cube_obj(100.0));
    let mut flagged = 0;
    for units in ["m", "mm"] {
        let out = haphe(&[
            "simulate",
            "--mesh",
            &cube,
            "--units",
            units,
            "--path",
            "press",
            "--seconds",
            "1",
        ]);
        let text = stdout(&out);
        assert!(out.status.success(), "{text}{}", stderr(&out));
        for (label, limit) in [
            ("fastest hand", MAX_HAND_SPEED_M_S),
            ("max penetration", MAX_PENETRATION_MM),
        ] {
            let (value, line) = figure(&text, label);
            assert_eq!(
                line.contains("impossible for a hand"),
                value > limit,
                "{line}"
            );
            flagged += usize::from(value > limit);
            if units == "mm" {
                assert!(value <= limit, "a 0.1 m cube pressed by the hand: {line}");
            }
        }
    }
    assert!(flagged > 0, "the 100 m cube's press is beyond any hand");
}

/// The bounds the summary holds runs to, as its documentation states them.
mod haphe_cli_limits {
    /// m/s at the device.
    pub const MAX_HAND_SPEED_M_S: f64 = 5.0;
    /// mm at the device.
    pub const MAX_PENETRATION_MM: f64 = 100.0;
}
