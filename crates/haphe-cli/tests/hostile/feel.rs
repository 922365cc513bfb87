//! Textures and effects from the command line and from scene files: every specification
//! that is not one (an unknown kind, a value non-finite, negative or out of its domain, a
//! vibration above half the servo rate, a zone inside an object that is not there) is
//! refused before anything runs, naming the flag (or the file's line) and the
//! specification, exit 2; a scene file's texture wins over the flag's; a zone inside an
//! open surface, which has no inside, is warned about.

use crate::common::{assert_error, haphe, ok, scratch, stderr, write};

/// The commands that take `--texture` and `--effect`, on a small sphere, writing a trace
/// to `out` where they can: short runs, and (in a build with the view) a view that would
/// serve (each refusal comes before).
fn commands(out: &str) -> Vec<Vec<&str>> {
    let sphere = ["--shape", "sphere", "--triangles", "100"];
    let mut commands = vec![
        [&["simulate", "--seconds", "0.1", "--out", out][..], &sphere].concat(),
        [
            &["run", "--device", "hand", "--seconds", "0.1", "--out", out][..],
            &sphere,
        ]
        .concat(),
    ];
    if cfg!(feature = "view") {
        commands.push([&["view", "--no-open", "--port", "0"][..], &sphere].concat());
    }
    commands
}

#[test]
fn bad_textures_and_effects_are_refused_by_every_command_naming_the_flag() {
    let dir = scratch("feel-flags");
    let out = dir.join("run.csv");
    let out = out.to_str().expect("a UTF-8 path");
    let half_rate = "vibration frequency must be at most half the servo rate";
    for command in commands(out) {
        for (flag, spec, says) in [
            ("--texture", "bumps:1:2", "unknown kind `bumps`"),
            (
                "--texture",
                "sine:0.0002",
                "expected `KIND:AMPLITUDE:WAVELENGTH`",
            ),
            ("--texture", "sine:nan:0.002", "texture amplitude must be"),
            ("--texture", "sine:-0.0002:0.002", "not -0.0002"),
            (
                "--texture",
                "noise:0.0002:inf",
                "texture wavelength must be",
            ),
            ("--effect", "wobble:1", "unknown kind `wobble`"),
            ("--effect", "viscosity:-2", "viscosity must be"),
            ("--effect", "viscosity:x", "`x` is not a number"),
            (
                "--effect",
                "constant:0:0:nan",
                "effect force must be finite",
            ),
            ("--effect", "spring:inf:0:0:0", "effect stiffness must be"),
            ("--effect", "magnet:-0.01:1", "magnet distance must be"),
            (
                "--effect",
                "vibration:-150:0.3",
                "vibration frequency must be",
            ),
            ("--effect", "vibration:600:0.3", half_rate),
            (
                "--effect",
                "viscosity:2:inside:5",
                "no object of the scene has id 5",
            ),
        ] {
            let mut args = command.clone();
            args.extend([flag, spec]);
            assert_error(&haphe(&args), &[&format!("{flag} `{spec}`: "), says]);
            assert!(!std::path::Path::new(out).exists(), "{args:?} ran");
        }
    }
}

#[test]
fn a_vibration_is_refused_above_half_the_rate_given() {
    let dir = scratch("feel-rate");
    for rate in [250.0f64, 1000.0, 4000.0] {
        let half = rate / 2.0;
        let simulate = |frequency: f64| {
            haphe(&[
                "simulate",
                "--shape",
                "sphere",
                "--triangles",
                "100",
                "--seconds",
                "0.05",
                "--rate",
                &rate.to_string(),
                "--effect",
                &format!("vibration:{frequency}:0.3"),
            ])
        };
        assert_error(
            &simulate(half + 1.0),
            &[&format!(
                "--effect `vibration:{}:0.3`: vibration frequency must be at most half the servo rate ({half} Hz at {rate} Hz), not {}",
                half + 1.0,
                half + 1.0
            )],
        );
        let at_half = simulate(half);
        assert_eq!(at_half.status.code(), Some(0), "{at_half:?}");
    }
    // A scene file's, named by its line, at the rate of the command.
    let scene = write(
        &dir,
        "s.toml",
        "# a buzz\neffects = [\"viscosity:1\", \"vibration:600:0.3\"]\n\n[[object]]\nshape = \"sphere\"\ntriangles = 100\n",
    );
    assert_error(
        &haphe(&["simulate", "--scene", &scene, "--seconds", "0.05"]),
        &[
            "s.toml: line 2: effect `vibration:600:0.3`: vibration frequency must be at most half the servo rate (500 Hz at 1000 Hz), not 600",
        ],
    );
    ok(&[
        "simulate",
        "--scene",
        &scene,
        "--seconds",
        "0.05",
        "--rate",
        "1200",
    ]);
}

