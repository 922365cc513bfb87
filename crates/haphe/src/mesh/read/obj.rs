//! Wavefront OBJ reader.
//!
//! Reads `v x y z [w] [r g b]` (only `x y z` are used; a weight or vertex colours, even NaN
//! ones, are ignored), `vt u [v] [w]` (texture coordinates: `u` and `v`, `v` 0 when left
//! out) and `f` with the `v`, `v/vt`, `v//vn` and `v/vt/vn` corner forms, 1-based or
//! negative (relative) indices, and polygons of any size (triangulated, see
//! [`super::polygon`]). The texture coordinates of the corners follow their triangles; a
//! file where some corner has none gives none at all. Everything else — `vn`, `o`, `g`,
//! `s`, `usemtl`, `mtllib`, lines `l`, points `p`, unknown statements — is skipped. Comments (`#` to the end of the
//! line), CRLF line ends, tabs and line continuation with a trailing backslash are handled.
//!
//! Why not `tobj`: it reports parse errors without a line number, and DESIGN §7 requires
//! every error to say where it is; it also splits the file into per-group meshes with their
//! own index spaces, which we would have to merge back into one vertex list.
//!
//! The reader works on bytes with no allocation per token, so a 3.6 MB scan is read in a few
//! tens of milliseconds in a release build.

use glam::DVec3;

use super::polygon::Triangulator;
use super::text::{Lines, show, tokens};
use super::textured::TexturedMesh;
use crate::mesh::{Mesh, Place, ReadErrorKind};

/// A corner without a texture coordinate (`v` or `v//vn`).
const NO_TEXTURE: u32 = u32::MAX;

/// Statements `looks_like_obj` accepts, besides comments and blank lines.
const OBJ_KEYWORDS: &[&[u8]] = &[
    b"v",
    b"vt",
    b"vn",
    b"vp",
    b"f",
    b"fo",
    b"l",
    b"p",
    b"o",
    b"g",
    b"s",
    b"mg",
    b"usemtl",
    b"mtllib",
    b"usemap",
    b"maplib",
    b"lod",
    b"shadow_obj",
    b"trace_obj",
    b"cstype",
    b"deg",
    b"bmat",
    b"step",
    b"curv",
    b"curv2",
    b"surf",
    b"parm",
    b"trim",
    b"hole",
    b"scrv",
    b"sp",
    b"end",
    b"con",
    b"bevel",
    b"c_interp",
    b"d_interp",
    b"ctech",
    b"stech",
];

/// How many bytes `looks_like_obj` inspects.
const SNIFF_BYTES: usize = 64 * 1024;

/// The faces read so far: corners as 0-based vertex indices, not yet checked against the
/// vertex count (OBJ allows a face to name a vertex defined further down).
#[derive(Default)]
struct Faces {
    /// All corners, face after face.
    corners: Vec<u32>,
    /// End of each face in `corners`.
    ends: Vec<usize>,
    /// The line each face starts on.
    lines: Vec<usize>,
    /// The largest corner index of each face.
    max_corner: Vec<u32>,
    /// The texture coordinate of each corner (0-based, not yet checked against the count),
    /// or [`NO_TEXTURE`].
    texture: Vec<u32>,
    /// The largest texture coordinate index of each face, if it names any.
    max_texture: Vec<Option<u32>>,
}

