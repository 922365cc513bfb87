//! `haphe validate` on files built to be slow or misread: repeated faces, a byte-order
//! mark, coordinates that overflow.

use std::time::Duration;

use crate::common::{haphe_within, scratch, stdout, write};

/// One face repeated 10 000 times (20 KB) took 6 s and 1.2 GB: the copies are grouped by
/// sorting, and their 49 995 000 pairs counted without testing them.
#[test]
fn repeated_faces_are_counted_quickly() {
    let dir = scratch("repeated");
    let mut obj = String::from("v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    for _ in 0..10_000 {
        obj += "f 1 2 3\n";
    }
    let path = write(&dir, "repeated.obj", obj);
    let o = haphe_within(&["validate", &path], Duration::from_secs(30));
    let out = stdout(&o);
    assert!(
        out.contains("self-intersections: 49995000 triangle pairs"),
        "{out}"
    );
    assert!(
        out.contains("49995000 pairs of coincident triangles"),
        "{out}"
    );
}

/// Triangles stacked in one cell (distinct but overlapping) stop at the budget and say so.
#[test]
fn stacked_triangles_stop_at_the_budget() {
    let dir = scratch("stacked");
    let mut obj = String::new();
    let n = 12_000;
    for i in 0..n {
        let z = i as f64 * 1e-7;
        obj += &format!("v 0 0 {z}\nv 1 0 {z}\nv 0 1 {}\n", z + 0.5);
    }
    for i in 0..n {
        obj += &format!("f {} {} {}\n", 3 * i + 1, 3 * i + 2, 3 * i + 3);
    }
    let path = write(&dir, "stacked.obj", obj);
    let o = haphe_within(&["validate", &path, "--json"], Duration::from_secs(60));
    let out = stdout(&o);
    let json: serde_json::Value = serde_json::from_str(out.trim()).expect("one JSON line");
    assert_eq!(json["self_intersections_complete"], false, "{out}");
    assert!(json["self_intersections"].as_u64().unwrap() > 0, "{out}");
    let o = haphe_within(&["validate", &path], Duration::from_secs(60));
    assert!(
        stdout(&o).contains("the search stopped at its budget"),
        "{}",
        stdout(&o)
    );
}

/// A UTF-8 byte-order mark used to lose the first vertex of an OBJ and make an ASCII STL
/// be read as binary.
#[test]
fn a_byte_order_mark_is_accepted() {
    let dir = scratch("bom");
    let obj = write(
        &dir,
        "t.obj",
        format!("\u{feff}{}", crate::common::tetrahedron(0.0)),
    );
    let stl = write(
        &dir,
        "t.stl",
        "\u{feff}solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n",
    );
    let off = write(
        &dir,
        "t.off",
        "\u{feff}OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
    );
    for (path, verdict) in [
        (&obj, "a valid closed solid"),
        (&stl, "1 triangles"),
        (&off, "1 triangles"),
    ] {
        let o = haphe_within(&["validate", path], Duration::from_secs(30));
        assert!(stdout(&o).contains(verdict), "{path}: {}", stdout(&o));
    }
}

/// A vertex at 1e300 m was "a valid closed solid" whose map no load accepted.
#[test]
fn an_absurd_coordinate_is_refused_at_read() {
    let dir = scratch("absurd");
    let path = write(
        &dir,
        "big.obj",
        crate::common::tetrahedron(0.0).replacen("v 0 0 0", "v 1e300 0 0", 1),
    );
    let o = haphe_within(&["validate", &path], Duration::from_secs(30));
    assert!(
        stdout(&o).contains(
            "big.obj: vertex 0: a vertex coordinate of 1e300 m is beyond the 1e9 m haphe accepts"
        ),
        "{}",
        stdout(&o)
    );
    let o = haphe_within(
        &["build", &path, "-o", dir.join("m.map").to_str().unwrap()],
        Duration::from_secs(30),
    );
    crate::common::assert_error(&o, &["big.obj: vertex 0", "1e9 m"]);
}
