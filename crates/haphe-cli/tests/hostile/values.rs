//! Numbers out of range from the command line or a scene file: the same library check,
//! a clear refusal naming the value and the limit.

use crate::common::{
    assert_error, haphe, scratch, simulate_scene, simulate_sphere, stderr, tetrahedron, write,
};

#[test]
fn material_flags_are_checked_like_a_scene_file() {
    for (flag, value, says) in [
        (
            "--stiffness",
            "-5",
            "--stiffness must be a finite number above 0 and at most 1000000 N/m, not -5",
        ),
        ("--damping", "NaN", "--damping must be"),
        (
            "--static-friction",
            "0.1",
            "--dynamic-friction must be at most --static-friction (0.1), not 0.2",
        ),
        (
            "--max-force",
            "-1",
            "--max-force must be a finite number above 0 and at most 100 N, not -1",
        ),
        (
            "--max-force",
            "1000",
            "--max-force must be a finite number above 0 and at most 100 N, not 1000",
        ),
        (
            "--stiffness",
            "1e7",
            "--stiffness must be a finite number above 0 and at most 1000000 N/m, not 1e7",
        ),
        (
            "--rate",
            "0",
            "--rate must be a finite number from 1 to 40000 Hz, not 0",
        ),
        (
            "--spin-us",
            "-5",
            "--spin-us must be a finite number from 0 to 1000000 µs, not -5",
        ),
    ] {
        // The default dynamic friction is 0: ask for more than the static coefficient.
        let o = if flag == "--static-friction" {
            simulate_sphere(&[flag, value, "--dynamic-friction", "0.2"])
        } else {
            simulate_sphere(&[flag, value])
        };
        assert_error(&o, &[says]);
    }
    let dir = scratch("material");
    assert_error(
        &simulate_scene(
            &dir,
            "[[object]]\nshape = \"sphere\"\ntriangles = 100\nmaterial = { stiffness = -5.0, damping = 0.0, static_friction = 0.0, dynamic_friction = 0.0 }\n",
        ),
        &[
            "s.toml: object 1 (line 1): material stiffness must be a finite number above 0 and at most 1000000 N/m, not -5",
        ],
    );
}

#[test]
fn scene_motions_are_checked() {
    let dir = scratch("motion");
    for (motion, says) in [
        (
            "{ kind = \"linear\", velocity = [nan, 0.0, 0.0] }",
            "motion velocity must be finite in every component, not NaN",
        ),
        (
            "{ kind = \"oscillating\", amplitude = [1e308, 0.0, 0.0], frequency = 1.0 }",
            "motion amplitude must be finite with a length of at most 100 m, not 1e308",
        ),
        (
            "{ kind = \"oscillating\", amplitude = [0.01, 0.0, 0.0], frequency = inf }",
            "motion frequency must be a finite number from 0 to 500 Hz, not inf",
        ),
        (
            "{ kind = \"rotating\", axis = [0.0, 0.0, 0.0], rate = 1.0 }",
            "motion axis must be finite with a length above 0, not 0",
        ),
        (
            "{ kind = \"rotating\", axis = [0.0, 0.0, 1.0], rate = nan }",
            "motion rate must be",
        ),
    ] {
        assert_error(
            &simulate_scene(
                &dir,
                &format!("[[object]]\nshape = \"sphere\"\ntriangles = 100\nmotion = {motion}\n"),
            ),
            &["s.toml: object 1", says],
        );
    }
}

#[test]
fn sizes_and_lengths_have_stated_limits() {
    assert_error(
        &haphe(&[
            "generate",
            "sphere",
            "--triangles",
            "18446744073709551615",
            "-o",
            "x.stl",
        ]),
        &[
            "--triangles: a built-in shape has from 1 to 10000000 triangles, not 18446744073709551615",
        ],
    );
    assert_error(
        &haphe(&[
            "simulate",
            "--shape",
            "sphere",
            "--triangles",
            "100000000000",
        ]),
        &["--triangles", "10000000"],
    );
    let dir = scratch("limits");
    assert_error(
        &simulate_scene(
            &dir,
            "[[object]]\nshape = \"sphere\"\ntriangles = 18446744073709551615\n",
        ),
        &["s.toml: object 1", "10000000 triangles"],
    );
    // A trace with a gap of 1e9 s would run for decades.
    let trace = write(&dir, "gap.csv", "t,x,y,z\n0,0,0,0.2\n1e9,0,0,0.2\n");
    assert_error(
        &simulate_sphere(&["--replay", &trace]),
        &["spans 1000000000 s", "3600 s", "--seconds"],
    );
}

#[test]
fn verify_and_realtime_refuse_what_cannot_be_done() {
    let dir = scratch("verify");
    let mesh = write(&dir, "t.obj", tetrahedron(0.0));
    let o = haphe(&["verify", &mesh, "--samples", "0"]);
    assert_error(&o, &["nothing to check"]);
    assert!(!crate::common::stdout(&o).contains("PASSED"));
    let o = simulate_sphere(&["--realtime", "--standby-core", "99999"]);
    assert_error(
        &o,
        &[
            "--standby-core",
            "core 99999 is not one this process may run on",
        ],
    );
}

/// A mesh far from the origin is placed at it, as the help says, and touched; a path that
/// touches nothing is reported.
#[test]
fn simulate_places_a_far_mesh_at_the_origin() {
    let dir = scratch("far-mesh");
    let mesh = write(&dir, "far.obj", tetrahedron(2000.0));
    let o = haphe(&[
        "simulate",
        "--mesh",
        &mesh,
        "--seconds",
        "1",
        "--path",
        "press",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("placed with its centre at the origin"),
        "{}",
        stderr(&o)
    );
    let out = crate::common::stdout(&o);
    assert!(!out.contains("contact           0.000 s"), "{out}");
    assert!(!out.contains("never touched"), "{out}");
}
