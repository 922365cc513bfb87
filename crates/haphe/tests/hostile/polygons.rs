//! A huge non-convex polygon: refused in bounded time with the file, the line and the face,
//! in OBJ, OFF and PLY alike; never fanned into triangles that overlap.

use std::time::Instant;

use haphe::mesh::{Place, ReadErrorKind, ReadOptions, read_mesh};

/// A star of `n` corners (radius 10 and 7 in turn), as `x y z` lines.
fn star(n: usize) -> Vec<String> {
    (0..n)
        .map(|i| {
            let angle = i as f64 / n as f64 * std::f64::consts::TAU;
            let r = if i % 2 == 0 { 10.0 } else { 7.0 };
            format!("{} {} 0", r * angle.cos(), r * angle.sin())
        })
        .collect()
}

#[test]
fn a_20000_corner_star_is_refused_quickly_naming_the_face() {
    let n = 20_000;
    let corners = star(n);
    let obj = {
        let mut text: String = corners.iter().map(|c| format!("v {c}\n")).collect();
        text.push_str("f 1 2 3\n");
        text.push('f');
        (1..=n).for_each(|i| text.push_str(&format!(" {i}")));
        text.push('\n');
        text
    };
    let list: String = (0..n).map(|i| format!(" {i}")).collect();
    let off = format!("OFF\n{n} 2 0\n{}\n3 0 1 2\n{n}{list}\n", corners.join("\n"));
    let ply = format!(
        "ply\nformat ascii 1.0\nelement vertex {n}\nproperty float x\nproperty float y\n\
         property float z\nelement face 2\nproperty list int int vertex_indices\nend_header\n\
         {}\n3 0 1 2\n{n}{list}\n",
        corners.join("\n")
    );
    for (name, text, at) in [
        ("star.obj", obj, Place::Line(n + 2)),
        ("star.off", off, Place::Line(n + 4)),
        ("star.ply", ply, Place::Face(1)),
    ] {
        let start = Instant::now();
        let e = read_mesh(name, text.as_bytes(), &ReadOptions::default()).unwrap_err();
        // A few milliseconds of work in a release build; the full ear clipping (about 10^8
        // tests) or the old self-intersection search of its fan took minutes.
        assert!(
            start.elapsed().as_secs_f64() < 10.0,
            "{name}: {:?}",
            start.elapsed()
        );
        assert_eq!(
            e.kind,
            ReadErrorKind::PolygonTooComplex {
                at,
                face: 1,
                corners: n
            },
            "{name}"
        );
        let message = e.to_string();
        assert!(message.starts_with(&format!("{name}: ")), "{message}");
        assert!(
            message.contains("20000 corners") && message.contains("face 1"),
            "{message}"
        );
    }
}

/// Below the budget, a large non-convex polygon is still cut exactly (n − 2 triangles).
#[test]
fn a_1000_corner_star_is_still_triangulated() {
    let n = 1000;
    let mut text: String = star(n).iter().map(|c| format!("v {c}\n")).collect();
    text.push('f');
    (1..=n).for_each(|i| text.push_str(&format!(" {i}")));
    text.push('\n');
    let mesh = read_mesh("star.obj", text.as_bytes(), &ReadOptions::default()).expect("reads");
    assert_eq!(mesh.triangles.len(), n - 2);
}
