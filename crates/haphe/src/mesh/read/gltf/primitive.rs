//! A glTF mesh's triangles: every triangle primitive (triangles, strips, fans) in the
//! mesh's own frame; points and lines are set aside and reported.

use glam::DVec3;
use gltf::json;
use gltf::json::mesh::{Mode, Semantic};
use gltf::json::validation::Checked;

use super::accessor::{Accessors, INDICES, POSITIONS, TEXTURE_COORDS};
use super::places::{ix, place};
use super::scene::SkippedPrimitive;
use crate::mesh::GltfPlace;
use crate::mesh::read::textured::VertexTextureCoords;
use crate::mesh::{Mesh, ReadErrorKind};

/// The extension name of Draco-compressed primitives.
pub(super) const DRACO: &str = "KHR_draco_mesh_compression";

/// The glTF name of a primitive mode.
fn mode_name(mode: Mode) -> &'static str {
    match mode {
        Mode::Points => "POINTS",
        Mode::Lines => "LINES",
        Mode::LineLoop => "LINE_LOOP",
        Mode::LineStrip => "LINE_STRIP",
        Mode::Triangles => "TRIANGLES",
        Mode::TriangleStrip => "TRIANGLE_STRIP",
        Mode::TriangleFan => "TRIANGLE_FAN",
    }
}

/// The triangles a primitive's vertex sequence draws in `mode`, as the glTF specification
/// defines them: strips alternate their winding, fans turn about the first vertex.
/// Triangles of a strip or fan that repeat a vertex are dropped (strips are joined by
/// such degenerate triangles); a plain triangle list is kept as written.
fn assemble(mode: Mode, sequence: &[u32], out: &mut Vec<[u32; 3]>) {
    match mode {
        Mode::Triangles => out.extend(sequence.chunks_exact(3).map(|t| [t[0], t[1], t[2]])),
        Mode::TriangleStrip => out.extend(
            sequence
                .windows(3)
                .enumerate()
                .map(|(i, w)| {
                    if i % 2 == 0 {
                        [w[0], w[1], w[2]]
                    } else {
                        [w[1], w[0], w[2]]
                    }
                })
                .filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2]),
        ),
        Mode::TriangleFan => {
            if let Some((&first, rest)) = sequence.split_first() {
                out.extend(
                    rest.windows(2)
                        .map(|w| [w[0], w[1], first])
                        .filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2]),
                );
            }
        }
        Mode::Points | Mode::Lines | Mode::LineLoop | Mode::LineStrip => {}
    }
}

/// Mesh `index` of the file: the triangles of all its triangle primitives, in its own
/// frame, only the vertices they use kept; with its vertices' texture coordinates
/// (`TEXCOORD_0`, `v` turned to point up: `1 − v`) when every triangle primitive has them.
///
/// # Errors
/// Naming the mesh, primitive and accessor: an unknown mode, a primitive without
/// `POSITION`, a Draco-compressed primitive with no uncompressed data, a bad accessor, an
/// index past the positions, texture coordinates that are not finite or not one per
/// position.
pub(super) fn read_mesh(
    accessors: &mut Accessors<'_>,
    index: usize,
    skipped: &mut Vec<SkippedPrimitive>,
) -> Result<(Mesh, Option<VertexTextureCoords>), ReadErrorKind> {
    let root: &json::Root = accessors.root;
    let mesh = &root.meshes[index];
    let mut out = Mesh::default();
    // Dropped at the first triangle primitive without texture coordinates.
    let mut texture = Some(Vec::new());
    for (p, primitive) in mesh.primitives.iter().enumerate() {
        let at = GltfPlace {
            mesh: Some(ix(index)),
            primitive: Some(ix(p)),
            ..GltfPlace::default()
        };
        let invalid = |message: String| ReadErrorKind::Invalid {
            at: place(at),
            message,
        };
        let Checked::Valid(mode) = primitive.mode else {
            return Err(invalid("its mode is not one glTF defines".to_owned()));
        };
        if matches!(
            mode,
            Mode::Points | Mode::Lines | Mode::LineLoop | Mode::LineStrip
        ) {
            skipped.push(SkippedPrimitive {
                mesh: index,
                primitive: p,
                mode: mode_name(mode),
            });
            continue;
        }
        let position = position_accessor(accessors, primitive, at)?;
        let base = out.vertices.len();
        let vertex_count = read_positions(accessors, position, at, &mut out.vertices)?;
        let sequence = read_sequence(accessors, primitive, at, base, vertex_count)?;
        assemble(mode, &sequence, &mut out.triangles);
        if let Some(list) = &mut texture
            && !read_texture_coords(accessors, primitive, at, vertex_count, list)?
        {
            texture = None;
        }
    }
    Ok(compact(out, texture))
}

