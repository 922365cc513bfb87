//! `--deform` end to end: `haphe simulate` deforms the object while the hand touches it,
//! with a deformer thread in lockstep with the simulated clock (every kind reports its
//! refreshes and the versions the ticks used; the same run twice gives the same trace; a
//! breathing sphere is felt where it is at each version); `haphe run` refreshes on the
//! wall clock; `haphe verify --deform` passes on the in-tree models; bad values are
//! refused naming the flag.

mod common;

use common::{assert_error, haphe, ok, s, scratch};

/// A press on a small sphere (radius 0.1 m at the origin) for 0.8 s at 1 kHz, `args`
/// added.
fn press(args: &[&str]) -> Vec<String> {
    let mut all: Vec<String> = [
        "simulate",
        "--shape",
        "sphere",
        "--triangles",
        "320",
        "--path",
        "press",
        "--seconds",
        "0.8",
    ]
    .map(String::from)
    .to_vec();
    all.extend(args.iter().map(|a| a.to_string()));
    all
}

fn run(args: &[String]) -> String {
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    ok(&args)
}

/// The line of the summary that starts with `label` (after its indent).
fn line<'a>(text: &'a str, label: &str) -> &'a str {
    text.lines()
        .map(str::trim_start)
        .find(|l| l.starts_with(label))
        .unwrap_or_else(|| panic!("no line {label:?} in:\n{text}"))
}

#[test]
fn every_kind_deforms_the_sphere_in_lockstep_and_reports_it() {
    for kind in ["breathe", "dent", "breathe-dent", "twist"] {
        let text = run(&press(&["--deform", kind]));
        println!("{text}");
        assert!(
            text.contains(&format!(
                "deformation: {kind} of sphere (id 0, 320 triangles) at 100 Hz, each version made by a deformer thread following the simulated clock"
            )),
            "{text}"
        );
        assert!(line(&text, "kind").ends_with(&format!("{kind} at 100 Hz")));
        // 0.8 s at 100 Hz: a refresh at 0, 10, ..., 790 ms, each before its tick.
        assert_eq!(
            line(&text, "refreshes"),
            "refreshes         80 made, 80 sent to the servo through the scene's editor"
        );
        assert!(line(&text, "refresh time").contains("p50 "));
        assert!(
            line(&text, "versions").contains(
                "the ticks used versions 1 to 80, each in force for 10 ticks (checked on the servo's scene)"
            ),
            "{text}"
        );
        // The scene keeps the version before the current one for the proxy to ride from:
        // every version up to the one before it comes back (the first shape, 0, too).
        assert!(
            line(&text, "handed back").contains("79 version(s)"),
            "{text}"
        );
        assert!(!text.contains("never touched"), "{text}");
    }
    // Another rate: 40 refreshes a second are 25 ticks each.
    let text = run(&press(&["--deform", "twist", "--deform-rate", "40"]));
    assert!(
        line(&text, "refreshes").contains("32 made, 32 sent"),
        "{text}"
    );
    assert!(
        line(&text, "versions").contains("versions 1 to 32, each in force for 25 ticks"),
        "{text}"
    );
}

/// The scale of `Deformation::Breathe` at `t` seconds.
fn breathe(t: f64) -> f64 {
    1.0 + 0.15 * (std::f64::consts::TAU * 2.0 * t).sin()
}

#[test]
fn a_breathing_sphere_is_felt_where_each_version_has_it_and_runs_repeat() {
    let dir = scratch("deform-breathe");
    let (a, b) = (dir.join("a.csv"), dir.join("b.csv"));
    run(&press(&["--deform", "breathe", "--out", s(&a)]));
    run(&press(&["--deform", "breathe", "--out", s(&b)]));
    let trace = std::fs::read_to_string(&a).expect("the trace");
    assert_eq!(
        trace,
        std::fs::read_to_string(&b).expect("the second trace"),
        "the same run twice gave two traces"
    );
    // In contact, the proxy lies on the sphere of the version in force: refresh j (at
    // j / 100 s) from tick 10 j on. The 320-triangle sphere's faces lie between 0.98 and
    // 1 of its radius (0.1 m) from its centre; the proxy within its skin of them.
    let (mut contact, mut off_rest) = (0usize, 0usize);
    for row in trace.lines().skip(1) {
        let f: Vec<&str> = row.split(',').collect();
        if f[10] != "1" {
            continue;
        }
        let t: f64 = f[0].parse().expect("t");
        let p: Vec<f64> = (4..7).map(|i| f[i].parse().expect("proxy")).collect();
        let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        let tick = (t * 1000.0).round();
        let scale = breathe((tick / 10.0).floor() / 100.0);
        let ratio = r / (0.1 * scale);
        assert!(
            (0.975..1.001).contains(&ratio),
            "t {t}: the proxy {r} m from the centre, the sphere's radius {} m",
            0.1 * scale
        );
        contact += 1;
        off_rest += usize::from((r / 0.1 - 1.0).abs() > 0.03);
    }
    // Guards against a check that holds without a deformation: enough contact, and the
    // proxy away from the sphere at rest on many of those ticks.
    assert!(contact > 50, "{contact} ticks in contact");
    assert!(
        off_rest > 20,
        "{off_rest} of {contact} ticks off the rest sphere"
    );
}

