//! The `haphe` binary end to end: exit codes, JSON fields, error messages (the demo and
//! `simulate` are in `simulate.rs`).

mod common;

use std::path::PathBuf;

use common::{haphe, scratch, stdout, write};

/// The built-in shapes, by their command-line names.
const SHAPES: [&str; 6] = [
    "sphere",
    "torus",
    "box",
    "thin-plate",
    "concave-corner",
    "blob",
];

const TETRAHEDRON: &str =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
const OPEN_TETRAHEDRON: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\n";

#[test]
fn validate_json_has_the_documented_fields_and_exit_codes() {
    let dir = scratch("json");
    let solid = write(&dir, "tet.obj", TETRAHEDRON);
    let open = write(&dir, "open.obj", OPEN_TETRAHEDRON);

    let out = haphe(&["validate", "--json", &solid]);
    assert_eq!(out.status.code(), Some(0), "a closed solid exits 0");
    let v: serde_json::Value = serde_json::from_str(stdout(&out).trim()).expect("one JSON object");
    assert_eq!(v["triangles"], 4);
    assert_eq!(v["vertices"], 4);
    assert_eq!(v["closed"], true);
    assert_eq!(v["boundary_edges"], 0);
    assert_eq!(v["nonmanifold_edges"], 0);
    assert_eq!(v["nonmanifold_vertices"], 0);
    assert_eq!(v["orientation_conflicts"], 0);
    assert_eq!(v["degenerate_triangles"], 0);
    assert_eq!(v["components"], 1);
    assert_eq!(v["usable_as"], "solid");
    assert!((v["volume"].as_f64().expect("a number") - 1.0 / 6.0).abs() < 1e-15);

    let out = haphe(&["validate", "--json", &open]);
    assert_eq!(out.status.code(), Some(1), "an open surface exits 1");
    let v: serde_json::Value = serde_json::from_str(stdout(&out).trim()).expect("JSON");
    assert_eq!(v["closed"], false);
    assert_eq!(v["boundary_edges"], 3);
    assert_eq!(v["volume"], serde_json::Value::Null);

    // Several files: one JSON line each, and the worst decides the exit code.
    let out = haphe(&["validate", "--json", &solid, &open]);
    assert_eq!(out.status.code(), Some(1));
    assert_eq!(stdout(&out).lines().count(), 2);
}

#[test]
fn unreadable_files_exit_2_with_the_file_and_the_place() {
    let dir = scratch("bad");
    let bad = write(&dir, "bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n");
    let solid = write(&dir, "tet.obj", TETRAHEDRON);
    let out = haphe(&["validate", &solid, &bad]);
    assert_eq!(out.status.code(), Some(2));
    let text = stdout(&out);
    assert!(
        text.contains(&format!("{bad}: line 4: vertex index 7 is out of range")),
        "{text}"
    );
    let missing = dir.join("missing.stl").display().to_string();
    let out = haphe(&["validate", "--json", &missing]);
    assert_eq!(out.status.code(), Some(2));
    let v: serde_json::Value = serde_json::from_str(stdout(&out).trim()).expect("JSON");
    assert!(
        v["error"]
            .as_str()
            .expect("an error")
            .contains("missing.stl")
    );
}

#[test]
fn units_scale_to_metres() {
    let dir = scratch("units");
    let solid = write(&dir, "tet.obj", TETRAHEDRON);
    let out = haphe(&["validate", "--json", "--units", "mm", &solid]);
    let v: serde_json::Value = serde_json::from_str(stdout(&out).trim()).expect("JSON");
    assert_eq!(v["bounds_max"][0], 0.001);
    let out = haphe(&["validate", "--units", "furlongs", &solid]);
    assert_eq!(
        out.status.code(),
        Some(2),
        "an unknown unit is a usage error"
    );
}

