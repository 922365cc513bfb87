//! Map files: the source mesh recorded and checked, damaged and older maps named as such
//! by every command, and the same answer whatever the map file is called.

use std::path::Path;

use crate::common::{assert_error, haphe, scratch, stderr, stdout, tetrahedron, write};

/// Asserts exit code 2 and every one of `parts` in the output (`validate` reports on
/// standard output, the other commands on standard error), with no "not a mesh" in it.
fn assert_refused(o: &std::process::Output, parts: &[&str]) {
    let all = format!("{}{}", stdout(o), stderr(o));
    assert_eq!(o.status.code(), Some(2), "{all}");
    for part in parts {
        assert!(all.contains(part), "{part:?} missing from: {all}");
    }
    assert!(!all.contains("not a mesh file haphe can read"), "{all}");
}

/// Builds `mesh` into `dir/name` and returns the map's path.
fn build(mesh: &str, dir: &Path, name: &str) -> String {
    let map = dir.join(name).display().to_string();
    let o = haphe(&["build", mesh, "-o", &map]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    map
}

/// `build` records the source's name, size and hash and prints them; `query` shows them;
/// `query --mesh` accepts the mesh the map was built from (renamed too) and refuses
/// another, naming both files.
#[test]
fn a_map_records_its_mesh_and_refuses_another() {
    let dir = scratch("provenance");
    let text = tetrahedron(0.0);
    let mesh = write(&dir, "tet.obj", &text);
    let map = dir.join("tet.map").display().to_string();
    let o = haphe(&["build", &mesh, "-o", &map]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let hash = format!("{:032x}", xxhash_rust::xxh3::xxh3_128(text.as_bytes()));
    let source = format!("source: tet.obj, {} bytes, xxh3-128 {hash}", text.len());
    assert!(stdout(&o).contains(&source), "{}", stdout(&o));

    let points = write(&dir, "p.csv", "0.01,0.01,0.01\n1,1,1\n");
    let o = haphe(&["query", &map, "--inside", &points, "--mesh", &mesh]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_eq!(stdout(&o), "inside\noutside\n");
    assert!(
        stderr(&o).contains(&format!("tet.map: a map of tet.obj, {} bytes", text.len())),
        "{}",
        stderr(&o)
    );
    // The same bytes under another name match: the content decides.
    let copy = write(&dir, "copy.obj", &text);
    let o = haphe(&["query", &map, "--inside", &points, "--mesh", &copy]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));

    let other = write(&dir, "other.obj", tetrahedron(2.0));
    let o = haphe(&["query", &map, "--inside", &points, "--mesh", &other]);
    assert_error(
        &o,
        &[
            "tet.map was built from tet.obj",
            "not from",
            "other.obj",
            "haphe build",
        ],
    );
    assert!(stdout(&o).is_empty(), "no answer for the wrong mesh");
    // A mesh file as the object: nothing to check against.
    let o = haphe(&["query", &mesh, "--inside", &points, "--mesh", &mesh]);
    assert_error(&o, &["tet.obj is a mesh file, not a map"]);
}

/// A map of an older format (version 10, before provenance) is refused with the version and
/// how to rebuild it, naming the file, by `query`, `verify` and `validate` alike.
#[test]
fn an_older_map_names_its_version_and_how_to_rebuild() {
    let dir = scratch("old-map");
    let mesh = write(&dir, "tet.obj", tetrahedron(0.0));
    let map = build(&mesh, &dir, "tet.map");
    let mut bytes = std::fs::read(&map).unwrap();
    bytes[8..12].copy_from_slice(&10u32.to_le_bytes());
    std::fs::write(&map, &bytes).unwrap();
    let points = write(&dir, "p.csv", "0,0,0\n");
    for args in [
        vec!["query", &map, "--inside", &points],
        vec!["verify", &map, "--samples", "10"],
        vec!["validate", &map],
    ] {
        let o = haphe(&args);
        assert_refused(
            &o,
            &[
                "tet.map: a map of format version 10",
                "older haphe",
                "haphe build MESH -o",
            ],
        );
    }
}

/// A damaged header is a damaged map (never "not a mesh file"), with the byte offset and
/// field, from every command; so is a magic with a byte changed.
#[test]
fn a_damaged_map_says_so_with_the_place() {
    let dir = scratch("damaged-map");
    let mesh = write(&dir, "tet.obj", tetrahedron(0.0));
    let map = build(&mesh, &dir, "tet.map");
    let good = std::fs::read(&map).unwrap();
    let points = write(&dir, "p.csv", "0,0,0\n");
    let cases: [(&str, usize, &[&str]); 4] = [
        ("magic", 3, &["byte 0 (magic)"]),
        ("version", 9, &["byte 8 (format version)"]),
        ("length", 17, &["byte 16 (file length)"]),
        ("body", good.len() - 100, &["byte 56 (checksum)", "damaged"]),
    ];
    for (what, at, says) in cases {
        let mut bytes = good.clone();
        bytes[at] ^= 0x5a;
        let damaged = write(&dir, &format!("{what}.ply"), &bytes);
        for args in [
            vec!["query", damaged.as_str(), "--inside", &points],
            vec!["verify", &damaged, "--samples", "10"],
            vec!["validate", &damaged],
        ] {
            let o = haphe(&args);
            let mut parts = vec!["damaged map: ", damaged.as_str()];
            parts.extend_from_slice(says);
            assert_refused(&o, &parts);
        }
    }
}

/// A good map named `.ply`: `query` and `verify` read it, `validate` says it is a map file
/// (not "not a PLY file"): detection by content, the same in every command.
#[test]
fn a_map_named_ply_is_a_map_for_every_command() {
    let dir = scratch("map-ply");
    let mesh = write(&dir, "tet.obj", tetrahedron(0.0));
    let map = build(&mesh, &dir, "tet.ply");
    let points = write(&dir, "p.csv", "0.01,0.01,0.01\n");
    let o = haphe(&["query", &map, "--inside", &points]);
    assert_eq!(
        (o.status.code(), stdout(&o).as_str()),
        (Some(0), "inside\n"),
        "{}",
        stderr(&o)
    );
    let o = haphe(&["verify", &map, "--samples", "20", "--ticks", "0"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_refused(
        &haphe(&["validate", &map]),
        &["tet.ply: a map file written by `haphe build`"],
    );
}

/// `verify` on a mesh of degenerate triangles only names the file.
#[test]
fn verify_on_an_all_degenerate_mesh_names_the_file() {
    let dir = scratch("degenerate");
    let mesh = write(
        &dir,
        "flat.obj",
        "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\nf 3 2 1\n",
    );
    let o = haphe(&["verify", &mesh, "--samples", "10"]);
    assert_error(&o, &["flat.obj"]);
}

/// `simulate --mesh`, `run --mesh` and scene files take a map file where they take a mesh:
/// the same run, trace byte for byte, as the mesh's; checked against the mesh beside it,
/// and refused, naming both files, once that mesh has changed, as `query --mesh` refuses
/// it.
#[test]
fn simulate_and_scene_files_take_a_map_checked_against_its_mesh() {
    let dir = scratch("map-simulate");
    let mesh = dir.join("ball.obj");
    crate::common::generate_sphere(&mesh, 2000);
    let mesh = mesh.display().to_string();
    let map = build(&mesh, &dir, "ball.map");
    let trace = |args: &[&str], name: &str| {
        let out = dir.join(name).display().to_string();
        let mut all = vec!["simulate", "--seconds", "1", "--out", &out];
        all.extend_from_slice(args);
        let o = haphe(&all);
        assert_eq!(o.status.code(), Some(0), "{args:?}: {}", stderr(&o));
        (std::fs::read(&out).expect("trace"), stderr(&o))
    };
    let (of_mesh, _) = trace(&["--mesh", &mesh], "mesh.csv");
    let (of_map, said) = trace(&["--mesh", &map], "map.csv");
    assert!(of_mesh.len() > 10_000 && of_mesh == of_map, "{said}");
    assert!(
        said.contains("ball.map: a map of") && said.contains("(checked)"),
        "{said}"
    );
    let scene_of =
        |object: &str, name: &str| write(&dir, name, format!("[[object]]\nmesh = \"{object}\"\n"));
    let (scene_mesh, scene_map) = (
        scene_of("ball.obj", "mesh.toml"),
        scene_of("ball.map", "map.toml"),
    );
    let (a, _) = trace(&["--scene", &scene_mesh], "scene-mesh.csv");
    let (b, _) = trace(&["--scene", &scene_map], "scene-map.csv");
    assert!(a.len() > 10_000 && a == b);
    // `run` takes it as well (the simulated hand, on the wall clock).
    let run = |seconds| {
        vec![
            "run",
            "--device",
            "hand",
            "--mesh",
            map.as_str(),
            "--seconds",
            seconds,
        ]
    };
    let o = haphe(&run("0.2"));
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(stdout(&o).contains("ball.map"), "{}", stdout(&o));

    // The mesh changes after the build: every entry point refuses the map.
    let mut text = std::fs::read(&mesh).unwrap();
    text.extend_from_slice(b"# edited\n");
    std::fs::write(&mesh, &text).unwrap();
    let points = write(&dir, "p.csv", "0,0,0\n");
    for args in [
        vec!["simulate", "--mesh", &map, "--seconds", "0.1"],
        vec!["simulate", "--scene", &scene_map, "--seconds", "0.1"],
        run("0.1"),
        vec!["query", &map, "--mesh", &mesh, "--inside", &points],
    ] {
        assert_error(
            &haphe(&args),
            &[
                "ball.map was built from ball.obj",
                "rebuild it with `haphe build",
            ],
        );
    }
}
