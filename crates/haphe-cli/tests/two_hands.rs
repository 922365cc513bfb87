//! `haphe run` with several devices in one scene: two simulated hands (`--device hand
//! --device hand`), each with its own tool, render, tick by tick, what each renders alone
//! on the same scene (the trace's columns of each hand equal a run of that hand alone with
//! its tool); two Force Dimension
//! devices behind the stand-in each get their own mapping, summary block and trace
//! columns; a fault of one stops both with zero force and names it; bad sets of devices
//! are refused before any device is opened.

mod common;
mod support;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use common::{assert_error, scratch, stdout};

/// Seconds and rate of the hands' runs: on the wall clock, so a slow tick on a shared
/// machine skips a deadline; the comparisons stop at the first one skipped. 4 ms a tick
/// leaves room for a machine busy building and testing.
const SECONDS: &str = "2";
const RATE_HZ: f64 = 250.0;

/// The real-time flags of every run here: normal priority and no overrun budget (the test
/// machine is shared).
const SHARED_MACHINE: [&str; 3] = ["--normal-priority", "--overrun-budget", "1000000"];

/// The scene of every run here: a small sphere (radius 0.1 m) at the origin.
const SPHERE: [&str; 4] = ["--shape", "sphere", "--triangles", "500"];

fn haphe() -> Command {
    Command::new(env!("CARGO_BIN_EXE_haphe"))
}

/// `haphe run` of `devices` on a small sphere for [`SECONDS`], writing `out`.
fn run(devices: &[&str], extra: &[&str], out: &Path) -> Output {
    let mut command = haphe();
    command.arg("run");
    for d in devices {
        command.args(["--device", d]);
    }
    command
        .args(SPHERE)
        .args(["--seconds", SECONDS])
        .args(["--rate", &RATE_HZ.to_string()])
        .args(SHARED_MACHINE)
        .args(extra)
        .arg("--out")
        .arg(out);
    let output = command.output().expect("runs");
    assert!(
        output.status.success(),
        "{}\n{}",
        stdout(&output),
        String::from_utf8_lossy(&output.stderr)
    );
    output
}

/// A trace: its header's columns and its rows' fields.
fn read(path: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let text = std::fs::read_to_string(path).expect("the trace");
    let mut lines = text.lines();
    let header = lines.next().expect("a header");
    let rows = lines
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect();
    (header.split(',').map(str::to_string).collect(), rows)
}

/// The rows of a trace before its first skipped deadline (a gap in `t`).
fn ticked(rows: &[Vec<String>]) -> usize {
    rows.iter()
        .enumerate()
        .take_while(|(k, r)| {
            let t: f64 = r[0].parse().expect("a time");
            (t - *k as f64 / RATE_HZ).abs() < 1e-9
        })
        .count()
}

/// Each hand of a two-hand run equals the run of that hand alone, column by column, at
/// every tick both runs ticked; `None` when too few deadlines were ticked in a row to
/// compare (the machine was too busy).
fn compare_hands(dir: &Path) -> Option<usize> {
    let both = dir.join("both.csv");
    // The first hand holds a tool of 5 mm radius, the second is a point.
    let tools = ["--tool-radius", "0.005", "--tool-radius", "0"];
    let printed = stdout(&run(&["hand", "hand"], &tools, &both));
    for block in [
        "  tool: a sphere of radius 5.000 mm",
        "  device 1 (hand):",
        "  device 2 (hand):",
    ] {
        assert!(printed.contains(block), "{block:?} missing:\n{printed}");
    }
    let (header, rows) = read(&both);
    let mut compared = usize::MAX;
    for hand in 1..=2 {
        let alone = dir.join(format!("hand{hand}.csv"));
        run(
            &[&format!("hand:{hand}")],
            &tools[2 * hand - 2..2 * hand],
            &alone,
        );
        let (columns, single) = read(&alone);
        let n = ticked(&rows).min(ticked(&single));
        if n < 100 {
            return None;
        }
        compared = compared.min(n);
        for (c, name) in columns.iter().enumerate().skip(1) {
            let mine = format!("d{hand}_{name}");
            let at = header.iter().position(|h| *h == mine).expect(&mine);
            for k in 0..n {
                assert_eq!(rows[k][at], single[k][c], "hand {hand}, tick {k}, {name}");
            }
        }
        // Guard, counted on the whole run of the hand alone: its path touches the sphere.
        let c = columns
            .iter()
            .position(|h| h == "contact")
            .expect("a contact column");
        let contact = single.iter().filter(|r| r[c] == "1").count();
        assert!(contact > 100, "hand {hand}: {contact} contact ticks");
    }
    Some(compared)
}

