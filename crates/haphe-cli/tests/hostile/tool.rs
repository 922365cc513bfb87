//! The tool's radius from the command line and from scene files: a value outside its domain
//! or larger than the scene is refused naming the flag (or the file's line), exit 2; the
//! flag overrides the file; a radius of 0 is the point.

use crate::common::{assert_error, haphe, ok, s, scratch, simulate_sphere, tetrahedron, write};

/// The diagonal of the tetrahedron's box (0.1 m on each side), as a message states a limit:
/// four significant digits, rounded down.
fn tetrahedron_diagonal() -> String {
    let diagonal = (3.0 * 0.1f64 * 0.1).sqrt();
    format!("{:.4}", (diagonal * 1e4).floor() / 1e4)
}

/// The commands that take `--tool-radius`, on `mesh`: short runs, and (in a build with
/// the view) a view that would serve (each refusal comes before).
fn commands(mesh: &str) -> Vec<Vec<&str>> {
    let mut commands = vec![
        vec!["simulate", "--mesh", mesh, "--seconds", "0.1"],
        vec![
            "run",
            "--device",
            "hand",
            "--mesh",
            mesh,
            "--seconds",
            "0.1",
        ],
    ];
    if cfg!(feature = "view") {
        commands.push(vec!["view", "--mesh", mesh, "--no-open", "--port", "0"]);
    }
    commands
}

#[test]
fn a_radius_outside_its_domain_is_refused_by_every_command() {
    let dir = scratch("tool-domain");
    let mesh = write(&dir, "t.obj", tetrahedron(0.0));
    for command in commands(&mesh) {
        for (value, shown) in [
            ("-0.001", "-0.001"),
            ("nan", "NaN"),
            ("inf", "inf"),
            ("0.6", "0.6"),
        ] {
            let mut args = command.clone();
            args.extend(["--tool-radius", value]);
            let o = haphe(&args);
            assert_error(
                &o,
                &[
                    "--tool-radius must be a finite number from 0 to 0.5 m",
                    &format!("not {shown}"),
                ],
            );
        }
    }
    assert_error(
        &simulate_sphere(&["--tool-radius", "2mm"]),
        &["--tool-radius", "2mm"],
    );
}

#[test]
fn a_radius_larger_than_the_scene_is_refused_naming_where_it_was_given() {
    let dir = scratch("tool-scene");
    let mesh = write(&dir, "t.obj", tetrahedron(0.0));
    let limit = format!(
        "must be at most {} m, the diagonal of the box bounding the scene's objects",
        tetrahedron_diagonal()
    );
    for command in commands(&mesh) {
        let mut args = command.clone();
        args.extend(["--tool-radius", "0.2"]);
        assert_error(
            &haphe(&args),
            &[&format!("--tool-radius {limit}"), "not 0.2"],
        );
    }
    // The same from a scene file, named by its line; the flag overrides the file.
    let scene = write(
        &dir,
        "s.toml",
        "# a tetrahedron\ntool_radius = 0.2\n\n[[object]]\nmesh = \"t.obj\"\n",
    );
    assert_error(
        &haphe(&["simulate", "--scene", &scene, "--seconds", "0.1"]),
        &[&format!("s.toml: line 2: tool_radius {limit}"), "not 0.2"],
    );
    let text = ok(&[
        "simulate",
        "--scene",
        &scene,
        "--seconds",
        "0.1",
        "--tool-radius",
        "0.001",
    ]);
    assert!(text.contains("tool: a sphere of radius 1.000 mm"), "{text}");
    // Just under the diagonal fits.
    let text = ok(&[
        "simulate",
        "--mesh",
        &mesh,
        "--seconds",
        "0.1",
        "--tool-radius",
        "0.17",
    ]);
    assert!(
        text.contains("tool: a sphere of radius 170.000 mm"),
        "{text}"
    );
}

#[test]
fn a_scene_file_gives_the_radius_and_zero_is_the_point() {
    let dir = scratch("tool-file");
    let scene = write(
        &dir,
        "s.toml",
        "tool_radius = 0.0025\n[[object]]\nshape = \"sphere\"\ntriangles = 100\n",
    );
    let text = ok(&["simulate", "--scene", &scene, "--seconds", "0.1"]);
    assert!(text.contains("tool: a sphere of radius 2.500 mm"), "{text}");
    assert_error(
        &haphe(&[
            "simulate",
            "--scene",
            &write(
                &dir,
                "bad.toml",
                "tool_radius = -1\n[[object]]\nshape = \"box\"\n",
            ),
        ]),
        &["bad.toml: line 1: tool_radius must be a finite number from 0 to 0.5 m, not -1"],
    );
    // A radius of 0 is the point: the same trace, byte for byte, and no tool line, on a
    // press and on strikes (1.5 m/s taps), on a shape and on a scene of two objects.
    let (point, zero) = (dir.join("point.csv"), dir.join("zero.csv"));
    let run = |objects: &[&str], path: &str, out: &std::path::Path, extra: &[&str]| {
        let mut args = vec![
            "simulate",
            "--path",
            path,
            "--seconds",
            "1",
            "--out",
            s(out),
        ];
        args.extend_from_slice(objects);
        args.extend_from_slice(extra);
        ok(&args)
    };
    let sphere = ["--shape", "sphere", "--triangles", "500"];
    let two = [
        "--scene",
        concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../scenes/blob-and-plate.toml"
        ),
    ];
    for (objects, path) in [
        (&sphere[..], "press"),
        (&sphere[..], "strike"),
        (&two[..], "strike"),
    ] {
        let a = run(objects, path, &point, &[]);
        let b = run(objects, path, &zero, &["--tool-radius", "0"]);
        assert!(!a.contains("tool:") && !b.contains("tool:"), "{b}");
        let (a, b) = (
            std::fs::read(&point).expect("point"),
            std::fs::read(&zero).expect("zero"),
        );
        assert!(a.len() > 10_000, "{} bytes", a.len());
        assert!(
            a == b,
            "--tool-radius 0 changed the trace of {path} on {objects:?}"
        );
    }
}

/// The demo takes `--tool-radius` too: 0 writes the same trace as no flag, byte for byte,
/// and a tool of 2 mm another, named in the summary.
#[test]
fn the_demo_with_a_tool_of_radius_zero_is_the_demo() {
    let dir = scratch("tool-demo");
    let trace = |name: &str, extra: &[&str]| {
        let (csv, png) = (
            dir.join(format!("{name}.csv")),
            dir.join(format!("{name}.png")),
        );
        let mut args = vec![
            "demo",
            "--fast",
            "--seconds",
            "1",
            "--out",
            s(&csv),
            "--plot",
            s(&png),
        ];
        args.extend_from_slice(extra);
        let text = ok(&args);
        (std::fs::read(&csv).expect("the trace"), text)
    };
    let (point, _) = trace("point", &[]);
    let (zero, _) = trace("zero", &["--tool-radius", "0"]);
    let (tool, text) = trace("tool", &["--tool-radius", "0.002"]);
    assert!(
        point.len() > 10_000 && point == zero,
        "--tool-radius 0 changed the demo's trace"
    );
    assert!(
        tool != point,
        "a tool of 2 mm left the trace as the point's"
    );
    assert!(text.contains("tool: a sphere of radius 2.000 mm"), "{text}");
}
