//! The readers never panic or hang on damaged input: every reader (and format detection)
//! runs on every prefix of a few small files — truncation at every byte — and on copies
//! with single bytes overwritten.

mod support;

use std::time::{Duration, Instant};

use haphe::mesh::{Format, ReadOptions, read_mesh};

/// A generous bound for reading a file of a few kilobytes, even on a loaded machine; a
/// reader that loops on bad input blows through it.
const MAX_READ_TIME: Duration = Duration::from_secs(2);

/// Small inputs covering every reader's paths (text and binary).
fn samples() -> Vec<(String, Vec<u8>)> {
    let mut samples = vec![
        (
            "inline.obj".to_owned(),
            b"# c\r\nv 0 0 0\nv 1 0 0 0.5 nan 1\nv 1 1 0\nv 0 1 \\\n0\nvt 0 0\n\
              f 1/1 2/1 3/1 4/1\nf -4//1 -3//1 -1//1\nl 1 2\n"
                .to_vec(),
        ),
        (
            "inline.stl".to_owned(),
            b"solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n\
              vertex 0 1 0\nendloop\nendfacet\nendsolid s\nsolid t\nendsolid t\n"
                .to_vec(),
        ),
        (
            "inline.ply".to_owned(),
            b"ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n\
              property float z\nelement face 1\nproperty list uchar int vertex_indices\n\
              element tristrips 1\nproperty list int int vertex_indices\nend_header\n\
              0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n6 0 1 2 -1 2 3\n"
                .to_vec(),
        ),
        ("inline_be.ply".to_owned(), big_endian_ply()),
    ];
    let dir = support::meshes();
    for name in [
        "odd/comments.off",
        "odd/whitespace.off",
        "odd/negative_indices.obj",
        "odd/notenoughindices.obj",
        "odd/joined_tetrahedra.obj",
        "odd/ply_points_bin.ply",
        "odd/points_ascii.ply",
        "odd/empty.stl",
        "odd/stl_empty_bin.stl",
        "models/tet.ply",
    ] {
        let bytes = std::fs::read(dir.join(name)).expect("real mesh is readable");
        samples.push((name.to_owned(), bytes));
    }
    // The first 20 triangles of a binary STL (a valid file of 1084 bytes).
    let mut stl = std::fs::read(dir.join("odd/soup.stl")).expect("soup.stl");
    stl.truncate(84 + 20 * 50);
    stl[80..84].copy_from_slice(&20u32.to_le_bytes());
    samples.push(("soup20.stl".to_owned(), stl));
    samples
}

/// A binary big-endian PLY: a triangle with double coordinates and a short-indexed face.
fn big_endian_ply() -> Vec<u8> {
    let mut bytes = b"ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty double x\n\
        property double y\nproperty double z\nelement face 1\n\
        property list uchar short vertex_indices\nend_header\n"
        .to_vec();
    for v in [[0.0f64, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]] {
        for x in v {
            bytes.extend(x.to_be_bytes());
        }
    }
    bytes.push(3);
    for i in 0..3i16 {
        bytes.extend(i.to_be_bytes());
    }
    bytes
}

/// Runs detection and every reader on `bytes`; results do not matter, returning does.
fn read_every_way(name: &str, bytes: &[u8]) {
    let formats = [
        None,
        Some(Format::Obj),
        Some(Format::Stl),
        Some(Format::Ply),
        Some(Format::Off),
    ];
    for format in formats {
        let options = ReadOptions {
            format,
            ..Default::default()
        };
        let start = Instant::now();
        let result = read_mesh(name, bytes, &options);
        let elapsed = start.elapsed();
        assert!(
            elapsed < MAX_READ_TIME,
            "{name} ({} bytes) as {format:?} took {elapsed:?}",
            bytes.len()
        );
        if let Err(e) = result {
            // Every error names the file.
            assert!(e.to_string().starts_with(name), "{e}");
        }
    }
}

#[test]
fn the_samples_load_whole() {
    for (name, bytes) in samples() {
        let loads = read_mesh(&name, &bytes, &ReadOptions::default());
        let expected_to_load =
            !name.contains("points") && !name.contains("notenough") && !name.contains("empty");
        assert_eq!(loads.is_ok(), expected_to_load, "{name}: {loads:?}");
    }
}

#[test]
fn every_prefix_is_read_without_panic_or_hang() {
    for (name, bytes) in samples() {
        for len in 0..=bytes.len() {
            read_every_way(&name, &bytes[..len]);
        }
    }
}

#[test]
fn overwritten_bytes_are_read_without_panic_or_hang() {
    const REPLACEMENTS: [u8; 8] = [0x00, 0xff, b'\n', b' ', b'-', b'9', b'#', b'\\'];
    for (name, bytes) in samples() {
        // Every byte of small files; a spread of positions in larger ones.
        let step = (bytes.len() / 400).max(1);
        let mut copy = bytes.clone();
        for at in (0..bytes.len()).step_by(step) {
            for replacement in REPLACEMENTS {
                copy[at] = replacement;
                read_every_way(&name, &copy);
            }
            copy[at] = bytes[at];
        }
    }
}