/// Reads OBJ bytes into a mesh in file units, with the texture coordinates of its
/// triangles' corners when every corner has one.
///
/// # Errors
/// With the line: malformed numbers or indices, index 0 or out of range (vertex or texture
/// coordinate), a face with fewer than three corners, a non-finite position or texture
/// coordinate. [`ReadErrorKind::Empty`] when the file holds no statement at all (only blank
/// lines and comments).
pub(super) fn read_obj(bytes: &[u8]) -> Result<TexturedMesh, ReadErrorKind> {
    let mut vertices: Vec<DVec3> = Vec::new();
    let mut texture: Vec<[f32; 2]> = Vec::new();
    let mut faces = Faces::default();
    let mut statements = 0usize;
    let mut joined: Vec<u8> = Vec::new();
    let mut lines = Lines::new(bytes, 1);
    while let Some((first_line, mut physical)) = lines.next_line() {
        let logical: &[u8] = if continues(physical) {
            // Join the continued lines (rare) into scratch space.
            joined.clear();
            loop {
                if !continues(physical) {
                    joined.extend_from_slice(physical);
                    break;
                }
                joined.extend_from_slice(without_continuation(physical));
                joined.push(b' ');
                match lines.next_line() {
                    Some((_, next)) => physical = next,
                    None => break,
                }
            }
            &joined
        } else {
            physical
        };
        let logical = match logical.iter().position(|&b| b == b'#') {
            Some(hash) => &logical[..hash],
            None => logical,
        };
        let mut tokens = tokens(logical);
        let Some(keyword) = tokens.next() else {
            continue;
        };
        statements += 1;
        match keyword {
            b"v" => vertices.push(parse_vertex(tokens, first_line, vertices.len())?),
            b"vt" => texture.push(parse_texture(tokens, first_line, texture.len())?),
            b"f" => parse_face(
                tokens,
                first_line,
                [vertices.len(), texture.len()],
                &mut faces,
            )?,
            _ => {}
        }
    }
    if statements == 0 {
        return Err(ReadErrorKind::Empty);
    }
    triangulate_faces(&faces, vertices, &texture)
}

/// True when the bytes look like OBJ statements: among the first non-comment lines, only
/// OBJ keywords, and at least one `v` or `f` statement.
pub(super) fn looks_like_obj(bytes: &[u8]) -> bool {
    let head = &bytes[..bytes.len().min(SNIFF_BYTES)];
    let mut lines = Lines::new(head, 1);
    let mut geometry = false;
    while let Some((_, line)) = lines.next_line() {
        let line = match line.iter().position(|&b| b == b'#') {
            Some(hash) => &line[..hash],
            None => line,
        };
        let Some(keyword) = tokens(line).next() else {
            continue;
        };
        if !OBJ_KEYWORDS.contains(&keyword) {
            // The last line may be cut by the sniff limit.
            return geometry && lines.at_end() && head.len() < bytes.len();
        }
        geometry |= keyword == b"v" || keyword == b"f";
    }
    geometry
}

/// True when a physical line ends with a backslash (before trailing white space).
fn continues(line: &[u8]) -> bool {
    line.trim_ascii_end().last() == Some(&b'\\')
}

/// A continued line without its trailing backslash.
fn without_continuation(line: &[u8]) -> &[u8] {
    let trimmed = line.trim_ascii_end();
    &trimmed[..trimmed.len().saturating_sub(1)]
}

/// Parses a decimal floating-point token (Rust syntax: also `inf` and `nan`).
fn parse_f64(token: &[u8]) -> Option<f64> {
    std::str::from_utf8(token).ok()?.parse().ok()
}

/// Parses an optionally signed decimal integer without allocating.
fn parse_i64(token: &[u8]) -> Option<i64> {
    let (negative, digits) = match token.split_first() {
        Some((b'-', rest)) => (true, rest),
        Some((b'+', rest)) => (false, rest),
        _ => (false, token),
    };
    if digits.is_empty() {
        return None;
    }
    let mut value: i64 = 0;
    for &d in digits {
        if !d.is_ascii_digit() {
            return None;
        }
        value = value.checked_mul(10)?.checked_add(i64::from(d - b'0'))?;
    }
    Some(if negative { -value } else { value })
}

