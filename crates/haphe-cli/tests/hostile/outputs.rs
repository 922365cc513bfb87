//! Outputs: checked before the work, never one of the inputs, never left half-written.

use std::time::{Duration, Instant};

use crate::common::{
    assert_error, files_in, generate_sphere, haphe, scratch, simulate_sphere, write,
};

/// `haphe build self.stl -o self.stl` used to replace the mesh with the map.
#[test]
fn an_output_that_is_an_input_is_refused() {
    let dir = scratch("self");
    let mesh = dir.join("s.stl");
    let m = mesh.to_str().unwrap();
    generate_sphere(&mesh, 200);
    let before = std::fs::read(&mesh).unwrap();
    assert_error(
        &haphe(&["build", m, "-o", m]),
        &["cannot write", "s.stl", "one of the input files"],
    );
    // Another name for the same file (a hard link) is caught too.
    let link = dir.join("link.stl");
    std::fs::hard_link(&mesh, &link).unwrap();
    assert_error(
        &haphe(&["build", m, "-o", link.to_str().unwrap()]),
        &["link.stl", "one of the input files"],
    );
    let trace = write(&dir, "hip.csv", "t,x,y,z\n0,0,0,0.2\n0.01,0,0,0.19\n");
    assert_error(
        &simulate_sphere(&["--replay", &trace, "--out", &trace]),
        &["hip.csv", "one of the input files"],
    );
    assert_eq!(std::fs::read(&mesh).unwrap(), before);
    assert_eq!(files_in(&dir), ["hip.csv", "link.stl", "s.stl"]);
}

/// Output paths in a missing folder, on a directory or on a device are refused before
/// any work, naming the path (bench used to fail only after the whole run).
#[test]
fn bad_output_paths_are_refused_before_the_work() {
    let dir = scratch("bad-out");
    // `haphe bench` is in builds with the `bench` feature.
    if cfg!(feature = "bench") {
        let missing = dir.join("no/such/folder/out.json");
        let start = Instant::now();
        let o = haphe(&[
            "bench",
            "--sizes",
            "1000000",
            "--json",
            missing.to_str().unwrap(),
        ]);
        assert_error(&o, &["out.json", "does not exist"]);
        assert!(
            start.elapsed() < Duration::from_secs(20),
            "bench ran before refusing"
        );
    }
    let plot = dir.join("missing/p.png");
    let o = haphe(&[
        "simulate",
        "--shape",
        "sphere",
        "--plot",
        plot.to_str().unwrap(),
    ]);
    assert_error(&o, &["cannot write", "p.png", "does not exist"]);
    let o = haphe(&["generate", "sphere", "-o", dir.to_str().unwrap()]);
    assert_error(&o, &["it is a directory"]);
    let o = haphe(&["generate", "sphere", "-o", "/dev/null"]);
    assert_error(&o, &["/dev/null", "character device"]);
    assert!(files_in(&dir).is_empty(), "{:?}", files_in(&dir));
}

/// A command that fails after it started writing leaves the old file as it was and no
/// temporary file (the trace of a run whose device faults).
#[test]
fn a_failed_run_keeps_the_old_output() {
    let dir = scratch("failed-run");
    let out = write(&dir, "trace.csv", "the old trace\n");
    // A scripted run that cannot start: a maximum force out of range is refused first.
    let o = simulate_sphere(&["--out", &out, "--max-force", "-1"]);
    assert_error(&o, &["--max-force"]);
    assert_eq!(std::fs::read_to_string(&out).unwrap(), "the old trace\n");
    assert_eq!(files_in(&dir), ["trace.csv"]);
    // A complete run replaces it whole.
    let o = simulate_sphere(&["--seconds", "0.05", "--out", &out]);
    assert_eq!(o.status.code(), Some(0), "{}", crate::common::stderr(&o));
    let text = std::fs::read_to_string(&out).unwrap();
    assert!(
        text.starts_with("t,") && text.lines().count() == 51,
        "{}",
        text.lines().count()
    );
    assert_eq!(files_in(&dir), ["trace.csv"]);
}
