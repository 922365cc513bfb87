//! Readers: OBJ, STL (ASCII and binary), PLY (ASCII and binary), OFF and glTF 2.0 (`.gltf`
//! and `.glb`), from bytes.
//!
//! [`read_mesh`] detects the format from the content (the file name is only a hint),
//! triangulates polygons, scales to metres and welds duplicate vertices. Every error names
//! the file and the place ([`ReadError`]). A glTF file is read as its default scene
//! flattened into one mesh in world coordinates; [`read_gltf`] keeps its nodes apart.

pub mod gltf;
mod obj;
mod off;
mod ply;
pub(crate) mod polygon;
mod stl;
mod text;
mod textured;
mod units;

pub use units::{
    LARGEST_LIKELY_SPAN_M, SMALLEST_LIKELY_SPAN_M, UNIT_NAMES, Units, UnitsHint, units_hint,
};

use self::gltf::{NoSideCars, Resolve};
use self::text::{skip_ascii_whitespace, starts_with_word};
pub(crate) use self::textured::TexturedMesh;
use super::{Mesh, ReadError, ReadErrorKind, Weld, WeldStats, weld};

/// A mesh file format.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Format {
    /// Wavefront OBJ (text): `v` and `f` statements, polygons, negative indices, groups.
    Obj,
    /// STL, ASCII or binary (told apart by content, not by the first word).
    Stl,
    /// PLY, ASCII or binary little/big endian; faces as index lists or triangle strips.
    Ply,
    /// Object File Format (text), with or without counts on the `OFF` line.
    Off,
    /// glTF 2.0: a `.gltf` (JSON) or a `.glb` (binary), its default scene flattened into
    /// one mesh in world coordinates (`read_gltf`).
    Gltf,
}

impl Format {
    /// Detects the format from the content, using the file name's extension only to break a
    /// tie (an OBJ and an OFF file can both start with a comment).
    ///
    /// # Errors
    /// [`ReadErrorKind::Empty`] for no bytes, [`ReadErrorKind::UnknownFormat`] when nothing
    /// matches.
    pub fn detect(name: &str, bytes: &[u8]) -> Result<Format, ReadErrorKind> {
        let bytes = without_byte_order_mark(bytes);
        let text_start = skip_ascii_whitespace(bytes);
        if text_start.is_empty() {
            return Err(ReadErrorKind::Empty);
        }
        if bytes.starts_with(gltf::GLB_MAGIC) || gltf_json(text_start, name) {
            return Ok(Format::Gltf);
        }
        if stl::looks_binary(bytes) || starts_with_word(text_start, b"solid") {
            return Ok(Format::Stl);
        }
        if text_start.starts_with(b"ply") {
            return Ok(Format::Ply);
        }
        if is_off_keyword(text_start) {
            return Ok(Format::Off);
        }
        let extension = name
            .rsplit_once('.')
            .map(|(_, e)| e.to_ascii_lowercase())
            .unwrap_or_default();
        match extension.as_str() {
            "obj" => Ok(Format::Obj),
            "stl" => Ok(Format::Stl),
            "ply" => Ok(Format::Ply),
            "off" => Ok(Format::Off),
            "gltf" | "glb" => Ok(Format::Gltf),
            _ if obj::looks_like_obj(bytes) => Ok(Format::Obj),
            _ => Err(ReadErrorKind::UnknownFormat {
                reason: format!(
                    "no STL, PLY, OFF or glTF signature and no OBJ statements (extension '{extension}')"
                ),
            }),
        }
    }
}

/// Whether the text is a glTF JSON document: an object that names its `asset` (every
/// glTF has one) near the start, or any JSON object in a file named `.gltf`.
fn gltf_json(text: &[u8], name: &str) -> bool {
    const LOOK_AHEAD_BYTES: usize = 1 << 16;
    text.starts_with(b"{")
        && (name.to_ascii_lowercase().ends_with(".gltf")
            || text[..text.len().min(LOOK_AHEAD_BYTES)]
                .windows(7)
                .any(|w| w == b"\"asset\""))
}

