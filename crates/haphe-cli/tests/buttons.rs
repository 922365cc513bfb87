//! Buttons and the clutch through the command: `--press` holds a button of the simulated
//! device, the trace records it (columns `buttons` and `clutch`), and with
//! `--clutch-button` the tool stays while it is held and then continues moved by minus the
//! hand's travel, as the summary says; the same with the Force Dimension stand-in library
//! holding its button (`haphe run --device dhd --clutch-button 0`).

mod common;
mod support;

use common::{assert_error, ok, s, scratch, simulate_sphere};

/// A trace's rows: time, tool (`hip_*`), buttons and clutch.
struct Row {
    t: f64,
    hip: [f64; 3],
    buttons: u32,
    clutch: bool,
}

fn rows(path: &std::path::Path) -> Vec<Row> {
    let text = std::fs::read_to_string(path).expect("the trace is written");
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().expect("a header").split(',').collect();
    let column = |name: &str| {
        header
            .iter()
            .position(|h| *h == name)
            .unwrap_or_else(|| panic!("no column {name} in {header:?}"))
    };
    let (buttons, clutch) = (column("buttons"), column("clutch"));
    lines
        .map(|l| {
            let f: Vec<&str> = l.split(',').collect();
            let num = |i: usize| f[i].parse::<f64>().expect("a number");
            Row {
                t: num(0),
                hip: [num(1), num(2), num(3)],
                buttons: f[buttons].parse().expect("a mask"),
                clutch: f[clutch] == "1",
            }
        })
        .collect()
}

fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>().sqrt()
}

/// Checks the first `rows` rows of the run `held`, whose clutch was held (button mask
/// `mask`) over `pressed`, against the run `free` without a clutch: before, the same
/// tool; held, the tool before the press; after, the free tool moved by minus the travel
/// while held, which is returned.
fn check_clutch(
    free: &[Row],
    held: &[Row],
    pressed: std::ops::Range<usize>,
    mask: u32,
    rows: usize,
) -> [f64; 3] {
    let before = free[pressed.start - 1].hip;
    let travel = [0, 1, 2].map(|k| free[pressed.end - 1].hip[k] - before[k]);
    for (k, (h, f)) in held.iter().zip(free).enumerate().take(rows) {
        let is_held = pressed.contains(&k);
        let buttons = if is_held { mask } else { 0 };
        assert_eq!((h.buttons, h.clutch), (buttons, is_held), "row {k}");
        let tool = if k < pressed.start {
            f.hip
        } else if is_held {
            before
        } else {
            [0, 1, 2].map(|i| f.hip[i] - travel[i])
        };
        assert!(distance(h.hip, tool) < 1e-12, "row {k}");
    }
    travel
}

/// The scripted device (no hand: the device point is the path, whatever the force) runs
/// the press twice, once without a press of the button and once holding the clutch
/// (button 2) from 0.5 s until 1.2 s: held, the tool stays at the point before the press;
/// after, it is the path moved by minus the path's travel while held.
#[test]
fn the_clutch_keeps_the_tool_and_moves_it_by_the_hands_travel() {
    let dir = scratch("clutch");
    let (free, held) = (dir.join("free.csv"), dir.join("held.csv"));
    let base = [
        "simulate",
        "--shape",
        "sphere",
        "--triangles",
        "500",
        "--path",
        "press",
        "--no-hand",
        "--seconds",
        "2",
    ];
    let run = |out: &std::path::Path, more: &[&str]| {
        let mut args = base.to_vec();
        args.extend_from_slice(&["--out", s(out)]);
        args.extend_from_slice(more);
        ok(&args)
    };
    run(&free, &[]);
    let text = run(&held, &["--clutch-button", "2", "--press", "2@0.5-1.2"]);
    let (free, held) = (rows(&free), rows(&held));
    assert_eq!(free.len(), held.len());
    let first = held.iter().position(|r| r.clutch).expect("held");
    let end = held.iter().rposition(|r| r.clutch).expect("held") + 1;
    assert!((held[first].t - 0.5).abs() < 1e-9 && (held[end].t - 1.2).abs() < 1e-9);
    assert!(free.iter().all(|r| r.buttons == 0 && !r.clutch));
    let travel = check_clutch(&free, &held, first..end, 4, held.len());
    let length = distance(travel, [0.0; 3]);
    // Guards the premise: the path moves while the clutch is held.
    assert!(length > 5e-3, "the path travels {length} m");
    let line = text
        .lines()
        .find(|l| l.trim_start().starts_with("clutch"))
        .unwrap_or_else(|| panic!("no clutch line in:\n{text}"));
    assert!(line.contains("button 2 held 1 time(s), 0.700 s"), "{line}");
    let moved: Vec<f64> = line
        .split_once("moved by (")
        .and_then(|(_, rest)| rest.split_once(')'))
        .map(|(numbers, _)| {
            numbers
                .split(',')
                .map(|x| x.trim().parse().expect("a number"))
                .collect()
        })
        .unwrap_or_else(|| panic!("no offset in {line}"));
    for k in 0..3 {
        // Minus the travel, in mm to one decimal.
        assert!((moved[k] + travel[k] * 1e3).abs() <= 0.05 + 1e-9, "{line}");
    }
}

