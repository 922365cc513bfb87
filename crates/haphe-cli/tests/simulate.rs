//! `haphe demo` and `haphe simulate` end to end: the demo's figures are sane, traces have
//! the documented columns, replay is byte-for-byte repeatable, scene files work and their
//! errors say where, and a short real-time run reports its timing.

mod common;

use common::{haphe, ok, s, scratch};

/// The first number after `label` on the summary line that starts with it.
fn figure(text: &str, label: &str) -> f64 {
    let line = text
        .lines()
        .find(|l| l.trim_start().starts_with(label))
        .unwrap_or_else(|| panic!("no line {label:?} in:\n{text}"));
    line.trim_start()[label.len()..]
        .split_whitespace()
        .find_map(|w| w.trim_end_matches(['%', ',', '(']).parse::<f64>().ok())
        .unwrap_or_else(|| panic!("no number in {line:?}"))
}

const HEADER: &str = "t,hip_x,hip_y,hip_z,proxy_x,proxy_y,proxy_z,force_x,force_y,force_z,contact,object,triangle,status";

#[test]
fn demo_fast_prints_sane_figures_and_draws_the_plot() {
    let dir = scratch("demo");
    let png = dir.join("demo.png");
    let csv = dir.join("demo.csv");
    let text = ok(&["demo", "--fast", "--plot", s(&png), "--out", s(&csv)]);
    println!("{text}");
    assert_eq!(figure(&text, "ticks"), 3000.0);
    let contact = figure(&text, "contact");
    assert!(contact > 0.5 && contact < 3.0, "contact {contact} s");
    let depth = figure(&text, "max penetration");
    assert!(depth > 0.5 && depth < 20.0, "max penetration {depth} mm");
    let force = figure(&text, "max force");
    assert!(force > 0.3 && force <= 3.3 + 1e-9, "max force {force} N");
    assert!(figure(&text, "tick time") > 0.0);
    assert!(
        figure(&text, "achieved rate") > 1000.0,
        "faster than real time"
    );
    assert!(
        text.contains("object 0:") && text.contains("object 1:"),
        "both objects touched"
    );
    let bytes = std::fs::read(&png).expect("the plot is written");
    assert!(bytes.starts_with(b"\x89PNG") && bytes.len() > 10_000);
    let trace = std::fs::read_to_string(&csv).expect("the trace is written");
    assert!(trace.starts_with(HEADER));
    assert_eq!(trace.lines().count(), 3001);
    // The proxy never goes below the thin plate's top (z = 0.05 mm) while it touches the
    // plate away from its rim (the plate spans x 0.15–0.35 m; the rows within 1 cm of its
    // edges are left out, where the proxy may touch the plate's side).
    let (mut on_plate, mut examined) = (0usize, 0usize);
    for line in trace.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        let (x, z): (f64, f64) = (f[4].parse().expect("x"), f[6].parse().expect("z"));
        if f[11] == "1" && f[10] == "1" {
            on_plate += 1;
            if (0.16..0.34).contains(&x) {
                examined += 1;
                assert!(z >= 5e-5, "the proxy went into the plate: {line}");
            }
        }
    }
    // The rows in contact with the plate are the summary's time on object 1 (1 ms each),
    // and most of them were examined: a proxy that fell through the plate, or a trace
    // whose contact columns were wrong, would leave this check with nothing to examine.
    let summary = text
        .split("object 1: ")
        .nth(1)
        .and_then(|rest| rest.split(' ').next())
        .and_then(|s| s.parse::<f64>().ok())
        .unwrap_or_else(|| panic!("no time on object 1: {text}"));
    assert_eq!(on_plate, (summary * 1e3).round() as usize, "{text}");
    assert!(
        examined * 2 > on_plate,
        "{examined} of {on_plate} rows on the plate examined"
    );
}

#[test]
fn replay_gives_byte_identical_traces() {
    let dir = scratch("replay");
    let recorded = dir.join("recorded.csv");
    ok(&[
        "simulate",
        "--shape",
        "torus",
        "--triangles",
        "2000",
        "--path",
        "circle",
        "--seconds",
        "2",
        "--out",
        s(&recorded),
    ]);
    let (a, b) = (dir.join("a.csv"), dir.join("b.csv"));
    for out in [&a, &b] {
        let text = ok(&[
            "simulate",
            "--shape",
            "torus",
            "--triangles",
            "2000",
            "--replay",
            s(&recorded),
            "--out",
            s(out),
        ]);
        assert_eq!(
            figure(&text, "ticks"),
            2000.0,
            "every sample replayed: {text}"
        );
        assert!(figure(&text, "contact") > 0.2, "{text}");
    }
    let (a, b) = (std::fs::read(&a).expect("a"), std::fs::read(&b).expect("b"));
    assert!(a.len() > 100_000);
    assert!(a == b, "two replays differ");
    // Replaying its own device points gives back the recorded run (same HIPs, same proxy).
    let original = std::fs::read(&recorded).expect("recorded");
    let rows = |bytes: &[u8]| -> Vec<String> {
        String::from_utf8_lossy(bytes)
            .lines()
            .map(|l| l.split(',').skip(1).take(3).collect::<Vec<_>>().join(","))
            .collect()
    };
    assert_eq!(rows(&a)[..2000], rows(&original)[..2000]);
}