#[test]
fn haphe_run_deforms_on_the_wall_clock() {
    let text = ok(&[
        "run",
        "--device",
        "hand",
        "--shape",
        "sphere",
        "--triangles",
        "320",
        "--seconds",
        "0.5",
        "--normal-priority",
        "--deform",
        "dent",
        "--deform-rate",
        "50",
    ]);
    println!("{text}");
    assert!(text.contains("at 50 Hz, each version made by a deformer thread on the wall clock"));
    // About 25 refreshes in 0.5 s; a loaded machine may skip a few (reported), never make
    // more than the time allows.
    let refreshes = line(&text, "refreshes");
    let made: u64 = refreshes
        .split_whitespace()
        .nth(1)
        .and_then(|w| w.parse().ok())
        .unwrap_or_else(|| panic!("{refreshes}"));
    assert!((5..=30).contains(&made), "{refreshes}");
    assert!(
        line(&text, "versions").contains("the ticks used versions up to"),
        "{text}"
    );
}

#[test]
fn verify_deform_passes_on_the_in_tree_models() {
    let models = concat!(env!("CARGO_MANIFEST_DIR"), "/../../meshes/models/");
    for (model, args) in [
        ("sphere.ply", vec!["--deform", "all"]),
        (
            "spot.obj",
            vec!["--deform", "breathe-dent", "--tool-radius", "0.002"],
        ),
    ] {
        let file = format!("{models}{model}");
        let mut all = vec!["verify", &file, "--samples", "0", "--ticks", "150"];
        all.extend(args);
        let out = haphe(&all);
        let text = common::stdout(&out);
        println!("{text}");
        assert_eq!(out.status.code(), Some(0), "{text}");
        assert!(text.trim_end().ends_with("PASSED"), "{text}");
        assert!(
            text.contains("deforming: the proxy against the brute-force proxy"),
            "{text}"
        );
        let rows: Vec<&str> = text
            .lines()
            .filter(|l| {
                ["| breathe ", "| dent ", "| twist ", "| breathe-dent "]
                    .iter()
                    .any(|k| l.starts_with(k))
            })
            .collect();
        assert_eq!(
            rows.len(),
            if model == "sphere.ply" { 3 } else { 1 },
            "{text}"
        );
        for row in rows {
            let cells: Vec<&str> = row.split('|').map(str::trim).collect();
            assert_eq!(cells[2], "150", "{row}");
            assert!(cells[3].parse::<u64>().expect("contact") > 0, "{row}");
            assert_eq!((cells[4], cells[6], cells[7]), ("0", "0", "0"), "{row}");
        }
    }
}

#[test]
fn bad_deformations_are_refused_naming_the_flag() {
    let sphere = ["--shape", "sphere", "--triangles", "100"];
    let mut commands = vec![
        [&["simulate", "--seconds", "0.1"][..], &sphere].concat(),
        [
            &["run", "--device", "hand", "--seconds", "0.1"][..],
            &sphere,
        ]
        .concat(),
    ];
    if cfg!(feature = "view") {
        commands.push([&["view", "--no-open", "--port", "0"][..], &sphere].concat());
    }
    for command in commands {
        for (flags, says) in [
            (
                &["--deform", "wobble"][..],
                "--deform: unknown deformation `wobble` (one of: breathe, dent, breathe-dent, twist)",
            ),
            (
                &["--deform", "dent", "--deform-rate", "0"],
                "--deform-rate must be a finite number from 0.1 to 1000 Hz, not 0",
            ),
            (&["--deform", "dent", "--deform-rate", "-5"], "not -5"),
            (&["--deform", "dent", "--deform-rate", "nan"], "not NaN"),
            (
                &["--deform", "dent", "--deform-rate", "1e9"],
                "not 1000000000",
            ),
            (
                &["--deform", "dent", "--deform-rate", "500", "--rate", "200"],
                "from 0.1 to 200 Hz (the servo rate, --rate 200), not 500",
            ),
            (&["--deform-rate", "50"], "--deform <KIND>"),
        ] {
            let mut args = command.clone();
            args.extend(flags);
            assert_error(&haphe(&args), &[says]);
        }
    }
    let sphere = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../meshes/models/sphere.ply"
    );
    assert_error(
        &haphe(&["verify", sphere, "--deform", "wobble"]),
        &["--deform", "unknown deformation `wobble`", "or all"],
    );
    assert_error(
        &haphe(&["verify", sphere, "--deform", "dent", "--ticks", "0"]),
        &["nothing to check: --deform runs --ticks ticks"],
    );
}