#[test]
fn two_simulated_hands_each_render_as_alone() {
    let dir = scratch("two-hands");
    // A run that skipped deadlines early leaves too little to compare: made again.
    let compared = (0..5).find_map(|_| compare_hands(&dir));
    let compared = compared.expect("five tries, each skipping deadlines within 100 ticks");
    println!("compared {compared} ticks of each hand");
}

/// Writes a stand-in path file: the device comes down from 2 cm above the sphere's top
/// at `x` into it, and stays (in the device frame, which `scale` maps onto the world).
fn path_file(dir: &Path, name: &str, x: f64, scale: f64) -> PathBuf {
    let mut text = String::new();
    for k in 0..1000 {
        // In the world: from 2 cm above the top (0.1 m) to 1 cm into the sphere.
        let z = (0.12 - 0.03 * (k as f64 / 300.0).min(1.0)) / scale;
        text.push_str(&format!("{x} 0 {z} 0 0 0\n"));
    }
    let path = dir.join(name);
    std::fs::write(&path, text).expect("written");
    path
}

/// The stand-in's report of a device: forces written, whether force output was still on
/// at close, the largest force.
fn report(path: &Path) -> (u64, bool, f64) {
    let text = std::fs::read_to_string(path).expect("a report");
    let f: Vec<&str> = text.split_whitespace().collect();
    (
        f[0].parse().expect("a count"),
        f[4] == "1",
        f[5].parse().expect("a force"),
    )
}

/// Two Force Dimension devices: each with its own `--scale` (the first flag for the
/// first device), its summary block and its trace columns; `fail` makes device 2 fail
/// from that read.
fn two_dhd(dir: &Path, fail: Option<u32>) -> (Output, [PathBuf; 2], PathBuf) {
    let csv = dir.join("dhd.csv");
    let forces = [dir.join("forces0.txt"), dir.join("forces1.txt")];
    let mut command = haphe();
    command
        .env("HAPHE_DHD_LIBRARY", support::standin(support::Standin::Dhd))
        .env("HAPHE_STANDIN_DEVICES", "2")
        .env("HAPHE_STANDIN_PATH", path_file(dir, "p0.txt", 0.0, 1.0))
        .env("HAPHE_STANDIN_PATH_1", path_file(dir, "p1.txt", 0.0, 2.0))
        .env("HAPHE_STANDIN_FORCES", &forces[0])
        .env("HAPHE_STANDIN_FORCES_1", &forces[1]);
    if let Some(k) = fail {
        command.env("HAPHE_STANDIN_FAIL_FROM_1", k.to_string());
    }
    let out = command
        .args(["run", "--device", "dhd:0", "--device", "dhd:1"])
        .args([
            "--scale", "1", "--scale", "2", "--centre", "0,0,0", "--centre", "0,0,0",
        ])
        .args(SPHERE)
        .args(["--seconds", "0.5"])
        .args(SHARED_MACHINE)
        .arg("--out")
        .arg(&csv)
        .output()
        .expect("runs");
    (out, forces, csv)
}

