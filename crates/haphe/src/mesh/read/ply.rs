//! PLY reader (ASCII, binary little and big endian), through `ply-rs-bw`.
//!
//! - `vertex` elements give the positions: `x`, `y`, `z` of any numeric type, and texture
//!   coordinates: the first of the pairs `u, v`, `s, t`, `texture_u, texture_v` the header
//!   declares whole (any numeric type); other properties (normals, colours, confidence) are
//!   ignored.
//! - `face` elements give polygons through a `vertex_indices` (or `vertex_index`) list of any
//!   integer types; polygons are triangulated ([`super::polygon`]).
//! - `tristrips` elements give triangle strips through a `vertex_indices` list where `-1`
//!   restarts the strip; every second triangle of a strip is flipped back to the strip's
//!   winding, and degenerate strip triangles (a repeated index, used to stitch strips) are
//!   skipped.
//! - Other elements are read and dropped.
//!
//! `ply-rs-bw` parses the header and one entry at a time, so each error names its place: the
//! line of an ASCII entry, the byte offset of a binary one, the face or vertex for index and
//! coordinate errors. Before handing the header to it, a short scan of our own checks what
//! it would accept silently or turn into huge work: duplicate element or property names (it
//! keeps only one, which shifts every binary record after it), elements without properties
//! but with a count (nothing to read, so nothing stops the loop), and binary counts that
//! need more bytes than the file has.

use glam::DVec3;
use ply_rs_bw::parser::{Parser, Reader};
use ply_rs_bw::ply::{ElementDef, Encoding, PropertyType};

use super::polygon::Triangulator;
use super::text::skip_ascii_whitespace;
use crate::mesh::{Mesh, Place, ReadErrorKind};

mod entries;
mod header;
mod source;

use super::textured::{TexturedMesh, VertexTextureCoords, corner_texture_coords};
use entries::{IndexList, Skip, TEXTURE_NAMES, VertexEntry};
use source::{Source, map_parse_error};

/// Reads PLY bytes into a mesh in file units, with the texture coordinates of its
/// triangles' corners when its vertices have some.
///
/// # Errors
/// A malformed header (its line), a malformed or missing entry (its line in ASCII, its byte
/// offset in binary), an index out of range or a face with fewer than three corners (the
/// face or strip), a non-finite position or texture coordinate (the vertex),
/// [`ReadErrorKind::Empty`] for no content.
pub(super) fn read_ply(bytes: &[u8]) -> Result<TexturedMesh, ReadErrorKind> {
    if skip_ascii_whitespace(bytes).is_empty() {
        return Err(ReadErrorKind::Empty);
    }
    let scan = header::scan(bytes)?;
    let mut reader = Reader::new(bytes);
    let header = Parser::<Skip>::new()
        .read_header(&mut reader)
        .map_err(|e| map_parse_error(&e, Place::Header))?;
    let payload = reader.into_inner();
    let header_bytes = bytes.len() - payload.len();
    let mut source = match header.encoding {
        Encoding::Ascii => Source::Ascii {
            text: payload,
            pos: 0,
            line: bytes[..header_bytes]
                .iter()
                .filter(|&&b| b == b'\n')
                .count(),
        },
        encoding => Source::Binary {
            rest: payload,
            total: bytes.len(),
            big_endian: encoding == Encoding::BinaryBigEndian,
        },
    };
    let vertex_count = header.elements.get("vertex").map_or(0, |e| e.count);
    let mut reading = Reading {
        vertex_count,
        vertices: Vec::new(),
        texture: None,
        corners: Vec::new(),
        ends: Vec::new(),
        strip_triangles: Vec::new(),
    };
    for (name, def) in &header.elements {
        let declared = scan.element_place(name);
        header::check_element(def, declared, &source)?;
        match name.as_str() {
            "vertex" => reading.vertices(def, declared, &mut source)?,
            "face" => reading.faces(def, declared, &mut source)?,
            "tristrips" => reading.strips(def, declared, &mut source)?,
            _ => {
                let parser = Parser::<Skip>::new();
                for i in 0..def.count {
                    source.entry(&parser, def, i)?;
                }
            }
        }
    }
    reading.finish()
}

/// The mesh being read.
struct Reading {
    /// The vertex count the header announces (faces may come before the vertices).
    vertex_count: usize,
    vertices: Vec<DVec3>,
    /// The vertices' texture coordinates, when the `vertex` element has some.
    texture: Option<VertexTextureCoords>,
    /// Face corners, checked against `vertex_count`, face after face.
    corners: Vec<u32>,
    /// End of each face in `corners`.
    ends: Vec<usize>,
    /// Triangles decoded from strips.
    strip_triangles: Vec<[u32; 3]>,
}