/// Appends the `TEXCOORD_0` of a primitive with `vertex_count` vertices to `texture`, `v`
/// turned to point up (`1 − v`); `false` when it has none.
///
/// # Errors
/// A bad accessor, a count other than the positions', a non-finite value.
fn read_texture_coords(
    accessors: &mut Accessors<'_>,
    primitive: &json::mesh::Primitive,
    at: GltfPlace,
    vertex_count: usize,
    texture: &mut VertexTextureCoords,
) -> Result<bool, ReadErrorKind> {
    let Some(accessor) = primitive
        .attributes
        .get(&Checked::Valid(Semantic::TexCoords(0)))
        .map(|a| a.value())
    else {
        return Ok(false);
    };
    let values = accessors.read(accessor, &TEXTURE_COORDS, at)?;
    let at = place(GltfPlace {
        accessor: Some((ix(accessor), "TEXCOORD_0")),
        ..at
    });
    if values.len() / 2 != vertex_count {
        return Err(ReadErrorKind::Invalid {
            at,
            message: format!(
                "{} texture coordinates for {vertex_count} positions",
                values.len() / 2
            ),
        });
    }
    for (e, uv) in values.chunks_exact(2).enumerate() {
        // Past f32's range is infinite too.
        let uv = [uv[0] as f32, (1.0 - uv[1]) as f32];
        if !uv.iter().all(|x| x.is_finite()) {
            return Err(ReadErrorKind::Invalid {
                at,
                message: format!("element {e}: a texture coordinate is NaN or infinite"),
            });
        }
        texture.push(uv);
    }
    Ok(true)
}

/// The `POSITION` accessor of a triangle primitive.
///
/// # Errors
/// A primitive without one, or compressed with Draco and no uncompressed data.
fn position_accessor(
    accessors: &Accessors<'_>,
    primitive: &json::mesh::Primitive,
    at: GltfPlace,
) -> Result<usize, ReadErrorKind> {
    let Some(position) = primitive
        .attributes
        .get(&Checked::Valid(Semantic::Positions))
        .map(|a| a.value())
    else {
        return Err(ReadErrorKind::Invalid {
            at: place(at),
            message: "a triangle primitive without a POSITION attribute".to_owned(),
        });
    };
    let draco = primitive
        .extensions
        .as_ref()
        .is_some_and(|e| e.others.contains_key(DRACO));
    if draco && !accessors.has_view(position) {
        return Err(ReadErrorKind::Unsupported {
            at: place(at),
            message: format!(
                "the primitive is compressed with {DRACO} (Draco), which haphe does not \
                 decode; export the file without Draco compression"
            ),
        });
    }
    Ok(position)
}

/// Appends the positions of accessor `position` to `vertices`; returns how many.
///
/// # Errors
/// A bad accessor, more vertices than 32-bit indices hold, a non-finite coordinate.
fn read_positions(
    accessors: &mut Accessors<'_>,
    position: usize,
    at: GltfPlace,
    vertices: &mut Vec<DVec3>,
) -> Result<usize, ReadErrorKind> {
    let positions = accessors.read(position, &POSITIONS, at)?;
    let vertex_count = positions.len() / 3;
    let base = vertices.len();
    if base + vertex_count > u32::MAX as usize {
        return Err(ReadErrorKind::TooLarge {
            at: place(at),
            message: format!(
                "{} vertices in the mesh, more than 32-bit indices hold",
                base + vertex_count
            ),
        });
    }
    if let Some(e) = positions.iter().position(|v| !v.is_finite()) {
        return Err(ReadErrorKind::Invalid {
            at: place(GltfPlace {
                accessor: Some((ix(position), "POSITION")),
                ..at
            }),
            message: format!("element {}: a coordinate is NaN or infinite", e / 3),
        });
    }
    vertices.extend(
        positions
            .chunks_exact(3)
            .map(|c| DVec3::new(c[0], c[1], c[2])),
    );
    Ok(vertex_count)
}