#[test]
fn generated_meshes_validate_as_solids() {
    let dir = scratch("generate");
    for shape in SHAPES {
        let path = dir.join(format!("{shape}.stl")).display().to_string();
        let out = haphe(&["generate", shape, "--triangles", "2000", "-o", &path]);
        assert!(
            out.status.success(),
            "{shape}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let out = haphe(&["validate", "--json", &path]);
        assert_eq!(out.status.code(), Some(0), "{shape}: {}", stdout(&out));
        let v: serde_json::Value = serde_json::from_str(stdout(&out).trim()).expect("JSON");
        let expected_genus = if shape == "torus" { 1 } else { 0 };
        assert_eq!(v["genus"], expected_genus, "{shape}");
    }
}

#[test]
fn shuffled_faces_are_the_same_solid_in_another_order() {
    let dir = scratch("shuffle");
    let (plain, shuffled) = (dir.join("plain.stl"), dir.join("shuffled.stl"));
    for (path, extra) in [(&plain, None), (&shuffled, Some("3"))] {
        let path = path.display().to_string();
        let mut args = vec!["generate", "blob", "--triangles", "2000", "-o", &path];
        args.extend(
            extra
                .map(|seed| ["--shuffle-faces", seed])
                .into_iter()
                .flatten(),
        );
        assert!(haphe(&args).status.success());
    }
    let (a, b) = (
        std::fs::read(&plain).expect("read"),
        std::fs::read(&shuffled).expect("read"),
    );
    // Binary STL: an 84-byte header, then 50 bytes per face.
    assert_eq!(a.len(), b.len());
    let faces = |bytes: &[u8]| {
        bytes[84..]
            .chunks(50)
            .map(<[u8]>::to_vec)
            .collect::<Vec<_>>()
    };
    let (mut fa, mut fb) = (faces(&a), faces(&b));
    assert_ne!(fa, fb, "the order changed");
    fa.sort();
    fb.sort();
    assert_eq!(fa, fb, "the same faces");
    let out = haphe(&["validate", "--json", &shuffled.display().to_string()]);
    assert_eq!(out.status.code(), Some(0), "{}", stdout(&out));
}

#[test]
fn every_odd_file_gets_a_verdict_not_a_crash() {
    // The repository's own copy of the odd files (meshes/README.md).
    let dir = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../../meshes/odd"));
    for entry in std::fs::read_dir(&dir).expect("odd folder") {
        let path = entry.expect("entry").path();
        let out = haphe(&["validate", "--json", &path.display().to_string()]);
        let code = out.status.code();
        assert!(matches!(code, Some(0..=2)), "{}: {code:?}", path.display());
        let v: serde_json::Value = serde_json::from_str(stdout(&out).trim()).expect("JSON");
        if code == Some(2) && v.get("error").is_some() {
            let name = path.file_name().expect("name").to_string_lossy();
            assert!(v["error"].as_str().expect("text").contains(name.as_ref()));
        }
    }
}

/// A cube of side `2·h` centred on `c`, as OBJ lines (vertices numbered from `first`),
/// faces counter-clockwise seen from outside.
fn obj_cube(c: [f64; 3], h: f64, first: usize) -> String {
    let mut text = String::new();
    for k in 0..8 {
        let s = |bit: usize| if k >> bit & 1 == 1 { h } else { -h };
        text += &format!("v {} {} {}\n", c[0] + s(0), c[1] + s(1), c[2] + s(2));
    }
    for [a, b, cc, d] in [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ] {
        let v = |i: usize| i + first;
        text += &format!(
            "f {} {} {}\nf {} {} {}\n",
            v(a),
            v(b),
            v(cc),
            v(a),
            v(cc),
            v(d)
        );
    }
    text
}

/// `haphe query --inside` decides by the non-zero rule: where two closed parts of one mesh
/// overlap the point is inside (crossing parity would say outside), also next to the faces
/// of one part that lie inside the other.
#[test]
fn query_inside_says_inside_where_parts_overlap() {
    let dir = scratch("overlap");
    let obj = obj_cube([0.0, 0.0, 0.0], 0.05, 1) + &obj_cube([0.06, 0.03, 0.02], 0.05, 9);
    let mesh = write(&dir, "boxes.obj", &obj);
    let points = write(
        &dir,
        "points.csv",
        "x,y,z\n0.03,0.015,0.01\n0.0101,0.0,0.0\n0.0099,0.0,0.0\n0.03,0.015,-0.0299\n\
         -0.03,-0.03,-0.03\n0.1,0.07,0.06\n0.2,0.0,0.0\n0.03,-0.04,0.06\n",
    );
    let out = haphe(&["query", &mesh, "--inside", &points]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let lines: Vec<String> = stdout(&out).lines().map(str::to_owned).collect();
    assert_eq!(
        lines,
        [
            "inside", "inside", "inside", "inside", "inside", "inside", "outside", "outside"
        ],
        "{}",
        stdout(&out)
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// A command this build left out names the feature that brings it and the line that builds
/// it in, whatever arguments it is given (`--help` included).
#[test]
fn commands_left_out_name_their_feature() {
    let mut left_out: Vec<(&[&str], &str)> = Vec::new();
    if cfg!(not(feature = "view")) {
        left_out.push((&["view", "--shape", "sphere"], "view"));
        left_out.push((&["view", "--help"], "view"));
        left_out.push((&["demo", "--view"], "view"));
    }
    if cfg!(not(feature = "bench")) {
        left_out.push((&["bench", "--quick"], "bench"));
    }
    for (args, feature) in left_out {
        let out = haphe(args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        for needed in [
            format!("cargo feature `{feature}`"),
            format!("--features {feature}"),
            "cargo install --locked --path crates/haphe-cli".to_owned(),
        ] {
            assert!(err.contains(&needed), "{args:?}: {needed:?} missing: {err}");
        }
    }
    // haphe verify runs with or without parry; without, it says why its columns are empty.
    let dir = scratch("verify-peer");
    let mesh = write(&dir, "t.obj", TETRAHEDRON);
    let out = haphe(&[
        "verify",
        &mesh,
        "--samples",
        "50",
        "--ticks",
        "0",
        "--strikes",
        "0",
    ]);
    let text = stdout(&out);
    assert_eq!(out.status.code(), Some(0), "{text}");
    assert_eq!(
        text.contains("parry3d-f64 is not in this build: cargo feature `bench`"),
        cfg!(not(feature = "bench")),
        "{text}"
    );
    assert_eq!(
        text.contains("parry disagreements: -"),
        cfg!(not(feature = "bench")),
        "{text}"
    );
}

/// `haphe verify --samples 0 --strikes N` runs the deep strikes alone on a closed model,
/// with the ticks by speed class, and names a map file's source; an open model has
/// nothing to strike and says so.
#[test]
fn verify_runs_deep_strikes_alone() {
    let dir = scratch("verify-strikes");
    let mesh = write(&dir, "t.obj", TETRAHEDRON);
    let out = haphe(&["verify", &mesh, "--samples", "0", "--strikes", "20"]);
    let text = stdout(&out);
    assert_eq!(out.status.code(), Some(0), "{text}");
    for line in [
        "| deep | 0.5–1 |",
        "| deep | 4–10 |",
        "| deep | all |",
        "| shallow | all |",
    ] {
        assert!(text.contains(line), "{line}: {text}");
    }
    assert!(text.contains("PASSED"), "{text}");
    // The count of deep strikes is printed, with its minimum (half the strikes run), and
    // the count is what passed: at least half of the 20 went deep.
    let line = text
        .lines()
        .find(|l| l.starts_with("deep strikes: "))
        .unwrap_or_else(|| panic!("no count of deep strikes: {text}"));
    let numbers: Vec<usize> = line
        .split(|c: char| !c.is_ascii_digit())
        .filter_map(|w| w.parse().ok())
        .collect();
    let [deep, run, required, out_of_contact] = numbers[..] else {
        panic!("{line}");
    };
    assert!(run > 0 && run <= 20, "{line}");
    assert_eq!(required, run.div_ceil(2), "{line}");
    assert!(deep >= required && deep <= run, "{line}");
    assert_eq!(out_of_contact, 0, "{line}");
    // The same numbers in the JSON report.
    let out = haphe(&[
        "verify",
        &mesh,
        "--samples",
        "0",
        "--strikes",
        "20",
        "--json",
    ]);
    let report: serde_json::Value = serde_json::from_str(&stdout(&out)).expect("JSON");
    let strikes = &report["strikes"];
    assert_eq!(strikes["deep"]["strikes"], deep, "{strikes}");
    assert_eq!(strikes["min_deep_strikes"], required, "{strikes}");
    // A map file says which mesh it was built from.
    let map = dir.join("t.hmap").display().to_string();
    assert!(haphe(&["build", &mesh, "-o", &map]).status.success());
    let out = haphe(&["verify", &map, "--samples", "0", "--strikes", "5"]);
    let text = stdout(&out);
    assert_eq!(out.status.code(), Some(0), "{text}");
    assert!(text.contains("a map of t.obj, "), "{text}");
    let open = write(&dir, "open.obj", OPEN_TETRAHEDRON);
    let out = haphe(&["verify", &open, "--samples", "0", "--strikes", "20"]);
    assert_eq!(out.status.code(), Some(2), "{}", stdout(&out));
    let message = common::stderr(&out);
    assert!(
        message.contains("open.obj") && message.contains("closed model"),
        "{message}"
    );
}

/// `haphe verify --tool-radius R` runs the proxy checks and the strikes with a tool of
/// that radius (named in the tables and the JSON), and refuses a radius outside its
/// domain naming the flag, with exit code 2.
#[test]
fn verify_checks_a_tool_with_a_size() {
    let dir = scratch("verify-tool");
    let mesh = write(&dir, "t.obj", TETRAHEDRON);
    let args = [
        "verify",
        &mesh,
        "--samples",
        "0",
        "--ticks",
        "500",
        "--strikes",
        "10",
    ];
    let out = haphe(&[&args[..], &["--tool-radius", "0.002"]].concat());
    let text = stdout(&out);
    assert_eq!(out.status.code(), Some(0), "{text}");
    assert_eq!(
        text.matches("a tool of radius 2.00 mm").count(),
        2,
        "{text}"
    );
    assert!(text.contains("PASSED"), "{text}");
    let out = haphe(&[&args[..], &["--tool-radius", "0.002", "--json"]].concat());
    let report: serde_json::Value = serde_json::from_str(&stdout(&out)).expect("JSON");
    assert_eq!(report["proxy"]["tool_radius_m"], 0.002);
    assert_eq!(report["strikes"]["tool_radius_m"], 0.002);
    for bad in ["nan", "-0.001", "2"] {
        let out = haphe(&[&args[..], &[&format!("--tool-radius={bad}")]].concat());
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{bad}: {err}");
        assert!(err.contains("--tool-radius"), "{bad}: {err}");
    }
}
