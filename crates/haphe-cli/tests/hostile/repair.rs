//! `haphe validate` names the triangles to flip and counts the holes; `haphe repair`
//! turns a broken box into a closed solid that `validate` accepts, refuses a hole above
//! its limit, and never writes over its input.

use crate::common::{assert_error, haphe, scratch, stderr, stdout, write};

/// The unit box's 8 corners and 12 triangles (outward), as OBJ lines.
const CORNERS: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n";
const FACES: [[u32; 3]; 12] = [
    [1, 3, 2],
    [1, 4, 3],
    [1, 2, 6],
    [1, 6, 5],
    [2, 3, 7],
    [2, 7, 6],
    [3, 4, 8],
    [3, 8, 7],
    [4, 1, 5],
    [4, 5, 8],
    [5, 6, 7],
    [5, 7, 8],
];

/// The box with the top quad (faces 10 and 11) missing, face 4 flipped and face 6 given
/// twice (the copy last): 11 faces.
fn broken_box() -> String {
    let mut faces: Vec<[u32; 3]> = FACES[..10].to_vec();
    faces[4].swap(1, 2);
    faces.push(FACES[6]);
    let mut text = CORNERS.to_owned();
    for f in faces {
        text += &format!("f {} {} {}\n", f[0], f[1], f[2]);
    }
    text
}

#[test]
fn validate_names_the_flips_and_counts_the_holes() {
    let dir = scratch("validate-fix");
    let mesh = write(&dir, "broken.obj", broken_box());
    let out = stdout(&haphe(&["validate", &mesh]));
    assert!(out.contains("  holes: 1 hole of 4 edges\n"), "{out}");
    assert!(
        out.contains("  triangles to flip for a consistent orientation (1): 4\n"),
        "{out}"
    );
    assert!(
        out.contains("inconsistently oriented triangles: flip 1 triangle(s) (4)"),
        "{out}"
    );
    let json = stdout(&haphe(&["validate", "--json", &mesh]));
    let v: serde_json::Value = serde_json::from_str(json.trim()).expect("json");
    assert_eq!(v["defects"]["faces_to_flip"], serde_json::json!([4]));
    assert_eq!(v["defects"]["holes"].as_array().map(Vec::len), Some(1));
    assert_eq!(v["defects"]["holes"][0].as_array().map(Vec::len), Some(4));
}

#[test]
fn repair_makes_a_closed_solid_that_validate_accepts() {
    let dir = scratch("repair");
    let text = broken_box();
    let mesh = write(&dir, "broken.obj", &text);
    let fixed = dir.join("fixed.obj").display().to_string();
    let o = haphe(&["repair", &mesh, &fixed]);
    let said = stdout(&o);
    assert_eq!(o.status.code(), Some(0), "{said}{}", stderr(&o));
    for part in [
        "welded 0 vertices into others within 1.732e-6 m",
        "dropped 1 duplicate triangle(s): 10",
        "flipped 1 triangle(s) for a consistent orientation: 4",
        "filled a hole of 4 edges",
        "with 2 triangle(s)",
        "fixed.obj: 12 triangles, 8 vertices: a valid closed solid, volume 1.000000e0 m³",
    ] {
        assert!(said.contains(part), "{part:?} missing from: {said}");
    }
    // The input is as it was; the output validates as a closed solid of the unit box's
    // volume.
    assert_eq!(std::fs::read_to_string(&mesh).unwrap(), text);
    let o = haphe(&["validate", "--json", &fixed]);
    assert_eq!(o.status.code(), Some(0), "{}", stdout(&o));
    let v: serde_json::Value = serde_json::from_str(stdout(&o).trim()).expect("json");
    assert_eq!(v["usable_as"], "solid");
    assert_eq!(v["closed"], true);
    let volume = v["volume"].as_f64().expect("a volume");
    assert!((volume - 1.0).abs() < 1e-12, "{volume}");
    // Written as STL too.
    let stl = dir.join("fixed.stl").display().to_string();
    assert_eq!(haphe(&["repair", &mesh, &stl]).status.code(), Some(0));
    assert_eq!(haphe(&["validate", &stl]).status.code(), Some(0));
}

#[test]
fn repair_refuses_a_large_hole_and_its_own_input() {
    let dir = scratch("repair-refuses");
    let mesh = write(&dir, "broken.obj", broken_box());
    let out = dir.join("out.obj").display().to_string();
    let o = haphe(&["repair", &mesh, &out, "--max-hole-edges", "3"]);
    assert_error(
        &o,
        &[
            "broken.obj: a hole of 4 edges",
            "larger than the limit of 3 edges",
            "--max-hole-edges 3",
            "nothing written",
        ],
    );
    assert!(!dir.join("out.obj").exists());
    let before = std::fs::read(&mesh).unwrap();
    let o = haphe(&["repair", &mesh, &mesh]);
    assert_error(&o, &["it is one of the input files"]);
    assert_eq!(std::fs::read(&mesh).unwrap(), before);
    let o = haphe(&["repair", &mesh, &dir.join("out.ply").display().to_string()]);
    assert_error(&o, &["repair writes .obj or .stl"]);
}