#[test]
fn scene_files_run_and_their_errors_say_where() {
    let dir = scratch("scene");
    let good = dir.join("two.toml");
    std::fs::write(
        &good,
        r#"# two objects, one moving
[[object]]
shape = "sphere"
triangles = 1000
position = [0.0, 0.0, 0.0]
material = { stiffness = 800.0, damping = 1.0, static_friction = 0.4, dynamic_friction = 0.3 }

[[object]]
name = "plate"
shape = "thin-plate"
triangles = 1000
position = [0.3, 0.0, 0.0]
rotation = [0.0, 0.0, 45.0]
motion = { kind = "oscillating", amplitude = [0.0, 0.0, 0.005], frequency = 1.0 }
"#,
    )
    .expect("write");
    let text = ok(&[
        "simulate",
        "--scene",
        s(&good),
        "--path",
        "press",
        "--seconds",
        "2",
    ]);
    assert!(text.contains("2 object(s)"), "{text}");
    assert!(figure(&text, "max penetration") > 0.5, "{text}");

    let bad = dir.join("bad.toml");
    std::fs::write(
        &bad,
        "[[object]]\nshape = \"sphere\"\n\n[[object]]\nshape = \"teapot\"\n",
    )
    .expect("write");
    let out = haphe(&["simulate", "--scene", s(&bad)]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        err.contains("bad.toml: object 2 (line 4)") && err.contains("teapot"),
        "{err}"
    );

    std::fs::write(
        &bad,
        "[[object]]\nshape = \"sphere\"\nposition = [0.0, 1.0]\n",
    )
    .expect("write");
    let err =
        String::from_utf8_lossy(&haphe(&["simulate", "--scene", s(&bad)]).stderr).into_owned();
    assert!(err.contains("bad.toml: line 3"), "{err}");

    std::fs::write(&bad, "[[object]]\nshape = \"box\"\ncolour = \"red\"\n").expect("write");
    let err =
        String::from_utf8_lossy(&haphe(&["simulate", "--scene", s(&bad)]).stderr).into_owned();
    assert!(
        err.contains("bad.toml: line 3") && err.contains("colour"),
        "{err}"
    );
}

#[test]
fn every_path_runs_with_and_without_the_hand() {
    for path in ["press", "slide", "circle", "explore", "strike"] {
        for hand in ["--hand", "--no-hand"] {
            let text = ok(&[
                "simulate",
                "--shape",
                "box",
                "--triangles",
                "1000",
                "--path",
                path,
                hand,
                "--seconds",
                "1.5",
            ]);
            assert!(figure(&text, "contact") > 0.05, "{path} {hand}: {text}");
            assert!(
                figure(&text, "max force") <= 3.3 + 1e-9,
                "{path} {hand}: {text}"
            );
        }
    }
}

/// The report of a press into a sphere of 1000 triangles in real time, at `rate` Hz for
/// `seconds`, `args` added.
fn realtime_press(rate: &str, seconds: &str, args: &[&str]) -> String {
    let mut all = vec![
        "simulate",
        "--shape",
        "sphere",
        "--triangles",
        "1000",
        "--path",
        "press",
        "--rate",
        rate,
        "--seconds",
        seconds,
        "--realtime",
    ];
    all.extend_from_slice(args);
    ok(&all)
}

#[test]
fn realtime_smoke_run_reports_lateness() {
    let text = realtime_press("2000", "0.3", &[]);
    println!("{text}");
    assert!(
        text.contains("lateness") && text.contains("overruns") && text.contains("missed deadlines"),
        "{text}"
    );
    assert!(figure(&text, "ticks") > 0.0);
}

/// `--normal-priority` keeps the time-shared priority and may spin the whole period.
#[test]
fn realtime_at_normal_priority_spins_the_whole_period() {
    let text = realtime_press("5000", "0.2", &["--spin-us", "200", "--normal-priority"]);
    println!("{text}");
    assert!(text.contains("servo thread      normal priority"), "{text}");
    assert!(!text.contains("FIFO"), "{text}");
    assert!(figure(&text, "ticks") > 0.0);
    if cfg!(target_os = "linux") {
        // Spinning the whole period, the thread never sleeps; what else ran is reported.
        assert!(text.contains("  interference      "), "{text}");
        assert!(text.contains("slept 0 time(s)"), "{text}");
    }
}

