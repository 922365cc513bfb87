//! A mesh as a reader returns it, with the texture coordinates of its triangles' corners.

use crate::mesh::Mesh;

/// The texture coordinates `[u, v]` of each triangle's three corners, in the order of the
/// mesh's triangles and of each triangle's corners.
pub(crate) type CornerTextureCoords = Vec<[[f32; 2]; 3]>;

/// The texture coordinates `[u, v]` of each vertex of a mesh (PLY and glTF give them so).
pub(crate) type VertexTextureCoords = Vec<[f32; 2]>;

/// A mesh as a reader returns it, with its corners' texture coordinates if it has some.
#[derive(Debug, Clone, Default)]
pub(crate) struct TexturedMesh {
    /// The mesh, unwelded, in file units.
    pub(crate) mesh: Mesh,
    /// One entry per triangle of `mesh`, or `None`.
    pub(crate) texture_coords: Option<CornerTextureCoords>,
}

impl From<Mesh> for TexturedMesh {
    fn from(mesh: Mesh) -> TexturedMesh {
        TexturedMesh {
            mesh,
            texture_coords: None,
        }
    }
}

/// The texture coordinates of the triangles' corners from those of their vertices; `None`
/// if a corner's vertex has none.
pub(crate) fn corner_texture_coords(
    triangles: &[[u32; 3]],
    per_vertex: &[[f32; 2]],
) -> Option<CornerTextureCoords> {
    triangles
        .iter()
        .map(|t| {
            Some([
                *per_vertex.get(t[0] as usize)?,
                *per_vertex.get(t[1] as usize)?,
                *per_vertex.get(t[2] as usize)?,
            ])
        })
        .collect()
}
