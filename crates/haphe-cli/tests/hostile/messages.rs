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

/// A misspelt shape, unit or device gets the closest known name; a product name gets the
/// specification that drives it (a Phantom runs through OpenHaptics).
#[test]
fn unknown_names_are_answered_with_what_was_meant() {
    let o = haphe(&["simulate", "--shape", "spehre"]);
    assert_error(&o, &["unknown shape 'spehre'", "did you mean 'sphere'?"]);
    let o = simulate_sphere(&["--units", "milimetres"]);
    assert_error(
        &o,
        &["--units", "unknown unit 'milimetres'", "did you mean 'mm'?"],
    );
    for (given, meant) in [
        ("phantom", "openhaptics"),
        ("openhaptic", "openhaptics"),
        ("falcon", "dhd"),
        ("hnad", "hand"),
    ] {
        let o = haphe(&["run", "--device", given, "--shape", "sphere"]);
        assert_error(
            &o,
            &[
                &format!("unknown device \"{given}\""),
                &format!("did you mean '{meant}'?"),
            ],
        );
    }
    // Nothing close: no guess.
    let o = haphe(&["simulate", "--shape", "teapot"]);
    assert_error(&o, &["unknown shape 'teapot'"]);
    assert!(!stderr(&o).contains("did you mean"), "{}", stderr(&o));
}

/// A unit factor of zero or below is a value out of its domain, not an unknown name.
#[test]
fn a_unit_factor_must_be_positive() {
    for factor in ["0", "-0.001", "-1"] {
        let o = simulate_sphere(&["--units", factor]);
        assert_error(&o, &["--units", "must be positive", factor]);
        assert!(!stderr(&o).contains("unknown unit"), "{}", stderr(&o));
    }
}

/// Plots are PNG: another extension is refused before any work, naming the one written.
#[test]
fn a_plot_is_refused_an_extension_it_does_not_write() {
    let dir = scratch("plot-extension");
    for name in ["out.jpg", "out.svg", "out"] {
        let path = dir.join(name);
        let path = path.to_str().expect("UTF-8");
        for args in [
            vec!["simulate", "--shape", "sphere", "--plot", path],
            vec!["demo", "--fast", "--plot", path],
        ] {
            let o = haphe(&args);
            assert_error(&o, &["--plot", "PNG only", ".png"]);
        }
        assert!(!dir.join(name).exists(), "{name} was written");
    }
    let png = dir.join("OUT.PNG");
    let o = simulate_sphere(&["--seconds", "0.1", "--plot", png.to_str().expect("UTF-8")]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        std::fs::read(&png)
            .expect("written")
            .starts_with(b"\x89PNG")
    );
}

/// A stiffness above what the device renders stably at the servo rate is warned about,
/// naming the bound; at or below it, nothing is said. The bound is the simulated
/// device's rated stiffness scaled by the rate (the passivity rule of a sampled wall).
#[test]
fn a_stiffness_beyond_the_stable_bound_is_warned() {
    let spec = haphe::servo::simulated_spec();
    for rate in [1000.0, 2000.0] {
        let stable = spec.max_stiffness * rate / haphe::servo::STIFFNESS_RATED_AT_HZ;
        for (stiffness, warned) in [(stable, false), (stable * 1.5, true)] {
            let o = simulate_sphere(&[
                "--seconds",
                "0.1",
                "--rate",
                &rate.to_string(),
                "--stiffness",
                &stiffness.to_string(),
            ]);
            let err = stderr(&o);
            assert!(o.status.success(), "{err}");
            assert_eq!(
                err.contains("renders stably"),
                warned,
                "{stiffness} N/m at {rate} Hz: {err}"
            );
            if warned {
                assert!(err.contains(&format!("the {stable:.0} N/m")), "{err}");
            }
        }
    }
}
