use super::*;

/// A unit square in z = 0 as two triangles, in ASCII.
const ASCII_SQUARE: &str = "ply\nformat ascii 1.0\ncomment square\n\
    element vertex 4\nproperty float x\nproperty float y\nproperty float z\n\
    element face 2\nproperty list uchar int vertex_indices\nend_header\n\
    0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n";

/// Appends a number to `bytes` in the byte order `big_endian` says.
macro_rules! put_number {
    ($bytes:expr, $big_endian:expr, $v:expr) => {
        if $big_endian {
            $bytes.extend($v.to_be_bytes())
        } else {
            $bytes.extend($v.to_le_bytes())
        }
    };
}

fn read(bytes: &[u8]) -> Result<Mesh, ReadErrorKind> {
    read_ply(bytes).map(|read| read.mesh)
}

/// Binary PLY of the unit square as one quad, with mixed property types: x double, y
/// short, z uchar, an ignored float, and a `list ushort uint vertex_indices`.
fn binary_square(big_endian: bool) -> Vec<u8> {
    let format = if big_endian {
        "binary_big_endian"
    } else {
        "binary_little_endian"
    };
    let mut bytes = format!(
        "ply\nformat {format} 1.0\nelement vertex 4\nproperty double x\nproperty short y\n\
         property uchar z\nproperty float confidence\nelement face 1\n\
         property list ushort uint vertex_indices\nend_header\n"
    )
    .into_bytes();
    macro_rules! put {
        ($v:expr) => {
            put_number!(bytes, big_endian, $v)
        };
    }
    for (x, y) in [(0.0f64, 0i16), (1.0, 0), (1.0, 1), (0.0, 1)] {
        put!(x);
        put!(y);
        bytes.push(0u8);
        put!(0.5f32);
    }
    put!(4u16);
    for i in 0..4u32 {
        put!(i);
    }
    bytes
}

#[test]
fn ascii_triangles() {
    let mesh = read(ASCII_SQUARE.as_bytes()).unwrap();
    assert_eq!(mesh.vertices.len(), 4);
    assert_eq!(mesh.triangles, vec![[0, 1, 2], [0, 2, 3]]);
    assert_eq!(mesh.vertices[2], DVec3::new(1.0, 1.0, 0.0));
    let crlf = ASCII_SQUARE.replace('\n', "\r\n");
    assert_eq!(read(crlf.as_bytes()).unwrap(), mesh);
}

#[test]
fn binary_little_and_big_endian_with_mixed_types() {
    for big_endian in [false, true] {
        let mesh = read(&binary_square(big_endian)).unwrap();
        assert_eq!(
            mesh.vertices[2],
            DVec3::new(1.0, 1.0, 0.0),
            "big endian {big_endian}"
        );
        assert_eq!(mesh.triangles, vec![[0, 1, 2], [0, 2, 3]]);
    }
}

#[test]
fn vertex_index_name_and_faces_before_vertices() {
    let text = "ply\nformat ascii 1.0\nelement face 1\nproperty list uchar uint vertex_index\n\
        element vertex 4\nproperty double x\nproperty double y\nproperty double z\nend_header\n\
        4 0 1 2 3\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n";
    let mesh = read(text.as_bytes()).unwrap();
    assert_eq!(mesh.triangles, vec![[0, 1, 2], [0, 2, 3]]);
}

#[test]
fn non_convex_polygon_is_ear_clipped() {
    let text = "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\nproperty float y\n\
        property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n\
        0 0 0\n3 0 0\n3 1 0\n1 1 0\n1 3 0\n0 3 0\n6 0 1 2 3 4 5\n";
    let mesh = read(text.as_bytes()).unwrap();
    assert_eq!(mesh.triangles.len(), 4);
    for t in 0..4 {
        let [a, b, c] = mesh.corners(t);
        assert!((b - a).cross(c - a).z > 0.0);
    }
}