#[test]
fn bad_presses_and_buttons_are_refused_naming_the_flag() {
    for bad in ["40@1-2", "0@2-1", "0@1", "x@1-2", "0@nan-2"] {
        let o = simulate_sphere(&["--press", bad]);
        assert_error(&o, &["--press", "N@FROM-UNTIL", bad]);
    }
    let o = simulate_sphere(&["--clutch-button", "32"]);
    assert_error(&o, &["--clutch-button", "32"]);
}

/// `haphe run --device dhd` on the stand-in, its samples a straight press at 1 kHz from
/// 8 cm above the origin down to it (the stand-in's units and frame), button 0 held over
/// `held` samples; the trace's rows.
fn run_standin(
    dir: &std::path::Path,
    name: &str,
    held: std::ops::Range<usize>,
    clutch: bool,
) -> Vec<Row> {
    let samples = 400;
    let mut text = String::new();
    for k in 0..=samples {
        let z = 0.08 * (1.0 - k as f64 / samples as f64);
        let buttons = u32::from(held.contains(&k));
        text.push_str(&format!(
            "0 0 {z} 0 0 {} {buttons}\n",
            -0.08 / (samples as f64 / 1000.0)
        ));
    }
    let path = dir.join(format!("{name}.txt"));
    std::fs::write(&path, text).expect("the samples are written");
    let csv = dir.join(format!("{name}.csv"));
    let mut command = std::process::Command::new(env!("CARGO_BIN_EXE_haphe"));
    command
        .env("HAPHE_DHD_LIBRARY", support::standin(support::Standin::Dhd))
        .env("HAPHE_STANDIN_PATH", &path)
        .args([
            "run",
            "--device",
            "dhd",
            "--shape",
            "sphere",
            "--triangles",
            "500",
        ])
        // No overrun budget here: the test machine is shared.
        .args([
            "--seconds",
            "0.3",
            "--normal-priority",
            "--overrun-budget",
            "1000000",
        ])
        .arg("--out")
        .arg(&csv);
    if clutch {
        command.args(["--clutch-button", "0"]);
    }
    let out = command.output().expect("runs");
    assert!(
        out.status.success(),
        "{}\n{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    rows(&csv)
}

/// Acceptance with a stand-in device through the command: the trace has the stand-in's
/// button, and with the clutch on it the tool stays while it is held and then continues
/// moved by minus the hand's travel (mapped into the world: the run without the clutch
/// gives the mapped device points, one sample a tick).
#[test]
fn the_clutch_of_a_force_dimension_stand_in() {
    let dir = scratch("clutch-dhd");
    let free = run_standin(&dir, "free", 100..200, false);
    let held = run_standin(&dir, "held", 100..200, true);
    assert!(
        free.len() >= 250 && held.len() >= 250,
        "{} {}",
        free.len(),
        held.len()
    );
    assert!(
        free.iter().all(|r| !r.clutch),
        "no clutch without --clutch-button"
    );
    let pressed: Vec<usize> = (0..free.len()).filter(|&k| free[k].buttons == 1).collect();
    assert_eq!(
        pressed.len(),
        100,
        "the stand-in's button reaches the trace"
    );
    let (start, end) = (pressed[0], pressed[99] + 1);
    assert_eq!(pressed, (start..end).collect::<Vec<_>>());
    let travel = check_clutch(&free, &held, start..end, 1, end + 50);
    // Guards the premise: 100 samples of the press, 2 cm down at the device.
    assert!(travel[2] < -5e-3, "{travel:?}");
}