#[test]
fn scene_files_name_the_line_and_their_textures_win_over_the_flag() {
    let dir = scratch("feel-file");
    let bad = write(
        &dir,
        "bad.toml",
        "[[object]]\nshape = \"sphere\"\ntriangles = 100\ntexture = \"sine:-1:0.002\"\n",
    );
    assert_error(
        &haphe(&["simulate", "--scene", &bad, "--seconds", "0.05"]),
        &[
            "bad.toml: line 4: texture `sine:-1:0.002`: texture amplitude must be",
            "not -1",
        ],
    );
    let inside = write(
        &dir,
        "inside.toml",
        "effects = [\"viscosity:2:inside:3\"]\n[[object]]\nshape = \"sphere\"\ntriangles = 100\n",
    );
    assert_error(
        &haphe(&["simulate", "--scene", &inside, "--seconds", "0.05"]),
        &["inside.toml: line 1: effect `viscosity:2:inside:3`: no object of the file has id 3"],
    );
    // The file's texture stays; the flag's textures the object that has none; the effects
    // are the file's, then the flags'.
    let scene = write(
        &dir,
        "s.toml",
        "effects = [\"viscosity:1\"]\n\n[[object]]\nshape = \"sphere\"\ntriangles = 100\ntexture = \"sine:0.0002:0.002\"\n\n\
         [[object]]\nshape = \"box\"\ntriangles = 100\nposition = [0.5, 0.0, 0.0]\n",
    );
    let text = ok(&[
        "simulate",
        "--scene",
        &scene,
        "--seconds",
        "0.05",
        "--texture",
        "noise:0.0001:0.001",
        "--effect",
        "viscosity:2:inside:1",
        "--effect",
        "spring:10:0:0:0",
    ]);
    let line = |name: &str| {
        text.lines()
            .find(|l| l.trim_start().starts_with(name))
            .unwrap_or_else(|| panic!("no {name} in {text}"))
            .to_string()
    };
    assert!(
        line("sphere").ends_with("texture of amplitude 0.200 mm)"),
        "{text}"
    );
    assert!(
        line("box").ends_with("texture of amplitude 0.100 mm)"),
        "{text}"
    );
    assert_eq!(
        line("effects:"),
        "effects: viscosity:1, viscosity:2:inside:1, spring:10:0:0:0"
    );
    // More effects than a scene holds.
    let many: Vec<&str> = ["--effect", "viscosity:1"].repeat(16);
    let mut args = vec!["simulate", "--scene", &scene, "--seconds", "0.05"];
    args.extend(many);
    assert_error(
        &haphe(&args),
        &["1 effects from the scene file and 16 from --effect, more than the limit of 16"],
    );
}

#[test]
fn a_zone_inside_an_open_surface_is_warned_about() {
    let dir = scratch("feel-open");
    // A tetrahedron without its slanted face: an open surface.
    let open = write(
        &dir,
        "open.obj",
        "v 0 0 0\nv 0.1 0 0\nv 0 0.1 0\nv 0 0 0.1\nf 1 3 2\nf 1 2 4\nf 1 4 3\n",
    );
    let closed = write(&dir, "closed.obj", crate::common::tetrahedron(0.0));
    let run = |mesh: &str| {
        let o = haphe(&[
            "simulate",
            "--mesh",
            mesh,
            "--seconds",
            "0.05",
            "--effect",
            "viscosity:2:inside:0",
        ]);
        assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
        stderr(&o)
    };
    let warned = run(&open);
    assert!(
        warned.contains("warning: --effect `viscosity:2:inside:0`: ")
            && warned.contains("open.obj (id 0) is not a closed solid"),
        "{warned}"
    );
    let quiet = run(&closed);
    assert!(!quiet.contains("not a closed solid"), "{quiet}");
}