/// `v x y z [w] [r g b]`: the position; the rest is ignored.
fn parse_vertex<'a>(
    mut tokens: impl Iterator<Item = &'a [u8]>,
    line: usize,
    count: usize,
) -> Result<DVec3, ReadErrorKind> {
    if count >= u32::MAX as usize {
        return Err(ReadErrorKind::TooLarge {
            at: Place::Line(line),
            message: format!("more than {} vertices", u32::MAX),
        });
    }
    let mut xyz = [0.0; 3];
    for (axis, value) in xyz.iter_mut().enumerate() {
        let Some(token) = tokens.next() else {
            return Err(ReadErrorKind::Syntax {
                at: Place::Line(line),
                message: format!("a vertex needs 3 coordinates, found {axis}"),
            });
        };
        *value = parse_f64(token).ok_or_else(|| ReadErrorKind::Syntax {
            at: Place::Line(line),
            message: format!("'{}' is not a number", show(token)),
        })?;
    }
    let p = DVec3::from_array(xyz);
    if !p.is_finite() {
        return Err(ReadErrorKind::NonFinite {
            at: Place::Line(line),
        });
    }
    Ok(p)
}

/// `vt u [v] [w]`: `u` and `v` (0 when left out); `w` is ignored.
fn parse_texture<'a>(
    mut tokens: impl Iterator<Item = &'a [u8]>,
    line: usize,
    count: usize,
) -> Result<[f32; 2], ReadErrorKind> {
    if count >= NO_TEXTURE as usize {
        return Err(ReadErrorKind::TooLarge {
            at: Place::Line(line),
            message: format!("more than {NO_TEXTURE} texture coordinates"),
        });
    }
    let mut uv = [0.0f32; 2];
    for (axis, value) in uv.iter_mut().enumerate() {
        let Some(token) = tokens.next() else {
            if axis == 0 {
                return Err(ReadErrorKind::Syntax {
                    at: Place::Line(line),
                    message: "a texture coordinate needs at least 1 number, found 0".to_owned(),
                });
            }
            break;
        };
        let read = parse_f64(token).ok_or_else(|| ReadErrorKind::Syntax {
            at: Place::Line(line),
            message: format!("'{}' is not a number", show(token)),
        })?;
        // Past f32's range is infinite too.
        *value = read as f32;
        if !value.is_finite() {
            return Err(ReadErrorKind::NonFiniteTextureCoordinate {
                at: Place::Line(line),
            });
        }
    }
    Ok(uv)
}

/// An OBJ index as written (1-based, or negative: relative to the `count` read so far),
/// 0-based. A positive index may name an element defined further down: checked at the end.
///
/// # Errors
/// `out_of_range` for index 0 or one before the first element.
fn resolve_index(
    written: i64,
    count: usize,
    out_of_range: impl Fn() -> ReadErrorKind,
) -> Result<u32, ReadErrorKind> {
    let resolved = match written {
        0 => return Err(out_of_range()),
        w if w > 0 => w - 1,
        w => count as i64 + w,
    };
    u32::try_from(resolved)
        .ok()
        .filter(|&i| i != NO_TEXTURE)
        .ok_or_else(out_of_range)
}

/// `f v1 v2 v3 ...` with `v`, `v/vt`, `v//vn` or `v/vt/vn` corners; `counts` are the
/// vertices and texture coordinates read so far.
fn parse_face<'a>(
    tokens: impl Iterator<Item = &'a [u8]>,
    line: usize,
    counts: [usize; 2],
    faces: &mut Faces,
) -> Result<(), ReadErrorKind> {
    let [vertex_count, texture_count] = counts;
    let start = faces.corners.len();
    let mut max_corner = 0u32;
    let mut max_texture: Option<u32> = None;
    for token in tokens {
        let mut parts = token.split(|&b| b == b'/');
        let position = parts.next().unwrap_or(token);
        let written = parse_i64(position).ok_or_else(|| ReadErrorKind::Syntax {
            at: Place::Line(line),
            message: format!("'{}' is not a vertex index", show(token)),
        })?;
        let corner = resolve_index(written, vertex_count, || ReadErrorKind::IndexOutOfRange {
            at: Place::Line(line),
            index: written,
            count: vertex_count,
        })?;
        max_corner = max_corner.max(corner);
        faces.corners.push(corner);
        let texture = match parts.next() {
            None | Some(b"") => NO_TEXTURE,
            Some(written) => {
                let written = parse_i64(written).ok_or_else(|| ReadErrorKind::Syntax {
                    at: Place::Line(line),
                    message: format!("'{}' is not a texture coordinate index", show(token)),
                })?;
                let t = resolve_index(written, texture_count, || {
                    ReadErrorKind::TextureIndexOutOfRange {
                        at: Place::Line(line),
                        index: written,
                        count: texture_count,
                    }
                })?;
                max_texture = Some(max_texture.map_or(t, |m| m.max(t)));
                t
            }
        };
        faces.texture.push(texture);
    }
    let corners = faces.corners.len() - start;
    if corners < 3 {
        return Err(ReadErrorKind::TooFewCorners {
            at: Place::Line(line),
            corners,
        });
    }
    faces.ends.push(faces.corners.len());
    faces.lines.push(line);
    faces.max_corner.push(max_corner);
    faces.max_texture.push(max_texture);
    Ok(())
}