/// Whether the text starts with an OFF keyword: `OFF` with optional prefixes (`ST`, `C`,
/// `N`, `4`, `n`: texture, colour, normal, 4D, n-dimensional), such as `COFF` or `NOFF`,
/// possibly glued to the counts (`OFF8 6 12`).
fn is_off_keyword(text: &[u8]) -> bool {
    let word_end = text
        .iter()
        .position(|b| !b.is_ascii_alphanumeric())
        .unwrap_or(text.len());
    let word = text[..word_end].to_ascii_uppercase();
    let Some(at) = word.windows(3).position(|w| w == b"OFF") else {
        return false;
    };
    let prefix_ok = word[..at]
        .iter()
        .all(|b| matches!(b, b'S' | b'T' | b'C' | b'N' | b'4'));
    let rest_ok = word[at + 3..].iter().all(u8::is_ascii_digit);
    prefix_ok && rest_ok && at <= 5
}

/// `bytes` without a leading UTF-8 byte-order mark, which some editors write at the start
/// of text files; a binary STL (whose 80-byte header may start with anything) is kept as
/// it is.
pub(crate) fn without_byte_order_mark(bytes: &[u8]) -> &[u8] {
    match bytes.strip_prefix(b"\xEF\xBB\xBF".as_slice()) {
        Some(rest) if !stl::looks_binary(bytes) => rest,
        _ => bytes,
    }
}

/// How to read a mesh file.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ReadOptions {
    /// The file's length unit; coordinates are scaled to metres once, here.
    pub units: Units,
    /// How duplicate vertices are merged after reading.
    pub weld: Weld,
    /// The format, or `None` to detect it from the content.
    pub format: Option<Format>,
}

/// Reads a mesh from the bytes of a file named `file` (the name is used in errors and as a
/// hint for the format).
///
/// Polygons are triangulated, coordinates are scaled to metres and vertices welded as
/// `options` say; vertices no face uses are dropped.
///
/// # Errors
/// A [`ReadError`] naming `file` and the place (line, byte, face or vertex) of the first
/// problem: unknown format, syntax, truncation, indices out of range, non-finite
/// coordinates, faces with fewer than three corners, or no faces at all.
///
/// # Examples
/// ```
/// use haphe::mesh::{read_mesh, ReadOptions};
/// let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
/// let mesh = read_mesh("tri.obj", obj, &ReadOptions::default()).unwrap();
/// assert_eq!(mesh.triangles.len(), 1);
///
/// let err = read_mesh("bad.obj", b"v 0 0 0\nf 1 2 9\n", &ReadOptions::default()).unwrap_err();
/// assert_eq!(err.to_string(), "bad.obj: line 2: vertex index 9 is out of range (the file has 1 vertices)");
/// ```
pub fn read_mesh(file: &str, bytes: &[u8], options: &ReadOptions) -> Result<Mesh, ReadError> {
    read_unwelded(file, bytes, options).map(|mesh| weld(&mesh, options.weld).0)
}

/// A mesh file read and welded, with what was found on the way.
#[derive(Debug, Clone)]
pub struct ReadMesh {
    /// The welded mesh.
    pub mesh: Mesh,
    /// The format (detected unless the options gave one).
    pub format: Format,
    /// What welding did.
    pub weld: WeldStats,
    /// The texture coordinates `[u, v]` of each triangle's corners: entry `t` belongs to
    /// `mesh.triangles[t]`, its corners in that triangle's order (polygons triangulated as
    /// their positions are; welding keeps every triangle). Read from OBJ `vt` (through the
    /// `v/vt` and `v/vt/vn` corner forms), PLY per-vertex `u, v`, `s, t` or
    /// `texture_u, texture_v`, and glTF `TEXCOORD_0`. One convention for every format: `v`
    /// points up the image (`v = 0` is its bottom row, as in OBJ and PLY); glTF, whose `v`
    /// points down (`v = 0` is the top row), is turned over on reading (`v ↦ 1 − v`), so a
    /// model textured the same way in two formats reads the same.
    ///
    /// `None` for a file without texture coordinates, and for a file where only some
    /// corners have one (an OBJ face without `vt`, a glTF primitive without `TEXCOORD_0`):
    /// that is not an error, the mesh is read without them.
    pub texture_coords: Option<Vec<[[f32; 2]; 3]>>,
}