#[test]
fn tristrips_alternate_winding_restart_and_skip_degenerates() {
    // A strip over a row of 3 quads (vertices 0..4 bottom, 4..8 top), then a restart and a
    // strip with a repeated index (a degenerate stitch).
    let text = "ply\nformat ascii 1.0\nelement vertex 8\nproperty float x\nproperty float y\n\
        property float z\nelement tristrips 1\nproperty list int int vertex_indices\nend_header\n\
        0 0 0\n1 0 0\n2 0 0\n3 0 0\n0 1 0\n1 1 0\n2 1 0\n3 1 0\n\
        12 0 4 1 5 -1 2 6 6 3 7 -1 -1\n";
    let mesh = read(text.as_bytes()).unwrap();
    // Run 1: (0 4 1), (4 1 5) flipped to (1 4 5). Run 2: (2 6 6) and (6 6 3) skipped,
    // (6 3 7) at an even position.
    assert_eq!(mesh.triangles, vec![[0, 4, 1], [1, 4, 5], [6, 3, 7]]);
    // The triangles of one run wind the same way (clockwise seen from +z here).
    for t in 0..2 {
        let [a, b, c] = mesh.corners(t);
        assert!((b - a).cross(c - a).z < 0.0, "triangle {t}");
    }
}

#[test]
fn strip_decoding_keeps_parity_across_skipped_triangles() {
    let mut out = Vec::new();
    decode_strip(&[0, 1, 2, 2, 3, 4], &mut out);
    // k = 0 (0 1 2); k = 1 (1 2 2) and k = 2 (2 2 3) skipped; k = 3 (2 3 4) flipped.
    assert_eq!(out, vec![[0, 1, 2], [3, 2, 4]]);
}

#[test]
fn indices_out_of_range_name_the_face_and_the_index_as_written() {
    let bad = ASCII_SQUARE.replace("3 0 2 3\n", "3 0 2 4\n");
    assert_eq!(
        read(bad.as_bytes()),
        Err(ReadErrorKind::IndexOutOfRange {
            at: Place::Face(1),
            index: 4,
            count: 4
        })
    );
    let negative = ASCII_SQUARE.replace("3 0 1 2\n", "3 0 -1 2\n");
    assert_eq!(
        read(negative.as_bytes()),
        Err(ReadErrorKind::IndexOutOfRange {
            at: Place::Face(0),
            index: -1,
            count: 4
        })
    );
    let strip = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n\
        property float z\nelement tristrips 2\nproperty list int int vertex_indices\nend_header\n\
        0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 -2\n";
    assert_eq!(
        read(strip.as_bytes()),
        Err(ReadErrorKind::IndexOutOfRange {
            at: Place::Strip(1),
            index: -2,
            count: 3
        })
    );
}

#[test]
fn too_few_corners() {
    let bad = ASCII_SQUARE.replace("3 0 2 3\n", "2 0 2\n");
    assert_eq!(
        read(bad.as_bytes()),
        Err(ReadErrorKind::TooFewCorners {
            at: Place::Face(1),
            corners: 2
        })
    );
}

#[test]
fn truncated_files_name_line_or_byte() {
    let cut = &ASCII_SQUARE[..ASCII_SQUARE.find("3 0 2 3").unwrap()];
    match read(cut.as_bytes()) {
        Err(ReadErrorKind::Truncated { at, message }) => {
            assert_eq!(at, Place::Line(16));
            assert!(message.contains("'face'"), "{message}");
        }
        other => panic!("{other:?}"),
    }
    let bytes = binary_square(false);
    // The header is 205 bytes; each vertex 8 + 2 + 1 + 4 = 15 bytes; the face starts at 265.
    let header = bytes.len() - 4 * 15 - 2 - 16;
    let cut = &bytes[..bytes.len() - 3];
    assert_eq!(
        read(cut),
        Err(ReadErrorKind::Truncated {
            at: Place::Byte((header + 60) as u64),
            message: "element 'face' announces 1 entries, the file ends in entry 0".into()
        })
    );
    // Cut inside the vertices: the element is known to need more bytes than are left.
    match read(&bytes[..header + 20]) {
        Err(ReadErrorKind::Truncated { at, .. }) => assert_eq!(at, Place::Byte(header as u64)),
        other => panic!("{other:?}"),
    }
}