/// Checks every face against the final vertex and texture coordinate counts and
/// triangulates, in file order; the corners' texture coordinates follow their triangles.
fn triangulate_faces(
    faces: &Faces,
    vertices: Vec<DVec3>,
    texture: &[[f32; 2]],
) -> Result<TexturedMesh, ReadErrorKind> {
    let count = vertices.len();
    if let Some(face) = faces.max_corner.iter().position(|&m| m as usize >= count) {
        return Err(ReadErrorKind::IndexOutOfRange {
            at: Place::Line(faces.lines[face]),
            index: i64::from(faces.max_corner[face]) + 1,
            count,
        });
    }
    if let Some((face, m)) = faces
        .max_texture
        .iter()
        .enumerate()
        .find_map(|(f, m)| m.filter(|&m| m as usize >= texture.len()).map(|m| (f, m)))
    {
        return Err(ReadErrorKind::TextureIndexOutOfRange {
            at: Place::Line(faces.lines[face]),
            index: i64::from(m) + 1,
            count: texture.len(),
        });
    }
    let capacity = faces.corners.len().saturating_sub(2 * faces.ends.len());
    let mut triangles = Vec::with_capacity(capacity);
    // Dropped at the first corner without a texture coordinate.
    let mut uvs = faces
        .texture
        .iter()
        .all(|&t| t != NO_TEXTURE)
        .then(|| Vec::with_capacity(capacity));
    let mut triangulator = Triangulator::default();
    let mut local = Vec::new();
    let mut start = 0;
    for (face, &end) in faces.ends.iter().enumerate() {
        local.clear();
        triangulator
            .triangulate_corners(&faces.corners[start..end], &vertices, &mut local)
            .map_err(|e| ReadErrorKind::PolygonTooComplex {
                at: Place::Line(faces.lines[face]),
                face,
                corners: e.corners,
            })?;
        let of = |list: &[u32], k: u32| list[start + k as usize];
        triangles.extend(local.iter().map(|t| t.map(|k| of(&faces.corners, k))));
        if let Some(uvs) = &mut uvs {
            uvs.extend(
                local
                    .iter()
                    .map(|t| t.map(|k| texture[of(&faces.texture, k) as usize])),
            );
        }
        start = end;
    }
    Ok(TexturedMesh {
        mesh: Mesh {
            vertices,
            triangles,
        },
        texture_coords: uvs,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(text: &str) -> Result<Mesh, ReadErrorKind> {
        read_obj(text.as_bytes()).map(|read| read.mesh)
    }

    fn read_uvs(text: &str) -> Option<Vec<[[f32; 2]; 3]>> {
        read_obj(text.as_bytes()).unwrap().texture_coords
    }

    const SQUARE: &str = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";

    #[test]
    fn triangle_and_quad() {
        let mesh = read(&format!("{SQUARE}f 1 2 3\nf 1 2 3 4\n")).unwrap();
        assert_eq!(mesh.vertices.len(), 4);
        assert_eq!(mesh.triangles, vec![[0, 1, 2], [0, 1, 2], [0, 2, 3]]);
    }

    #[test]
    fn all_corner_forms() {
        let text = format!(
            "{SQUARE}vt 0 0\nvn 0 0 1\nf 1/1 2/1 3/1\nf 1//1 3//1 4//1\nf 1/1/1 2/1/1 4/1/1\n"
        );
        let mesh = read(&text).unwrap();
        assert_eq!(mesh.triangles, vec![[0, 1, 2], [0, 2, 3], [0, 1, 3]]);
    }

    #[test]
    fn negative_indices_are_relative_to_the_vertices_so_far() {
        let mesh = read(&format!("{SQUARE}f -4 -3 -2 -1\nv 5 5 5\nf -1 -2 -3\n")).unwrap();
        assert_eq!(mesh.triangles, vec![[0, 1, 2], [0, 2, 3], [4, 3, 2]]);
    }

    #[test]
    fn non_convex_polygon_is_ear_clipped() {
        // An L: corner 4 (index 3) is reflex, so a fan from corner 1 would overlap.
        let text = "v 0 0 0\nv 3 0 0\nv 3 1 0\nv 1 1 0\nv 1 3 0\nv 0 3 0\nf 1 2 3 4 5 6\n";
        let mesh = read(text).unwrap();
        assert_eq!(mesh.triangles.len(), 4);
        let area: f64 = (0..4)
            .map(|t| {
                let [a, b, c] = mesh.corners(t);
                0.5 * (b - a).cross(c - a).z
            })
            .inspect(|&a| assert!(a > 0.0))
            .sum();
        assert!((area - 5.0).abs() < 1e-12);
    }

    /// Whether every corner's texture coordinate is `uv_of` its position.
    fn corners_follow(text: &str, uv_of: impl Fn(DVec3) -> [f32; 2]) {
        let read = read_obj(text.as_bytes()).unwrap();
        let uvs = read.texture_coords.expect("texture coordinates");
        assert_eq!(uvs.len(), read.mesh.triangles.len());
        for (t, tri_uvs) in uvs.iter().enumerate() {
            let expected = read.mesh.corners(t).map(&uv_of);
            assert_eq!(*tri_uvs, expected, "triangle {t}");
        }
    }

    #[test]
    fn texture_coordinates_follow_the_corners_of_a_quad() {
        // The texture coordinates listed in another order than the vertices, so that a
        // corner's vt index differs from its v index; u = x / 2, v = y.
        let text = format!(
            "{SQUARE}vt 0.5 1\nvt 0 0\nvt 0.5 0\nvt 0 1\n\
             f 1/2 2/3/1 3/1 4/4\nf -4/-3 -2/-4 -1/-1\n"
        );
        corners_follow(&text, |p| [p.x as f32 / 2.0, p.y as f32]);
        let read = read_obj(text.as_bytes()).unwrap();
        assert_eq!(read.mesh.triangles.len(), 3);
    }

    #[test]
    fn texture_coordinates_follow_an_ear_clipped_polygon() {
        // The L of `non_convex_polygon_is_ear_clipped`, u = x, v = y: the reflex corner
        // is cut around, and each corner keeps its own vt.
        let text = "v 0 0 0\nv 3 0 0\nv 3 1 0\nv 1 1 0\nv 1 3 0\nv 0 3 0\n\
                    vt 0 3\nvt 1 3\nvt 1 1\nvt 3 1\nvt 3 0\nvt 0 0\n\
                    f 1/6 2/5 3/4 4/3 5/2 6/1\n";
        corners_follow(text, |p| [p.x as f32, p.y as f32]);
    }

    #[test]
    fn texture_coordinates_may_come_after_the_faces_and_default_v_to_0() {
        corners_follow(
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1 2/2 3/3\nvt 0\nvt 2\nvt 0 0\n",
            |p| [2.0 * p.x as f32, 0.0],
        );
    }

    #[test]
    fn a_face_without_texture_coordinates_leaves_the_file_without() {
        for text in [
            format!("{SQUARE}vt 0 0\nf 1/1 2/1 3/1\nf 1 3 4\n"),
            format!("{SQUARE}vt 0 0\nf 1/1 2//1 3/1\n"),
            format!("{SQUARE}f 1 2 3\n"),
        ] {
            let read = read_obj(text.as_bytes()).unwrap();
            assert!(!read.mesh.triangles.is_empty());
            assert_eq!(read_uvs(&text), None, "{text}");
        }
    }

    #[test]
    fn bad_texture_coordinates_name_the_line() {
        assert_eq!(
            read(&format!("{SQUARE}vt 0 x\n")),
            Err(ReadErrorKind::Syntax {
                at: Place::Line(5),
                message: "'x' is not a number".to_owned()
            })
        );
        assert!(matches!(
            read(&format!("{SQUARE}vt\n")),
            Err(ReadErrorKind::Syntax {
                at: Place::Line(5),
                ..
            })
        ));
        for value in ["nan", "inf", "1e39"] {
            assert_eq!(
                read(&format!("{SQUARE}vt 0 {value}\n")),
                Err(ReadErrorKind::NonFiniteTextureCoordinate { at: Place::Line(5) }),
                "{value}"
            );
        }
        let err = read(&format!("{SQUARE}vt 0 0\n\nf 1/1 2/9 3/1\n")).unwrap_err();
        assert_eq!(
            err.to_string(),
            "line 7: texture coordinate index 9 is out of range (the file has 1 texture coordinates)"
        );
        assert_eq!(
            read(&format!("{SQUARE}vt 0 0\nf 1/1 2/-2 3/1\n")),
            Err(ReadErrorKind::TextureIndexOutOfRange {
                at: Place::Line(6),
                index: -2,
                count: 1
            })
        );
        assert_eq!(
            read(&format!("{SQUARE}vt 0 0\nf 1/1 2/0 3/1\n")),
            Err(ReadErrorKind::TextureIndexOutOfRange {
                at: Place::Line(6),
                index: 0,
                count: 1
            })
        );
        assert!(matches!(
            read(&format!("{SQUARE}vt 0 0\nf 1/1 2/a 3/1\n")),
            Err(ReadErrorKind::Syntax {
                at: Place::Line(6),
                ..
            })
        ));
    }

    #[test]
    fn crlf_tabs_comments_and_continuation() {
        let text =
            "# head\r\nv\t0 0 0 # trailing\r\nv 1 0 0\r\nv 0 1 \\\r\n 0\r\n\r\nf 1 2 \\\r\n3\r\n";
        let mesh = read(text).unwrap();
        assert_eq!(mesh.vertices[2], DVec3::new(0.0, 1.0, 0.0));
        assert_eq!(mesh.triangles, vec![[0, 1, 2]]);
    }

    #[test]
    fn continuation_keeps_the_first_line_number_and_counts_the_rest() {
        let err = read("v 0 0 \\\n0\nv 1 0 0\nv 0 1 0\nf 1 \\\n2 \\\n3\nf 1 2 7\n").unwrap_err();
        assert_eq!(
            err,
            ReadErrorKind::IndexOutOfRange {
                at: Place::Line(8),
                index: 7,
                count: 3
            }
        );
        let err = read("v 0 0 0\nf 1 \\\n2 \\\n3\n").unwrap_err();
        assert_eq!(
            err,
            ReadErrorKind::IndexOutOfRange {
                at: Place::Line(2),
                index: 3,
                count: 1
            }
        );
    }

    #[test]
    fn weights_colours_and_nan_colours_are_ignored() {
        let text = "v 0 0 0 1\nv 1 0 0 0.5 0.5 0.5\nv 0 1 0 nan nan nan\nf 1 2 3\n";
        let mesh = read(text).unwrap();
        assert_eq!(mesh.vertices[1], DVec3::X);
    }

    #[test]
    fn other_statements_are_ignored() {
        let text = "mtllib a.mtl\no thing\ng group\ns 1\nusemtl m\nv 0 0 0\nv 1 0 0\nv 0 1 0\n\
                    l 1 2\np 1\ncurv 0 1 1 2\nwhatever 1 2 3\nf 1 2 3\n";
        assert_eq!(read(text).unwrap().triangles.len(), 1);
    }

    #[test]
    fn index_zero_is_out_of_range() {
        let err = read("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n").unwrap_err();
        assert_eq!(
            err,
            ReadErrorKind::IndexOutOfRange {
                at: Place::Line(4),
                index: 0,
                count: 3
            }
        );
    }

    #[test]
    fn out_of_range_reports_the_index_as_written() {
        let err = read("v 0 0 0\nf 1 2 9\n").unwrap_err();
        assert_eq!(
            err.to_string(),
            "line 2: vertex index 9 is out of range (the file has 1 vertices)"
        );
        let err = read(&format!("{SQUARE}f 1 2 -5\n")).unwrap_err();
        assert_eq!(
            err,
            ReadErrorKind::IndexOutOfRange {
                at: Place::Line(5),
                index: -5,
                count: 4
            }
        );
        let err = read("v 0 0 0\nf 1 1 99999999999999999999\n").unwrap_err();
        assert!(
            matches!(
                err,
                ReadErrorKind::Syntax {
                    at: Place::Line(2),
                    ..
                }
            ),
            "{err:?}"
        );
    }

    #[test]
    fn forward_references_are_allowed() {
        let mesh = read("f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n").unwrap();
        assert_eq!(mesh.triangles, vec![[0, 1, 2]]);
    }

    #[test]
    fn too_few_corners() {
        let err = read("v 0 0 0\nv 1 0 0\nf 1// 2//\n").unwrap_err();
        assert_eq!(
            err,
            ReadErrorKind::TooFewCorners {
                at: Place::Line(3),
                corners: 2
            }
        );
    }

    #[test]
    fn bad_numbers_name_the_line() {
        for (text, line) in [
            ("v 0 0 x\n", 1),
            ("v 0 0\n", 1),
            ("v 0 0 0\n\nf 1 a 1\n", 3),
            ("v 0 0 0\nf 1 /2 1\n", 2),
            ("v 0 0 0\nf 1 - 1\n", 2),
        ] {
            match read(text) {
                Err(ReadErrorKind::Syntax { at, .. }) => {
                    assert_eq!(at, Place::Line(line), "{text}")
                }
                other => panic!("{text}: {other:?}"),
            }
        }
    }

    #[test]
    fn non_finite_positions_are_rejected() {
        for text in ["v 0 nan 0\n", "v 0 0 inf\n", "v 1e999 0 0\n"] {
            assert_eq!(
                read(text),
                Err(ReadErrorKind::NonFinite { at: Place::Line(1) })
            );
        }
    }

    #[test]
    fn vertices_without_faces_and_empty_files() {
        let mesh = read(SQUARE).unwrap();
        assert_eq!((mesh.vertices.len(), mesh.triangles.len()), (4, 0));
        assert_eq!(read(""), Err(ReadErrorKind::Empty));
        assert_eq!(read("# only\n\n  # comments\n"), Err(ReadErrorKind::Empty));
        // A backslash at the very end of the file.
        assert_eq!(read("v 0 0 0 \\").unwrap().vertices.len(), 1);
    }

    #[test]
    fn sniffing() {
        assert!(looks_like_obj(b"# c\nv 0 0 0\nf 1 1 1\n"));
        assert!(looks_like_obj(b"o x\r\nv\t0 0 0\r\n"));
        assert!(!looks_like_obj(b"# c\no x\n"));
        assert!(!looks_like_obj(b"v 0 0 0\nhello world\n"));
        assert!(!looks_like_obj(b"\x00\x01\x02"));
    }
}