/// The vertex sequence of a primitive whose `vertex_count` vertices start at `base`: its
/// indices offset by `base`, or its vertices in order (`base..base + vertex_count`) when it
/// has none.
///
/// # Errors
/// A bad accessor, an index past the primitive's vertices.
fn read_sequence(
    accessors: &mut Accessors<'_>,
    primitive: &json::mesh::Primitive,
    at: GltfPlace,
    base: usize,
    vertex_count: usize,
) -> Result<Vec<u32>, ReadErrorKind> {
    let Some(indices) = primitive.indices else {
        // `read_positions` kept `base + vertex_count` within u32.
        return Ok((base as u32..(base + vertex_count) as u32).collect());
    };
    let indices = indices.value();
    let values = accessors.read(indices, &INDICES, at)?;
    let mut sequence = Vec::with_capacity(values.len());
    for v in values {
        // Read from unsigned integers of at most 32 bits: exact.
        let v = v as u32;
        if v as usize >= vertex_count {
            return Err(ReadErrorKind::IndexOutOfRange {
                at: place(GltfPlace {
                    accessor: Some((ix(indices), "indices")),
                    ..at
                }),
                index: i64::from(v),
                count: vertex_count,
            });
        }
        sequence.push(base as u32 + v);
    }
    Ok(sequence)
}

/// `mesh` with only the vertices its triangles use, in the order first used; the
/// vertices' `texture` coordinates follow them.
fn compact(
    mesh: Mesh,
    texture: Option<VertexTextureCoords>,
) -> (Mesh, Option<VertexTextureCoords>) {
    let mut new_index = vec![u32::MAX; mesh.vertices.len()];
    let mut vertices = Vec::new();
    let mut kept_texture = texture.as_ref().map(|_| Vec::new());
    let triangles = mesh
        .triangles
        .iter()
        .map(|t| {
            t.map(|v| {
                let slot = &mut new_index[v as usize];
                if *slot == u32::MAX {
                    *slot = vertices.len() as u32;
                    vertices.push(mesh.vertices[v as usize]);
                    if let (Some(kept), Some(all)) = (&mut kept_texture, &texture) {
                        kept.push(all[v as usize]);
                    }
                }
                *slot
            })
        })
        .collect();
    (
        Mesh {
            vertices,
            triangles,
        },
        kept_texture,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Whether two triangles are the same up to a rotation of their corners (the same
    /// triangle with the same winding).
    fn same_winding(a: [u32; 3], b: [u32; 3]) -> bool {
        (0..3).any(|r| [a[r], a[(r + 1) % 3], a[(r + 2) % 3]] == b)
    }

    #[test]
    fn strips_alternate_and_fans_turn_about_the_first_vertex() {
        let v: Vec<u32> = (10..16).collect();
        let mut strip = Vec::new();
        assemble(Mode::TriangleStrip, &v, &mut strip);
        // The specification: p_i = {v_i, v_(i+(1+i%2)), v_(i+(2-i%2))}.
        let spec: Vec<[u32; 3]> = (0..v.len() - 2)
            .map(|i| [v[i], v[i + 1 + i % 2], v[i + 2 - i % 2]])
            .collect();
        assert_eq!(strip.len(), spec.len());
        for (mine, theirs) in strip.iter().zip(&spec) {
            assert!(same_winding(*mine, *theirs), "{mine:?} {theirs:?}");
        }
        let mut fan = Vec::new();
        assemble(Mode::TriangleFan, &v, &mut fan);
        // p_i = {v_(i+1), v_(i+2), v_0}.
        let spec: Vec<[u32; 3]> = (0..v.len() - 2)
            .map(|i| [v[i + 1], v[i + 2], v[0]])
            .collect();
        assert_eq!(fan, spec);
    }

    #[test]
    fn degenerate_strip_joins_are_dropped() {
        let mut strip = Vec::new();
        // Two strips (0 1 2) and (3 4 5) joined by repeating 2 and 3.
        assemble(Mode::TriangleStrip, &[0, 1, 2, 2, 3, 3, 4, 5], &mut strip);
        assert!(
            strip
                .iter()
                .all(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2])
        );
        // (0 1 2) and (3 4 5); the four joining triangles each repeat a vertex.
        assert_eq!(strip.len(), 2);
    }
}