/// Like [`read_mesh`], also saying which format was read and what welding did (what the
/// front ends report).
///
/// # Errors
/// As [`read_mesh`], and [`ReadErrorKind::Empty`] or [`ReadErrorKind::UnknownFormat`]
/// when no format was given and none is recognised.
pub fn read_mesh_with_stats(
    file: &str,
    bytes: &[u8],
    options: &ReadOptions,
) -> Result<ReadMesh, ReadError> {
    read_mesh_resolving(file, bytes, options, &mut NoSideCars)
}

/// Like [`read_mesh_with_stats`], fetching the side-car files a `.gltf` refers to through
/// `resolver` (what a front end that read the file from a path uses).
///
/// # Errors
/// As [`read_mesh_with_stats`], and a side-car file the resolver cannot fetch.
pub fn read_mesh_resolving(
    file: &str,
    bytes: &[u8],
    options: &ReadOptions,
    resolver: &mut dyn Resolve,
) -> Result<ReadMesh, ReadError> {
    let format = match options.format {
        Some(f) => f,
        None => Format::detect(file, bytes).map_err(|kind| ReadError {
            file: file.to_owned(),
            kind,
        })?,
    };
    let options = ReadOptions {
        format: Some(format),
        ..*options
    };
    let raw = read_textured(file, bytes, &options, resolver)?;
    // Welding renumbers vertices and keeps every triangle, in order.
    let (mesh, weld) = weld(&raw.mesh, options.weld);
    Ok(ReadMesh {
        mesh,
        format,
        weld,
        texture_coords: raw.texture_coords,
    })
}

/// Like [`read_mesh`] but without welding: the mesh exactly as the file indexes it (scaled
/// to metres, vertices no face uses kept).
///
/// # Errors
/// As [`read_mesh`].
pub fn read_unwelded(file: &str, bytes: &[u8], options: &ReadOptions) -> Result<Mesh, ReadError> {
    read_unwelded_with(file, bytes, options, &mut NoSideCars)
}

/// Like [`read_unwelded`], fetching the side-car files a `.gltf` refers to through
/// `resolver` (the other formats need none).
///
/// # Errors
/// As [`read_mesh`], and a side-car file the resolver cannot fetch.
pub fn read_unwelded_with(
    file: &str,
    bytes: &[u8],
    options: &ReadOptions,
    resolver: &mut dyn Resolve,
) -> Result<Mesh, ReadError> {
    read_textured(file, bytes, options, resolver).map(|read| read.mesh)
}

