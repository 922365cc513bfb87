//! Query CSV files: a header only by its names, every other bad line an error naming the
//! file and the line; far segments answered as the brute force does.

use crate::common::{assert_error, haphe, scratch, stdout, tetrahedron, write};

#[test]
fn a_bad_first_line_is_an_error_not_a_header() {
    let dir = scratch("csv");
    let mesh = write(&dir, "t.obj", tetrahedron(0.0));
    let bad = write(&dir, "bad.csv", "0.07,0,abc\n0.01,0.01,0.01\n");
    assert_error(
        &haphe(&["query", &mesh, "--inside", &bad]),
        &["bad.csv: line 1", "\"abc\" is not a number", "x,y,z"],
    );
    let later = write(&dir, "later.csv", "x,y,z\n0.01,0.01,0.01\nx,y,z\n");
    assert_error(
        &haphe(&["query", &mesh, "--inside", &later]),
        &["later.csv: line 3"],
    );
    // The header by its names (any case, spaces, a byte-order mark) is skipped.
    let good = write(&dir, "good.csv", "\u{feff}X, Y ,z\n0.01,0.01,0.01\n1,1,1\n");
    let o = haphe(&["query", &mesh, "--inside", &good]);
    assert_eq!(o.status.code(), Some(0), "{}", crate::common::stderr(&o));
    assert_eq!(stdout(&o), "inside\noutside\n");
    let segments = write(
        &dir,
        "s.csv",
        "x0,y0,z0,x1,y1,z1\n-1,0.02,0.02,1,0.02,0.02\n",
    );
    let o = haphe(&["query", &mesh, "--segments", &segments]);
    assert_eq!(o.status.code(), Some(0), "{}", crate::common::stderr(&o));
    assert!(stdout(&o).ends_with(",true\n"), "{}", stdout(&o));
}

/// Segments from 3e11 m and 3e12 m away used to report an exit for an entry, or nothing.
#[test]
fn far_segments_find_the_entry() {
    let dir = scratch("far");
    let mesh = write(&dir, "t.obj", tetrahedron(0.0));
    let mut rows = String::new();
    for far in ["3e5", "3e9", "3e11", "3e12", "3e15", "1e300"] {
        rows += &format!("-{far},0.02,0.02,0.02,0.02,0.02\n");
    }
    let segments = write(&dir, "s.csv", &rows);
    let o = haphe(&["query", &mesh, "--segments", &segments]);
    assert_eq!(o.status.code(), Some(0), "{}", crate::common::stderr(&o));
    for line in stdout(&o).lines() {
        // The face at x = 0 (the tetrahedron's first face touching the yz plane), entering.
        let fields: Vec<&str> = line.split(',').collect();
        assert_eq!(fields.len(), 6, "{line}");
        assert_eq!(fields[5], "true", "{line}");
        assert_eq!(fields[2].parse::<f64>().unwrap(), 0.0, "{line}");
    }
}
