//! One set of defaults whatever the entry point: the device's maximum force and the
//! material of an object are the library's (`haphe::scene::DEFAULT_MAX_FORCE_N`,
//! `Material::DEFAULT`) in the library's own options, the simulated and network devices,
//! the command's flags and what a run reports, and the C API. (Python's and C's are
//! compared with the command's in `crates/haphe-py/tests/test_defaults.py`.)

mod common;

use common::{ok, scratch, write};
use haphe::proxy::ProxyOptions;
use haphe::scene::{DEFAULT_MAX_FORCE_N, Material};

/// The `[default: X]` clap shows for `--flag` in `haphe COMMAND --help`.
fn help_default(command: &str, flag: &str) -> f64 {
    let help = ok(&[command, "--help"]);
    let at = help
        .find(&format!("--{flag} <"))
        .unwrap_or_else(|| panic!("no --{flag} in `haphe {command} --help`:\n{help}"));
    let rest = &help[at..];
    let start = rest.find("[default: ").expect("a default") + "[default: ".len();
    let end = start + rest[start..].find(']').expect("closed");
    rest[start..end]
        .parse()
        .unwrap_or_else(|e| panic!("--{flag}'s default {:?}: {e}", &rest[start..end]))
}

#[test]
fn the_library_has_one_maximum_force() {
    assert_eq!(ProxyOptions::default().max_force(), DEFAULT_MAX_FORCE_N);
    assert_eq!(
        haphe::servo::simulated_spec().max_force,
        DEFAULT_MAX_FORCE_N
    );
    assert_eq!(
        haphe_devices::UdpOptions::default().max_force,
        DEFAULT_MAX_FORCE_N
    );
    assert_eq!(Material::default(), Material::DEFAULT);
}

#[test]
fn the_commands_flags_default_to_the_librarys() {
    for command in ["simulate", "run"] {
        assert_eq!(
            help_default(command, "max-force"),
            DEFAULT_MAX_FORCE_N,
            "{command}"
        );
        let m = Material::DEFAULT;
        for (flag, value) in [
            ("stiffness", m.stiffness()),
            ("damping", m.damping()),
            ("static-friction", m.static_friction()),
            ("dynamic-friction", m.dynamic_friction()),
        ] {
            assert_eq!(help_default(command, flag), value, "{command} --{flag}");
        }
    }
}

/// The object lines of a run's summary: "  NAME (id N, T triangles, K N/m, friction S/D)".
fn material_of(summary: &str) -> String {
    let line = summary
        .lines()
        .find(|l| l.contains(" N/m, friction "))
        .unwrap_or_else(|| panic!("no object line in:\n{summary}"));
    let at = line.rfind("triangles, ").expect("a triangle count") + "triangles, ".len();
    line[at..].to_string()
}

#[test]
fn a_built_in_shape_and_a_scene_file_object_get_the_same_material() {
    let dir = scratch("defaults");
    let scene = write(
        &dir,
        "box.toml",
        "[[object]]\nshape = \"box\"\ntriangles = 2000\n",
    );
    let run = ["--path", "press", "--seconds", "0.5"];
    let shape_args = ["simulate", "--shape", "box", "--triangles", "2000"];
    let from_shape = ok(&[&shape_args[..], &run[..]].concat());
    let from_scene = ok(&[&["simulate", "--scene", scene.as_str()][..], &run[..]].concat());
    let expected = default_material_text();
    assert_eq!(material_of(&from_shape), expected, "{from_shape}");
    assert_eq!(material_of(&from_scene), expected, "{from_scene}");
    // And the run renders at most the default maximum, which it reports.
    for text in [&from_shape, &from_scene] {
        assert_default_maximum(text);
    }
}

/// How an object line of the summary shows [`Material::DEFAULT`].
fn default_material_text() -> String {
    let m = Material::DEFAULT;
    format!(
        "{:.0} N/m, friction {}/{})",
        m.stiffness(),
        m.static_friction(),
        m.dynamic_friction()
    )
}

/// Asserts that a run's summary reports the library's default maximum force.
fn assert_default_maximum(summary: &str) {
    let line = summary
        .lines()
        .find(|l| l.trim_start().starts_with("max force"))
        .expect("a max force line");
    assert!(
        line.contains(&format!("(device maximum {DEFAULT_MAX_FORCE_N} N;")),
        "{line}"
    );
}

#[test]
fn a_mesh_file_and_a_scene_file_mesh_object_get_the_same_material() {
    let dir = scratch("defaults-mesh");
    let mesh = write(&dir, "tet.obj", common::tetrahedron(0.0));
    let scene = write(&dir, "tet.toml", format!("[[object]]\nmesh = {mesh:?}\n"));
    let run = ["--path", "press", "--seconds", "0.5"];
    let from_mesh = ok(&[&["simulate", "--mesh", mesh.as_str()][..], &run[..]].concat());
    let from_scene = ok(&[&["simulate", "--scene", scene.as_str()][..], &run[..]].concat());
    let from_run = ok(&[
        "run",
        "--device",
        "hand",
        "--mesh",
        mesh.as_str(),
        "--seconds",
        "0.5",
    ]);
    let expected = default_material_text();
    for text in [&from_mesh, &from_scene, &from_run] {
        assert_eq!(material_of(text), expected, "{text}");
        assert_default_maximum(text);
    }
}