#[test]
fn huge_counts_fail_fast_without_allocating() {
    let text = "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\n\
        property float x\nproperty float y\nproperty float z\nend_header\n\x00\x00";
    assert!(matches!(
        read(text.as_bytes()),
        Err(ReadErrorKind::Truncated { .. })
    ));
    let ascii = "ply\nformat ascii 1.0\nelement vertex 4000000000\n\
        property float x\nproperty float y\nproperty float z\nend_header\n0 0 0\n";
    assert!(matches!(
        read(ascii.as_bytes()),
        Err(ReadErrorKind::Truncated { .. })
    ));
    let empty_element = "ply\nformat binary_little_endian 1.0\nelement nothing 4000000000\n\
        end_header\n";
    assert!(matches!(
        read(empty_element.as_bytes()),
        Err(ReadErrorKind::Syntax {
            at: Place::Line(3),
            ..
        })
    ));
}

#[test]
fn header_errors_name_the_line() {
    let cases: [(&str, Place); 6] = [
        ("ply\nformat ascii 1.0\nelement vertex 1\n", Place::Line(4)),
        (
            "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float x\n\
          end_header\n",
            Place::Line(5),
        ),
        (
            "ply\nformat ascii 1.0\nelement a 0\nelement a 0\nend_header\n",
            Place::Line(4),
        ),
        ("ply\nformat ascii 9\nend_header\n", Place::Line(2)),
        (
            "ply\nformat ascii 1.0\nproperty float x\nend_header\n",
            Place::Line(3),
        ),
        ("plyx\nend_header\n", Place::Line(1)),
    ];
    for (text, place) in cases {
        let err = read(text.as_bytes()).unwrap_err();
        let at = match &err {
            ReadErrorKind::Syntax { at, .. } | ReadErrorKind::Truncated { at, .. } => *at,
            other => panic!("{text:?}: {other:?}"),
        };
        assert_eq!(at, place, "{text:?}: {err}");
    }
}

#[test]
fn bad_layouts_name_the_element() {
    let no_z = ASCII_SQUARE.replace("property float z\n", "");
    assert!(matches!(
        read(no_z.as_bytes()),
        Err(ReadErrorKind::Syntax {
            at: Place::Line(4),
            ..
        })
    ));
    let float_indices = ASCII_SQUARE.replace("list uchar int", "list uchar float");
    assert!(matches!(
        read(float_indices.as_bytes()),
        Err(ReadErrorKind::Syntax {
            at: Place::Line(8),
            ..
        })
    ));
}

#[test]
fn bad_ascii_entries_name_the_line() {
    let bad = ASCII_SQUARE.replace("1 1 0\n", "1 x 0\n");
    let err = read(bad.as_bytes()).unwrap_err();
    assert!(
        matches!(
            err,
            ReadErrorKind::Syntax {
                at: Place::Line(13),
                ..
            }
        ),
        "{err:?}"
    );
    assert!(!err.to_string().contains('\n'), "{err}");
    let short = ASCII_SQUARE.replace("1 1 0\n", "1 1\n");
    assert!(matches!(
        read(short.as_bytes()),
        Err(ReadErrorKind::Syntax {
            at: Place::Line(13),
            ..
        })
    ));
}

#[test]
fn non_finite_binary_vertex_names_the_vertex() {
    let mut bytes = binary_square(false);
    let header = bytes.len() - 4 * 15 - 2 - 16;
    bytes[header + 15..header + 23].copy_from_slice(&f64::NAN.to_le_bytes());
    assert_eq!(
        read(&bytes),
        Err(ReadErrorKind::NonFinite {
            at: Place::Vertex(1)
        })
    );
}