/// The rows of the trace `name` of `haphe simulate` on a box, the device point on the
/// slide path (no hand: the same path in every run), `args` added: per row its columns.
fn slide_rows(dir: &std::path::Path, name: &str, args: &[&str]) -> Vec<Vec<String>> {
    let csv = dir.join(name);
    let mut all = vec![
        "simulate",
        "--shape",
        "box",
        "--triangles",
        "500",
        "--stiffness",
        "500",
        "--path",
        "slide",
        "--no-hand",
        "--seconds",
        "2",
        "--out",
        s(&csv),
    ];
    all.extend_from_slice(args);
    ok(&all);
    let text = std::fs::read_to_string(&csv).expect("the trace is written");
    text.lines()
        .skip(1)
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect()
}

/// Columns `first..first + 3` of `row` (hip 1, force 7) as a vector.
fn column3(row: &[String], first: usize) -> [f64; 3] {
    [0, 1, 2].map(|k| row[first + k].parse().expect("a number"))
}

#[test]
fn a_viscosity_pulls_against_the_velocity_in_free_space() {
    let dir = scratch("viscosity");
    let plain = slide_rows(&dir, "plain.csv", &[]);
    let viscous = slide_rows(&dir, "viscous.csv", &["--effect", "viscosity:2"]);
    assert_eq!(plain.len(), viscous.len());
    let (mut examined, mut fastest) = (0usize, 0.0f64);
    for i in 1..plain.len() - 1 {
        let (row, v) = (&plain[i], &viscous[i]);
        // The same path: the device point is where it was.
        assert_eq!(row[1..4], v[1..4], "row {i}");
        if row[13] != "free" || v[13] != "free" {
            continue;
        }
        // The velocity from the positions: the mean over each tick before and after; the
        // true velocity lies between them where it changes monotonically (and the path's
        // own velocity, which the servo is given, is its derivative to within 0.1 %).
        let t = |r: &[String]| r[0].parse::<f64>().expect("t");
        let (p0, p1, p2) = (
            column3(&plain[i - 1], 1),
            column3(row, 1),
            column3(&plain[i + 1], 1),
        );
        let force = column3(v, 7);
        assert_eq!(column3(row, 7), [0.0; 3], "row {i}: free, no effect");
        let mut speed = 0.0;
        for k in 0..3 {
            let before = (p1[k] - p0[k]) / (t(row) - t(&plain[i - 1]));
            let after = (p2[k] - p1[k]) / (t(&plain[i + 1]) - t(row));
            let velocity = 0.5 * (before + after);
            speed += velocity * velocity;
            assert!(
                (force[k] + 2.0 * velocity).abs()
                    <= (after - before).abs() + 1e-3 * velocity.abs() + 1e-9,
                "row {i}, axis {k}: force {} for a velocity {velocity}",
                force[k]
            );
        }
        examined += 1;
        fastest = fastest.max(speed.sqrt());
    }
    // The slide path approaches the box and leaves it through free space: hundreds of
    // free rows, moving (else −2 v would be 0 and prove nothing).
    assert!(examined > 200, "{examined} free rows");
    assert!(fastest > 0.05, "fastest {fastest} m/s");
}

#[test]
fn a_texture_makes_a_steady_slide_felt_as_bumps() {
    let dir = scratch("texture");
    let plain = slide_rows(&dir, "plain.csv", &[]);
    let (amplitude, stiffness) = (0.0002, 500.0);
    let textured = slide_rows(&dir, "textured.csv", &["--texture", "sine:0.0002:0.002"]);
    assert_eq!(plain.len(), textured.len());
    // Where the device point slides at one height across the box's top face (its z
    // unchanged from the row before), both runs in contact: the plain run's force is
    // steady, the textured one's rises and falls over the ridges of the sine.
    let (mut plain_z, mut textured_z) = (Vec::new(), Vec::new());
    for i in 1..plain.len() {
        let same_height = plain[i][3] == plain[i - 1][3];
        if same_height && plain[i][13] == "contact" && textured[i][13] == "contact" {
            plain_z.push(column3(&plain[i], 7)[2]);
            textured_z.push(column3(&textured[i], 7)[2]);
        }
    }
    let spread = |v: &[f64]| {
        v.iter().copied().fold(f64::MIN, f64::max) - v.iter().copied().fold(f64::MAX, f64::min)
    };
    // The slide covers many wavelengths (2 mm) at 1 kHz: hundreds of rows.
    assert!(plain_z.len() > 200, "{} rows", plain_z.len());
    assert!(spread(&plain_z) < 1e-9, "plain: {}", spread(&plain_z));
    // Along one axis of a face across another the height swings by 2A/3 (the mean of the
    // three sines), pressed by the stiffness; sampled 18 times a wavelength, the extremes
    // are reached to within cos(π/18).
    let swing = stiffness * 2.0 * amplitude / 3.0;
    let felt = spread(&textured_z);
    assert!(
        felt >= 0.95 * swing && felt <= swing + 1e-9,
        "textured: {felt} N, expected {swing} N"
    );
}