impl Reading {
    fn vertices(
        &mut self,
        def: &ElementDef,
        declared: Place,
        source: &mut Source<'_>,
    ) -> Result<(), ReadErrorKind> {
        for axis in ["x", "y", "z"] {
            match def.properties.get(axis).map(|p| &p.data_type) {
                Some(PropertyType::Scalar(_)) => {}
                _ => {
                    return Err(ReadErrorKind::Syntax {
                        at: declared,
                        message: format!("element 'vertex' has no number property '{axis}'"),
                    });
                }
            }
        }
        if def.count > u32::MAX as usize {
            return Err(ReadErrorKind::TooLarge {
                at: declared,
                message: format!("{} vertices do not fit 32-bit indices", def.count),
            });
        }
        let scalar = |name: &str| {
            matches!(
                def.properties.get(name).map(|p| &p.data_type),
                Some(PropertyType::Scalar(_))
            )
        };
        let pair = TEXTURE_NAMES
            .iter()
            .position(|names| names.iter().all(|&n| scalar(n)));
        self.vertices.reserve(source.capacity_for(def.count));
        let mut texture = pair.map(|_| Vec::with_capacity(source.capacity_for(def.count)));
        let parser = Parser::<VertexEntry>::new();
        for i in 0..def.count {
            let entry = source.entry(&parser, def, i)?;
            let p = DVec3::from_array(entry.xyz);
            if !p.is_finite() {
                return Err(ReadErrorKind::NonFinite {
                    at: Place::Vertex(i),
                });
            }
            self.vertices.push(p);
            if let (Some(pair), Some(texture)) = (pair, &mut texture) {
                // Past f32's range is infinite too.
                let uv = entry.texture[pair].map(|x| x as f32);
                if !uv.iter().all(|x| x.is_finite()) {
                    return Err(ReadErrorKind::NonFiniteTextureCoordinate {
                        at: Place::Vertex(i),
                    });
                }
                texture.push(uv);
            }
        }
        self.texture = texture;
        Ok(())
    }

    fn faces(
        &mut self,
        def: &ElementDef,
        declared: Place,
        source: &mut Source<'_>,
    ) -> Result<(), ReadErrorKind> {
        if def.count == 0 {
            return Ok(()); // An empty face element may declare anything.
        }
        header::check_index_list(def, declared, &["vertex_indices", "vertex_index"])?;
        self.ends.reserve(source.capacity_for(def.count));
        let parser = Parser::<IndexList>::new();
        for face in 0..def.count {
            let list = source.entry(&parser, def, face)?.indices;
            if list.len() < 3 {
                return Err(ReadErrorKind::TooFewCorners {
                    at: Place::Face(face),
                    corners: list.len(),
                });
            }
            for &index in &list {
                let corner = self.check_index(index, Place::Face(face))?;
                self.corners.push(corner);
            }
            self.ends.push(self.corners.len());
        }
        Ok(())
    }

    fn strips(
        &mut self,
        def: &ElementDef,
        declared: Place,
        source: &mut Source<'_>,
    ) -> Result<(), ReadErrorKind> {
        if def.count == 0 {
            return Ok(());
        }
        header::check_index_list(def, declared, &["vertex_indices"])?;
        let parser = Parser::<IndexList>::new();
        for strip in 0..def.count {
            let list = source.entry(&parser, def, strip)?.indices;
            for run in list.split(|&i| i == -1) {
                let run = run
                    .iter()
                    .map(|&i| self.check_index(i, Place::Strip(strip)))
                    .collect::<Result<Vec<u32>, _>>()?;
                decode_strip(&run, &mut self.strip_triangles);
            }
        }
        Ok(())
    }

    /// A corner index checked against the announced vertex count.
    fn check_index(&self, index: i64, at: Place) -> Result<u32, ReadErrorKind> {
        match u32::try_from(index) {
            Ok(i) if (i as usize) < self.vertex_count => Ok(i),
            _ => Err(ReadErrorKind::IndexOutOfRange {
                at,
                index,
                count: self.vertex_count,
            }),
        }
    }

    /// Triangulates the faces (now that every vertex is known) and appends the strips; the
    /// corners take their vertices' texture coordinates.
    fn finish(self) -> Result<TexturedMesh, ReadErrorKind> {
        let mut triangles = Vec::with_capacity(
            self.corners.len().saturating_sub(2 * self.ends.len()) + self.strip_triangles.len(),
        );
        let mut triangulator = Triangulator::default();
        let mut start = 0;
        for (face, &end) in self.ends.iter().enumerate() {
            triangulator
                .triangulate(&self.corners[start..end], &self.vertices, &mut triangles)
                .map_err(|e| ReadErrorKind::PolygonTooComplex {
                    at: Place::Face(face),
                    face,
                    corners: e.corners,
                })?;
            start = end;
        }
        triangles.extend(self.strip_triangles);
        let texture_coords = self
            .texture
            .and_then(|texture| corner_texture_coords(&triangles, &texture));
        Ok(TexturedMesh {
            mesh: Mesh {
                vertices: self.vertices,
                triangles,
            },
            texture_coords,
        })
    }
}

/// Triangles of one strip run `v0 v1 v2 v3 ...`: `(v0 v1 v2)`, `(v2 v1 v3)`, ... — every
/// second one swapped so all share the first one's winding; those with a repeated index
/// are skipped (they keep the parity, as in the file).
fn decode_strip(run: &[u32], out: &mut Vec<[u32; 3]>) {
    for (k, w) in run.windows(3).enumerate() {
        let (a, b, c) = (w[0], w[1], w[2]);
        if a == b || b == c || a == c {
            continue;
        }
        out.push(if k % 2 == 0 { [a, b, c] } else { [b, a, c] });
    }
}

#[cfg(test)]
mod tests;
