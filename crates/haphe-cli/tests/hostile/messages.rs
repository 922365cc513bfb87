//! Messages: the file and the place, each cause once, no Debug output; standard output
//! named when it cannot be written.

use std::process::{Command, Stdio};

use crate::common::{assert_error, haphe, scratch, simulate_sphere, stderr};

/// `/dev/full` as standard output: the message says it is standard output. Linux has
/// `/dev/full`; elsewhere the test is ignored, saying so, instead of passing unrun.
#[test]
#[cfg_attr(not(target_os = "linux"), ignore = "needs /dev/full (Linux)")]
fn a_full_standard_output_is_named() {
    let full = std::fs::File::create("/dev/full").expect("/dev/full opens for writing on Linux");
    let dir = scratch("full-stdout");
    let plot = dir.join("demo.png");
    let o = Command::new(env!("CARGO_BIN_EXE_haphe"))
        .args(["demo", "--fast", "--plot", plot.to_str().unwrap()])
        .stdout(Stdio::from(full))
        .stderr(Stdio::piped())
        .output()
        .expect("runs");
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("cannot write to standard output: No space left on device"),
        "{err}"
    );
}

/// A cause is shown once (it used to read `Is a directory (os error 21): Is a directory
/// (os error 21)`), and a missing plot folder gives a sentence, not a Debug dump.
#[test]
fn causes_are_shown_once_without_debug_output() {
    let dir = scratch("messages");
    let o = haphe(&["validate", dir.to_str().unwrap()]);
    let out = crate::common::stdout(&o);
    assert_eq!(out.matches("directory").count(), 1, "{out}");
    let o = haphe(&[
        "demo",
        "--fast",
        "--plot",
        dir.join("no/p.png").to_str().unwrap(),
    ]);
    assert_error(&o, &["p.png", "does not exist"]);
    let missing = dir.join("missing.obj");
    let o = haphe(&[
        "build",
        missing.to_str().unwrap(),
        "-o",
        dir.join("m.map").to_str().unwrap(),
    ]);
    assert_error(&o, &["missing.obj", "No such file or directory"]);
    assert_eq!(
        stderr(&o).matches("No such file").count(),
        1,
        "{}",
        stderr(&o)
    );
}

/// A negative `--seconds` is read as a value and refused with the limit.
#[test]
fn negative_seconds_are_a_value_with_a_clear_refusal() {
    let o = simulate_sphere(&["--seconds", "-1"]);
    assert_error(
        &o,
        &["--seconds must be a positive number of at most 3600, not -1"],
    );
    let o = simulate_sphere(&["--seconds", "1e9"]);
    assert_error(&o, &["--seconds", "3600", "1000000000"]);
}

/// A map file is recognised by its header in every command, whatever its name.
#[test]
fn a_map_named_like_a_mesh_is_recognised_everywhere() {
    let dir = scratch("map-as-ply");
    let mesh = crate::common::write(&dir, "t.obj", crate::common::tetrahedron(0.0));
    let map = dir.join("t.ply");
    let o = haphe(&["build", &mesh, "-o", map.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let o = haphe(&["validate", map.to_str().unwrap()]);
    let out = crate::common::stdout(&o);
    assert!(
        out.contains("t.ply: a map file written by `haphe build`, not a mesh file"),
        "{out}"
    );
    let o = haphe(&[
        "build",
        map.to_str().unwrap(),
        "-o",
        dir.join("again.map").to_str().unwrap(),
    ]);
    assert_error(&o, &["t.ply: a map file written by `haphe build`"]);
    let points = crate::common::write(&dir, "p.csv", "0.01,0.01,0.01\n");
    let o = haphe(&["query", map.to_str().unwrap(), "--inside", &points]);
    assert_eq!(crate::common::stdout(&o), "inside\n", "{}", stderr(&o));
}
