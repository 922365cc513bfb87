//! A UTF-8 byte-order mark at the start of a text mesh file is accepted by every reader,
//! through the shared entry point (format detection and `read_mesh`).

use haphe::mesh::{Format, ReadOptions, read_mesh};

const BOM: &str = "\u{feff}";

fn tetrahedron_obj() -> String {
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n".into()
}

#[test]
fn every_text_format_reads_the_same_with_a_byte_order_mark() {
    let stl = "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n";
    let off = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    let ply = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    let obj = tetrahedron_obj();
    for (name, text, format) in [
        ("t.obj", obj.as_str(), Format::Obj),
        ("t.stl", stl, Format::Stl),
        ("t.off", off, Format::Off),
        ("t.ply", ply, Format::Ply),
    ] {
        let plain = read_mesh(name, text.as_bytes(), &ReadOptions::default()).expect(name);
        let marked = format!("{BOM}{text}");
        assert_eq!(
            Format::detect(name, marked.as_bytes()),
            Ok(format),
            "{name}"
        );
        // Detected from the content alone, too (no extension).
        assert_eq!(
            Format::detect("mesh", marked.as_bytes()),
            Ok(format),
            "{name}"
        );
        let read = read_mesh(name, marked.as_bytes(), &ReadOptions::default()).expect(name);
        assert_eq!(read, plain, "{name}");
        let given = ReadOptions {
            format: Some(format),
            ..ReadOptions::default()
        };
        assert_eq!(
            read_mesh(name, marked.as_bytes(), &given).expect(name),
            plain,
            "{name}"
        );
    }
}

/// A binary STL whose 80-byte header happens to start with the mark's bytes stays binary.
#[test]
fn a_binary_stl_header_starting_with_the_mark_stays_binary() {
    let mut bytes = vec![0u8; 84 + 50];
    bytes[..3].copy_from_slice(b"\xEF\xBB\xBF");
    bytes[80..84].copy_from_slice(&1u32.to_le_bytes());
    for (k, v) in [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
        .iter()
        .enumerate()
    {
        for (j, x) in v.iter().enumerate() {
            let at = 84 + 12 + 12 * k + 4 * j;
            bytes[at..at + 4].copy_from_slice(&x.to_le_bytes());
        }
    }
    let mesh = read_mesh("t.stl", &bytes, &ReadOptions::default()).expect("binary STL");
    assert_eq!(mesh.triangles.len(), 1);
}
