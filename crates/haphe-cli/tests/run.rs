//! `haphe run` and `haphe devices` against the Force Dimension stand-in library (built
//! here from crates/haphe-devices/tests/standin/dhd.c): the device is found, opened,
//! mapped onto the scene and run; Ctrl-C stops a run that has no end; a missing library
//! is an error that says what to install and which variable to set.

mod support;

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

use support::Standin;

fn haphe() -> Command {
    Command::new(env!("CARGO_BIN_EXE_haphe"))
}

fn standin() -> PathBuf {
    support::standin(Standin::Dhd)
}

/// `haphe run --device dhd` on a small sphere, with the Force Dimension library at `lib`.
fn run_dhd(lib: impl AsRef<std::ffi::OsStr>) -> Command {
    let mut command = haphe();
    command.env("HAPHE_DHD_LIBRARY", lib).args([
        "run",
        "--device",
        "dhd",
        "--shape",
        "sphere",
        "--triangles",
        "500",
    ]);
    command
}

#[test]
fn run_and_devices_with_the_stand_in() {
    let lib = standin();
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("run-cli");
    std::fs::create_dir_all(&dir).expect("a directory");
    let csv = dir.join("run.csv");
    let out = run_dhd(&lib)
        // No overrun budget here: the test machine is shared (the budget has its own
        // tests in haphe's tests/servo_clocked.rs).
        .args([
            "--seconds",
            "0.3",
            "--normal-priority",
            "--overrun-budget",
            "1000000",
        ])
        .arg("--out")
        .arg(&csv)
        .output()
        .expect("runs");
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stdout}\n{stderr}");
    assert!(
        stdout.contains("device: Force Dimension stand-in omega.3"),
        "{stdout}"
    );
    assert!(
        stdout.contains("workspace 100 × 100 × 100 mm; maximum force 3.30 N"),
        "{stdout}"
    );
    assert!(stdout.contains("mapping: "), "{stdout}");
    // Deadlines may be skipped on a loaded machine: every tick run is in the trace.
    let ticks: usize = stdout
        .lines()
        .find_map(|l| l.trim().strip_prefix("ticks"))
        .and_then(|l| l.split_whitespace().next())
        .and_then(|n| n.parse().ok())
        .expect("the ticks line");
    assert!(ticks > 100 && ticks <= 300, "{stdout}");
    let rows = std::fs::read_to_string(&csv)
        .expect("the trace")
        .lines()
        .count();
    assert_eq!(rows, ticks + 1);

    let out = haphe()
        .env("HAPHE_DHD_LIBRARY", &lib)
        .arg("devices")
        .output()
        .expect("runs");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success());
    assert!(stdout.contains("dhd (Force Dimension): ready"), "{stdout}");
    assert!(stdout.contains("1 device(s) connected"), "{stdout}");
    assert!(
        stdout.contains("stand-in omega.3: workspace x -50..50"),
        "{stdout}"
    );
}

#[test]
fn ctrl_c_stops_a_run_without_end() {
    let lib = standin();
    let mut child = run_dhd(&lib)
        .args(["--normal-priority", "--overrun-budget", "1000000"])
        .stdout(Stdio::piped())
        .spawn()
        .expect("runs");
    let mut lines = BufReader::new(child.stdout.take().expect("stdout")).lines();
    for line in lines.by_ref() {
        if line.expect("a line").contains("running until Ctrl-C") {
            break;
        }
    }
    std::thread::sleep(std::time::Duration::from_millis(300));
    let status = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .expect("kill");
    assert!(status.success());
    let rest: Vec<String> = lines.map_while(Result::ok).collect();
    let status = child.wait().expect("ends");
    assert!(status.success(), "{rest:?}");
    assert!(rest.iter().any(|l| l.contains("(stopped)")), "{rest:?}");
}

#[test]
fn a_missing_library_says_what_to_do() {
    let out = run_dhd("/nonexistent/libdhd.so").output().expect("runs");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2));
    for needed in ["libdhd.so", "HAPHE_DHD_LIBRARY", "Force Dimension SDK"] {
        assert!(stderr.contains(needed), "{needed}: {stderr}");
    }
    let out = haphe()
        .args(["run", "--device", "phantom", "--shape", "sphere"])
        .output()
        .expect("runs");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr.contains("unknown device \"phantom\""), "{stderr}");
}

/// `haphe run` checks the material of a lone object as `haphe simulate` does (they share
/// the arguments), before any device is opened.
#[test]
fn a_bad_material_is_refused_as_in_simulate() {
    for command in [&["run", "--device", "hand"][..], &["simulate"][..]] {
        let out = haphe()
            .args(command)
            .args(["--shape", "sphere", "--triangles", "100", "--stiffness=-5"])
            .output()
            .expect("runs");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{command:?}: {stderr}");
        assert!(stderr.contains("--stiffness"), "{command:?}: {stderr}");
    }
}