/// [`read_unwelded_with`], with the texture coordinates of the corners.
fn read_textured(
    file: &str,
    bytes: &[u8],
    options: &ReadOptions,
    resolver: &mut dyn Resolve,
) -> Result<TexturedMesh, ReadError> {
    let fail = |kind| ReadError {
        file: file.to_owned(),
        kind,
    };
    let scale = options.units.metres_per_unit();
    if !(scale.is_finite() && scale > 0.0) {
        return Err(fail(ReadErrorKind::Syntax {
            at: super::Place::Header,
            message: format!("the unit factor {scale} is not a positive finite number"),
        }));
    }
    let bytes = without_byte_order_mark(bytes);
    let format = match options.format {
        Some(f) => f,
        None => Format::detect(file, bytes).map_err(fail)?,
    };
    let TexturedMesh {
        mut mesh,
        texture_coords,
    } = match format {
        Format::Obj => obj::read_obj(bytes),
        Format::Stl => stl::read_stl(bytes).map(TexturedMesh::from),
        Format::Ply => ply::read_ply(bytes),
        Format::Off => off::read_off(bytes).map(TexturedMesh::from),
        Format::Gltf => {
            // Scaled to metres by the reader (translations too); weld as for the others.
            let scene = gltf::read_gltf(file, bytes, options.units, resolver)?;
            let read = scene.flatten_textured();
            read.mesh.check_indices_and_finite().map_err(fail)?;
            return Ok(read);
        }
    }
    .map_err(fail)?;
    if mesh.triangles.is_empty() {
        return Err(fail(ReadErrorKind::NoFaces {
            vertices: mesh.vertices.len(),
        }));
    }
    if scale != 1.0 {
        for p in &mut mesh.vertices {
            *p *= scale;
        }
    }
    // Readers check as they go, with lines; this is the backstop (a scaled huge value can
    // overflow to infinity).
    mesh.check_indices_and_finite().map_err(fail)?;
    Ok(TexturedMesh {
        mesh,
        texture_coords,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn off_variants_are_detected_from_the_content() {
        for header in [
            "OFF\n",
            "COFF\n",
            "NOFF\n",
            "STOFF\n",
            "CNOFF\n",
            "4OFF\n",
            "off\n",
            "OFF8 6 12\n",
        ] {
            assert_eq!(
                Format::detect("mesh.txt", header.as_bytes()),
                Ok(Format::Off),
                "{header}"
            );
        }
        for other in ["OFFSET 1\n", "XOFF\n"] {
            assert_ne!(
                Format::detect("mesh.txt", other.as_bytes()),
                Ok(Format::Off),
                "{other}"
            );
        }
    }
}

#[cfg(test)]
mod texture_tests {
    use base64::Engine;
    use glam::DVec3;

    use super::*;

    /// Reads `bytes` welded and checks that every corner's texture coordinate is `uv_of`
    /// its position; returns the mesh.
    fn corners_follow(file: &str, bytes: &[u8], uv_of: impl Fn(DVec3) -> [f32; 2]) -> Mesh {
        let read = read_mesh_with_stats(file, bytes, &ReadOptions::default()).unwrap();
        let uvs = read.texture_coords.expect("texture coordinates");
        assert_eq!(uvs.len(), read.mesh.triangles.len());
        for (t, tri_uvs) in uvs.iter().enumerate() {
            assert_eq!(*tri_uvs, read.mesh.corners(t).map(&uv_of), "triangle {t}");
        }
        read.mesh
    }

    #[test]
    fn welding_keeps_the_texture_coordinates_with_their_triangles() {
        // Two quads sharing an edge, every vertex written twice (welded to 6), in cm.
        let obj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 1 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\n\
                   vt 0 0\nvt 0.5 0\nvt 0.5 1\nvt 0 1\nvt 1 0\nvt 1 1\n\
                   f 1/1 2/2 3/3 4/4\nf 5/2 6/5 7/6 8/3\n";
        let options = ReadOptions {
            units: Units::Centimetres,
            ..ReadOptions::default()
        };
        let read = read_mesh_with_stats("two.obj", obj.as_bytes(), &options).unwrap();
        assert_eq!(read.mesh.vertices.len(), 6);
        let uvs = read.texture_coords.unwrap();
        for (t, tri_uvs) in uvs.iter().enumerate() {
            let expected = read
                .mesh
                .corners(t)
                .map(|p| [(p.x * 50.0) as f32, (p.y * 100.0) as f32]);
            assert_eq!(*tri_uvs, expected, "triangle {t}");
        }
    }

    /// A glTF quad (indexed, `TEXCOORD_0` as normalised unsigned bytes) and a triangle
    /// (not indexed, `TEXCOORD_0` as floats unless `second_without`), both with u = x and
    /// glTF's v = 1 − y, in one mesh placed by a node that mirrors x.
    fn textured_gltf(second_without: bool) -> String {
        let mut buffer = Vec::new();
        for p in [[0f32, 0., 0.], [1., 0., 0.], [1., 1., 0.], [0., 1., 0.]] {
            buffer.extend(p.iter().flat_map(|c| c.to_le_bytes()));
        }
        for i in [0u16, 1, 2, 0, 2, 3] {
            buffer.extend(i.to_le_bytes());
        }
        for [x, y] in [[0u8, 0], [1, 0], [1, 1], [0, 1]] {
            buffer.extend([255 * x, 255 * (1 - y)]);
        }
        let triangle = [[0f32, 0., 1.], [0.5, 0., 1.], [0., 0.25, 1.]];
        for p in triangle {
            buffer.extend(p.iter().flat_map(|c| c.to_le_bytes()));
        }
        for p in triangle {
            buffer.extend([p[0], 1.0 - p[1]].iter().flat_map(|c| c.to_le_bytes()));
        }
        assert_eq!(buffer.len(), 128);
        let data = base64::engine::general_purpose::STANDARD.encode(&buffer);
        let second_attributes = if second_without {
            r#"{"POSITION": 3}"#
        } else {
            r#"{"POSITION": 3, "TEXCOORD_0": 4}"#
        };
        format!(
            r#"{{"asset": {{"version": "2.0"}}, "scene": 0, "scenes": [{{"nodes": [0]}}],
            "nodes": [{{"mesh": 0, "scale": [-1, 1, 1]}}],
            "meshes": [{{"primitives": [
                {{"attributes": {{"POSITION": 0, "TEXCOORD_0": 2}}, "indices": 1}},
                {{"attributes": {second_attributes}}}]}}],
            "buffers": [{{"byteLength": 128, "uri": "data:application/octet-stream;base64,{data}"}}],
            "bufferViews": [
                {{"buffer": 0, "byteOffset": 0, "byteLength": 48}},
                {{"buffer": 0, "byteOffset": 48, "byteLength": 12}},
                {{"buffer": 0, "byteOffset": 60, "byteLength": 8}},
                {{"buffer": 0, "byteOffset": 68, "byteLength": 36}},
                {{"buffer": 0, "byteOffset": 104, "byteLength": 24}}],
            "accessors": [
                {{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                  "min": [0, 0, 0], "max": [1, 1, 0]}},
                {{"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"}},
                {{"bufferView": 2, "componentType": 5121, "normalized": true, "count": 4,
                  "type": "VEC2"}},
                {{"bufferView": 3, "componentType": 5126, "count": 3, "type": "VEC3",
                  "min": [0, 0, 1], "max": [0.5, 0.25, 1]}},
                {{"bufferView": 4, "componentType": 5126, "count": 3, "type": "VEC2"}}]}}"#
        )
    }

    #[test]
    fn gltf_texture_coordinates_follow_the_corners_with_v_turned_up() {
        // Placed with x mirrored (the triangles turned over): u = −x in the world, and v
        // = y once glTF's downward v is turned up.
        let gltf = textured_gltf(false);
        let mesh = corners_follow("quad.gltf", gltf.as_bytes(), |p| {
            [(-p.x) as f32, p.y as f32]
        });
        assert_eq!(mesh.triangles.len(), 3);
        let without = textured_gltf(true);
        let read =
            read_mesh_with_stats("quad.gltf", without.as_bytes(), &ReadOptions::default()).unwrap();
        assert_eq!(read.mesh.triangles.len(), 3);
        assert_eq!(read.texture_coords, None);
    }

    #[test]
    fn gltf_texture_coordinates_must_match_the_positions() {
        let gltf = textured_gltf(false).replace(
            r#""count": 3, "type": "VEC2""#,
            r#""count": 2, "type": "VEC2""#,
        );
        let err = read_mesh_with_stats("quad.gltf", gltf.as_bytes(), &ReadOptions::default())
            .unwrap_err();
        assert_eq!(
            err.to_string(),
            "quad.gltf: mesh 0, primitive 1, accessor 4 (TEXCOORD_0): 2 texture coordinates \
             for 3 positions"
        );
    }

    #[test]
    fn formats_without_texture_coordinates_read_none() {
        let stl = b"solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n\
                    vertex 0 1 0\nendloop\nendfacet\nendsolid t\n";
        let off = b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
        for (file, bytes) in [("t.stl", &stl[..]), ("t.off", &off[..])] {
            let read = read_mesh_with_stats(file, bytes, &ReadOptions::default()).unwrap();
            assert_eq!(read.texture_coords, None, "{file}");
        }
    }
}