#[test]
fn two_force_dimension_devices_have_their_own_mapping_summary_and_columns() {
    let dir = scratch("two-dhd");
    let (out, forces, csv) = two_dhd(&dir, None);
    let printed = stdout(&out);
    assert!(out.status.success(), "{printed}\n{}", common::stderr(&out));
    for needed in [
        "haphe run: device dhd:0, dhd:1 on",
        "device 1 (dhd:0): Force Dimension stand-in omega.3",
        "device 2 (dhd:1): Force Dimension stand-in sigma.7",
        "  mapping: 1.000 world m per device m",
        "  mapping: 2.000 world m per device m",
        "  device 1 (dhd:0):",
        "  device 2 (dhd:1):",
    ] {
        assert!(printed.contains(needed), "{needed:?} missing:\n{printed}");
    }
    let (header, rows) = read(&csv);
    let at = |name: &str| header.iter().position(|h| h == name).expect(name);
    let (z1, z2) = (at("d1_hip_z"), at("d2_hip_z"));
    let (f1, f2) = (at("d1_force_z"), at("d2_force_z"));
    assert_eq!(header.len(), 1 + 2 * 17, "{header:?}");
    // Both devices come down to 1 cm below the top of the sphere, each through its own
    // mapping (the second's path is half as long in the device, scaled by 2), and each
    // is pushed up.
    let last = &rows[rows.len() - 1];
    for (z, f) in [(z1, f1), (z2, f2)] {
        let hip_z: f64 = last[z].parse().expect("a number");
        let force_z: f64 = last[f].parse().expect("a number");
        assert!((hip_z - 0.09).abs() < 1e-9, "{hip_z}");
        assert!(force_z > 1.0, "{force_z}");
    }
    for (i, f) in forces.iter().enumerate() {
        let (written, enabled, largest) = report(f);
        // Zero at open, one a tick, then zeros at the end.
        assert!(written as usize > rows.len(), "device {i}: {written}");
        assert!(!enabled && largest > 1.0, "device {i}");
    }
}

#[test]
fn a_fault_of_one_device_stops_both_and_names_it() {
    let dir = scratch("two-dhd-fault");
    let (out, forces, _) = two_dhd(&dir, Some(400));
    assert_error(
        &out,
        &[
            "device 2 (dhd:1) faulted: device error code 5",
            "communication error between the host and the haptic device",
            "zero force was written to every device",
        ],
    );
    for (i, f) in forces.iter().enumerate() {
        let text = std::fs::read_to_string(f).expect("a report");
        let fields: Vec<&str> = text.split_whitespace().collect();
        // The last force written to each device is zero, though both were pressing.
        assert_eq!(&fields[1..4], &["0", "0", "0"], "device {i}: {text}");
        let largest: f64 = fields[5].parse().expect("a force");
        assert!(largest > 1.0, "device {i} pressed before: {text}");
    }
}

#[test]
fn bad_sets_of_devices_are_refused_before_any_opens() {
    let dir = scratch("two-bad");
    let forces = dir.join("forces.txt");
    let cases: [(&[&str], &[&str]); 6] = [
        (
            &["--device", "dhd:0", "--device", "dhd"],
            &["device 2 (dhd) is device 1 (dhd:0) again: each device may be given once"],
        ),
        (
            &["--device", "dhd:0", "--device", "dhd:3"],
            &["device 2 (dhd:3)", "no Force Dimension device at index 3"],
        ),
        (
            &["--device", "dhd:0", "--device", "dhd:1", "--scale", "2"],
            &[
                "--scale is given 1 time(s) for 2 device(s)",
                "none for device 2 (dhd:1)",
            ],
        ),
        (
            &[
                "--device", "dhd:0", "--device", "dhd:1", "--centre", "0,0,0", "--centre", "0,0,1",
                "--centre", "1,1,1",
            ],
            &[
                "--centre is given 3 time(s) for 2 device(s)",
                "1 more than there are devices",
            ],
        ),
        (
            &["--device", "hand", "--device", "hand", "--plot", "x.png"],
            &["--plot draws one device's run"],
        ),
        (
            &[
                "--device",
                "hand",
                "--device",
                "hand",
                "--tool-radius",
                "0.01",
            ],
            &[
                "--tool-radius is given 1 time(s) for 2 device(s)",
                "none for device 2 (hand)",
            ],
        ),
    ];
    for (args, needed) in cases {
        let _ = std::fs::remove_file(&forces);
        let out = haphe()
            .env("HAPHE_DHD_LIBRARY", support::standin(support::Standin::Dhd))
            .env("HAPHE_STANDIN_DEVICES", "2")
            .env("HAPHE_STANDIN_FORCES", &forces)
            .args([
                "run",
                "--shape",
                "sphere",
                "--triangles",
                "500",
                "--seconds",
                "0.2",
            ])
            .args(args)
            .output()
            .expect("runs");
        assert_error(&out, needed);
        // The first device was never opened, or opened and closed with no force.
        if let Ok(text) = std::fs::read_to_string(&forces) {
            let largest: f64 = text
                .split_whitespace()
                .nth(5)
                .expect("a field")
                .parse()
                .expect("a force");
            assert_eq!(largest, 0.0, "{args:?}: {text}");
        }
    }
}
