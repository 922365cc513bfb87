//! `haphe view --cut` end to end: a voxelised cube pressed by the mouse device (points sent
//! over the page's WebSocket, as the page sends its pointer's) is cut while a real headless
//! Chromium shows it; the page redraws the object from each new mesh it receives, with
//! other triangles than the first; Ctrl-C prints the cutting's summary and writes the
//! volume as cut. The cutting flags a replay cannot take are refused.
//!
//! Needs Chromium (`apt-get install chromium`; `.ci/run` installs it), as
//! crates/haphe-view/tests/browser.rs does.

#[path = "../../haphe-view/tests/support/cdp.rs"]
mod cdp;
mod common;
mod support;

use std::io::{BufRead, BufReader};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use cdp::Browser;
use common::{haphe, scratch, stderr};
use support::{Running, signal};

const CUBE: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../meshes/models/20mm-xyz-cube.stl"
);

#[test]
fn the_page_redraws_a_volume_as_it_is_cut() {
    let dir = scratch("view-cut");
    let saved = dir.join("cut.nii.gz");
    let mut child = Running(
        Command::new(env!("CARGO_BIN_EXE_haphe"))
            .args(["view", "--mesh", CUBE, "--units", "mm", "--voxel", "0.001"])
            .args(["--tool-radius", "0.002", "--cut", "--save-volume"])
            .arg(&saved)
            .args(["--no-open", "--port", "0"])
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::inherit())
            .spawn()
            .expect("haphe runs"),
    );
    let mut lines = BufReader::new(child.0.stdout.take().expect("stdout")).lines();
    let mut printed = String::new();
    let url = loop {
        let line = lines
            .next()
            .expect("haphe prints the address")
            .expect("utf-8");
        printed.push_str(&line);
        printed.push('\n');
        if let Some(rest) = line.strip_prefix("view: ") {
            break rest.split(' ').next().expect("the address").to_string();
        }
    };
    assert!(
        printed.contains("cutting: a tool of radius 2.00 mm removes the material it presses on with 0.5 N or more"),
        "{printed}"
    );

    let mut browser = Browser::start(1024, 700);
    browser.navigate(&url);
    browser.wait_for(
        "!!(window.haphe && window.haphe.ready && window.haphe.frames > 2 && window.haphe.connected)",
        Duration::from_secs(40),
        "the page to draw the live view",
    );
    let first = browser
        .eval("window.haphe.info.objects[0].triangles")
        .as_u64()
        .expect("the first mesh's triangles");
    // The device: a second connection of the page's own kind, whose points move the mouse
    // device from above the cube (its top at z = 10 mm) down to 4 mm, where it holds.
    browser.eval(
        "new Promise((done) => { const s = new WebSocket(`ws://${location.host}/ws`); \
         window.press = s; s.onopen = () => done(true); })",
    );
    for k in 0..=40 {
        let z = 0.016 - 0.012 * f64::from(k) / 40.0;
        browser.eval(&format!(
            "window.press.send(JSON.stringify({{ hip: [0, 0, {z}] }}))"
        ));
        std::thread::sleep(Duration::from_millis(25));
    }
    browser.wait_for(
        "!!(window.haphe.shapes[0] && window.haphe.shapes[0].triangles !== window.haphe.info.objects[0].triangles)",
        Duration::from_secs(60),
        "a new mesh with other triangles than the first",
    );
    // Read at once: the version received last and the geometry drawn.
    let seen = browser.eval(
        "JSON.stringify({ shape: window.haphe.shapes[0], drawn: window.haphe.drawnMesh(0) })",
    );
    let seen: serde_json::Value = serde_json::from_str(seen.as_str().expect("text")).expect("JSON");
    let (shape, drawn) = (&seen["shape"], &seen["drawn"]);
    browser.eval("window.press.close()");

    // Ctrl-C: the servo stops, then the cutting's summary and the volume written.
    signal(&child.0, "INT");
    let started = Instant::now();
    for line in lines {
        printed.push_str(&line.expect("utf-8"));
        printed.push('\n');
        assert!(started.elapsed() < Duration::from_secs(30), "no clean stop");
    }
    let code = child.0.wait().expect("exits");
    println!("{printed}");
    assert!(code.success(), "{printed}");
    let errors = std::mem::take(&mut browser.errors);
    assert!(errors.is_empty(), "console errors: {errors:#?}");

    let triangles = shape["triangles"].as_u64().expect("a count");
    assert!(
        shape["version"].as_u64().expect("a version") >= 1,
        "{shape}"
    );
    assert_ne!(triangles, first, "{shape}");
    // The geometry drawn is the mesh received.
    assert_eq!(
        (drawn["vertices"].as_u64(), drawn["triangles"].as_u64()),
        (shape["vertices"].as_u64(), Some(triangles)),
        "{seen}"
    );
    for part in [
        "\ncutting:\n",
        "  tool              radius 2.00 mm, cutting from 0.5 N",
        "sent to the servo through the scene's editor",
        "  surface now       ",
        "volume written to ",
    ] {
        assert!(printed.contains(part), "{part:?} missing from:\n{printed}");
    }
    let removed: u64 = printed
        .lines()
        .find_map(|l| l.trim().strip_prefix("removed"))
        .and_then(|rest| rest.split_whitespace().next()?.parse().ok())
        .expect("the removed voxels");
    assert!(removed > 0, "{printed}");
    let bytes = std::fs::read(&saved).expect("the volume written");
    let name = saved.display().to_string();
    let (volume, _) = haphe::volume::Volume::read_nifti(&name, &bytes, 0.0).expect("it reads");
    assert!(volume.dims().iter().all(|&d| d > 20), "{:?}", volume.dims());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn cutting_flags_a_replay_or_two_devices_cannot_take_are_refused() {
    let dir = scratch("view-cut-refusals");
    let trace = dir.join("run.csv").display().to_string();
    let saved = dir.join("out.nii").display().to_string();
    let voxelised = ["--mesh", CUBE, "--units", "mm", "--voxel", "0.002"];
    for (extra, expected) in [
        (
            vec!["--replay", &trace, "--cut"],
            "--cut cuts or saves the volume of a live view; a replay (--replay) shows its trace's objects as they were",
        ),
        (
            vec!["--replay", &trace, "--save-volume", &saved],
            "--save-volume cuts or saves the volume of a live view",
        ),
        (
            vec!["--cut", "--deform", "breathe"],
            "--cut and --deform cannot be used together",
        ),
        (
            vec!["--cut", "--device", "hand", "--device", "hand"],
            "--cut cuts with one device's tool; give one --device",
        ),
        (vec!["--cut", "--cut-force", "-1"], "--cut-force"),
        (vec!["--cut", "--cut-refresh", "0"], "--cut-refresh"),
    ] {
        let mut args = vec!["view"];
        args.extend_from_slice(&voxelised);
        args.extend_from_slice(&extra);
        args.push("--no-open");
        let out = haphe(&args);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {}", stderr(&out));
        assert!(
            stderr(&out).contains(expected),
            "{args:?}: {}",
            stderr(&out)
        );
    }
    // Without a volume, as `simulate` says.
    let out = haphe(&["view", "--shape", "sphere", "--cut", "--no-open"]);
    assert!(
        stderr(&out).contains("--cut needs a volume"),
        "{}",
        stderr(&out)
    );
    let _ = std::fs::remove_dir_all(&dir);
}