#[test]
fn no_faces_and_empty() {
    let points = "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n\
        property float z\nend_header\n0 0 0\n\n1 1 1\n\n";
    let mesh = read(points.as_bytes()).unwrap();
    assert_eq!((mesh.vertices.len(), mesh.triangles.len()), (2, 0));
    let mesh = read(b"ply\nformat ascii 1.0\nend_header\n").unwrap();
    assert!(mesh.vertices.is_empty() && mesh.triangles.is_empty());
    let no_index_list = "ply\nformat ascii 1.0\nelement face 0\nproperty uchar flags\nend_header\n";
    let mesh = read(no_index_list.as_bytes()).unwrap();
    assert!(mesh.vertices.is_empty() && mesh.triangles.is_empty());
    assert_eq!(read(b" \n"), Err(ReadErrorKind::Empty));
}

/// Whether every corner's texture coordinate is `uv_of` its position.
fn corners_follow(bytes: &[u8], uv_of: impl Fn(DVec3) -> [f32; 2]) {
    let read = read_ply(bytes).unwrap();
    let uvs = read.texture_coords.expect("texture coordinates");
    assert_eq!(uvs.len(), read.mesh.triangles.len());
    for (t, tri_uvs) in uvs.iter().enumerate() {
        assert_eq!(*tri_uvs, read.mesh.corners(t).map(&uv_of), "triangle {t}");
    }
}

/// The unit square of [`ASCII_SQUARE`] with texture coordinates `names` per vertex:
/// `(x / 2, 1 − y)`.
fn ascii_textured_square(names: [&str; 2]) -> String {
    format!(
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float {}\n\
         property float y\nproperty float z\nproperty double {}\n\
         element face 2\nproperty list uchar int vertex_indices\nend_header\n\
         0 0 0 0 1\n1 0.5 0 0 1\n1 0.5 1 0 0\n0 0 1 0 0\n3 0 1 2\n3 0 2 3\n",
        names[0], names[1]
    )
}

#[test]
fn ascii_texture_coordinates_follow_the_corners_under_each_name() {
    for names in [["u", "v"], ["s", "t"], ["texture_u", "texture_v"]] {
        corners_follow(ascii_textured_square(names).as_bytes(), |p| {
            [p.x as f32 / 2.0, 1.0 - p.y as f32]
        });
    }
    // Half a pair is no pair; no pair is no texture coordinates.
    let half = ascii_textured_square(["u", "t"]);
    assert_eq!(read_ply(half.as_bytes()).unwrap().texture_coords, None);
    assert_eq!(
        read_ply(ASCII_SQUARE.as_bytes()).unwrap().texture_coords,
        None
    );
}

#[test]
fn binary_texture_coordinates_of_a_quad_follow_its_triangles() {
    for big_endian in [false, true] {
        let mut bytes = format!(
            "ply\nformat {} 1.0\nelement vertex 4\nproperty float x\nproperty float y\n\
             property float z\nproperty float u\nproperty ushort v\nelement face 1\n\
             property list uchar int vertex_indices\nend_header\n",
            if big_endian {
                "binary_big_endian"
            } else {
                "binary_little_endian"
            }
        )
        .into_bytes();
        macro_rules! put {
            ($v:expr) => {
                put_number!(bytes, big_endian, $v)
            };
        }
        // u = 3x, v = 7y, as a float and an unsigned short.
        for (x, y) in [(0.0f32, 0.0f32), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)] {
            put!(x);
            put!(y);
            put!(0.0f32);
            put!(3.0 * x);
            put!(7 * y as u16);
        }
        bytes.push(4);
        for i in 0..4i32 {
            put!(i);
        }
        corners_follow(&bytes, |p| [3.0 * p.x as f32, 7.0 * p.y as f32]);
        assert_eq!(read(&bytes).unwrap().triangles.len(), 2);
    }
}

#[test]
fn a_non_finite_texture_coordinate_names_its_vertex() {
    // Past f32's range (ASCII PLY has no NaN).
    let text = ascii_textured_square(["u", "v"]).replace("1 0.5 1 0 0\n", "1 0.5 1 0 1e39\n");
    assert_eq!(
        read(text.as_bytes()),
        Err(ReadErrorKind::NonFiniteTextureCoordinate {
            at: Place::Vertex(2)
        })
    );
}
