//! `haphe validate` on files built to be slow or misread: repeated faces, a byte-order
//! mark, coordinates that overflow.

use std::time::Duration;

use crate::common::{haphe_within, scratch, stdout, write};

/// One face repeated 10 000 times (20 KB) took 6 s and 1.2 GB: the copies are grouped by
/// sorting, and their 49 995 000 pairs counted without testing them (duplicate faces,
/// not self-intersections).
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
        out.contains("self-intersections: 0 triangle pairs"),
        "{out}"
    );
    assert!(out.contains("problem: 9999 duplicate face(s)"), "{out}");
    assert!(
        out.contains("49995000 pairs of coincident triangles"),
        "{out}"
    );
}

/// Distinct triangles through one line (each pair crosses), all in the same few cells: the
/// search stops at its budget and says so, with the pairs it found.
#[test]
fn stacked_triangles_stop_at_the_budget() {
    let dir = scratch("stacked");
    let mut obj = String::new();
    let n = 4_000;
    for i in 0..n {
        // The plane z = h (1 - 2x - 2y) holds the line x + y = 1/2, z = 0 for every h.
        let h = (i as f64 / n as f64 - 0.5) * 0.1 + 1e-4;
        obj += &format!("v 0 0 {h}\nv 1 0 {}\nv 0 1 {}\n", -h, -h);
    }
    for i in 0..n {
        obj += &format!("f {} {} {}\n", 3 * i + 1, 3 * i + 2, 3 * i + 3);
    }
    let path = write(&dir, "stacked.obj", obj);
    let o = haphe_within(&["validate", &path, "--json"], Duration::from_secs(120));
    let out = stdout(&o);
    let json: serde_json::Value = serde_json::from_str(out.trim()).expect("one JSON line");
    assert_eq!(json["self_intersections_complete"], false, "{out}");
    let found = json["self_intersections"].as_u64().unwrap();
    assert!(found >= 1_000_000, "{out}");
    let o = haphe_within(&["validate", &path], Duration::from_secs(120));
    let text = stdout(&o);
    assert!(
        text.contains(&format!(
            "self-intersections: at least {found} triangle pairs"
        )),
        "{text}"
    );
    assert!(
        text.contains("the search stopped at its budget of 2097152 candidate pairs"),
        "{text}"
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
