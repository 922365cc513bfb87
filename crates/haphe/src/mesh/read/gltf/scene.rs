//! The default scene of a glTF file as read: its meshes, the nodes that place them, and
//! the primitives skipped.

use glam::DAffine3;

use crate::mesh::Mesh;
use crate::mesh::read::textured::{TexturedMesh, VertexTextureCoords, corner_texture_coords};

/// A node of the default scene that holds a mesh.
#[derive(Debug, Clone, PartialEq)]
pub struct GltfNode {
    /// The node's index in the file.
    pub index: usize,
    /// The node's name, if it has one.
    pub name: Option<String>,
    /// The index of its mesh in the file (in [`GltfScene::meshes`]).
    pub mesh: usize,
    /// Its mesh's name, if it has one.
    pub mesh_name: Option<String>,
    /// `world_from_node`: the product of the transforms from the scene's root down to this
    /// node (metres; any affine map, scale and shear included).
    pub world_from_node: DAffine3,
    /// The node's `extras` as JSON text, else its mesh's, if either has some.
    pub extras: Option<String>,
}

impl GltfNode {
    /// Whether the node's world transform mirrors (a negative determinant): its triangles
    /// are turned over when placed, so that they keep facing outwards.
    pub fn mirrors(&self) -> bool {
        self.world_from_node.matrix3.determinant() < 0.0
    }

    /// The node's name for reports: its own, else its mesh's, else `node N`.
    pub fn label(&self) -> String {
        self.name
            .clone()
            .or_else(|| self.mesh_name.clone())
            .unwrap_or_else(|| format!("node {}", self.index))
    }
}

/// A primitive that was not read because it draws points or lines.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SkippedPrimitive {
    /// The mesh.
    pub mesh: usize,
    /// The primitive within the mesh.
    pub primitive: usize,
    /// Its mode: `POINTS`, `LINES`, `LINE_LOOP` or `LINE_STRIP`.
    pub mode: &'static str,
}

/// The default scene of a glTF file, read.
#[derive(Debug, Clone, PartialEq)]
pub struct GltfScene {
    /// The scene read: the file's `scene`, else its first; `None` for a file without
    /// scenes, whose root nodes are read.
    pub scene: Option<usize>,
    /// The meshes by their index in the file: the ones the scene's nodes use, each in its
    /// own frame, in metres, not welded (`None` for the others).
    pub meshes: Vec<Option<Mesh>>,
    /// The scene's nodes that hold a mesh, depth first, in the order the file lists them.
    pub nodes: Vec<GltfNode>,
    /// The primitives of those meshes that draw points or lines, not read.
    pub skipped: Vec<SkippedPrimitive>,
    /// The texture coordinates of each mesh's vertices (`v` pointing up), where every
    /// triangle primitive of the mesh has `TEXCOORD_0`.
    pub(crate) texture_coords: Vec<Option<VertexTextureCoords>>,
}

impl GltfScene {
    /// The mesh of `node`, in its own frame.
    pub fn mesh_of(&self, node: &GltfNode) -> &Mesh {
        static EMPTY: Mesh = Mesh {
            vertices: Vec::new(),
            triangles: Vec::new(),
        };
        self.meshes
            .get(node.mesh)
            .and_then(Option::as_ref)
            .unwrap_or(&EMPTY)
    }

    /// The mesh of `node` placed in the world (metres, world frame), its triangles turned
    /// over when the node's transform mirrors.
    pub fn placed(&self, node: &GltfNode) -> Mesh {
        let mut out = Mesh::default();
        self.place_into(node, &mut out);
        out
    }

    fn place_into(&self, node: &GltfNode, out: &mut Mesh) {
        let mesh = self.mesh_of(node);
        let base = out.vertices.len() as u32;
        out.vertices.extend(
            mesh.vertices
                .iter()
                .map(|&p| node.world_from_node.transform_point3(p)),
        );
        let mirrors = node.mirrors();
        out.triangles
            .extend(mesh.triangles.iter().map(|&[a, b, c]| {
                if mirrors {
                    [base + a, base + c, base + b]
                } else {
                    [base + a, base + b, base + c]
                }
            }));
    }

    /// Every node's mesh placed in the world, as one mesh (world frame, not welded).
    pub fn flatten(&self) -> Mesh {
        let (vertices, triangles) = self.nodes.iter().fold((0, 0), |(v, t), node| {
            let mesh = self.mesh_of(node);
            (v + mesh.vertices.len(), t + mesh.triangles.len())
        });
        let mut out = Mesh {
            vertices: Vec::with_capacity(vertices),
            triangles: Vec::with_capacity(triangles),
        };
        for node in &self.nodes {
            self.place_into(node, &mut out);
        }
        out
    }

    /// [`GltfScene::flatten`], with the texture coordinates of the triangles' corners when
    /// every placed mesh has them.
    pub(crate) fn flatten_textured(&self) -> TexturedMesh {
        let mesh = self.flatten();
        let mut per_vertex = Some(Vec::with_capacity(mesh.vertices.len()));
        for node in &self.nodes {
            let texture = self.texture_coords.get(node.mesh).and_then(Option::as_ref);
            match (&mut per_vertex, texture) {
                (Some(all), Some(texture)) => all.extend_from_slice(texture),
                _ => per_vertex = None,
            }
        }
        // Vertices are placed node after node, as `flatten` does.
        let texture_coords =
            per_vertex.and_then(|all| corner_texture_coords(&mesh.triangles, &all));
        TexturedMesh {
            mesh,
            texture_coords,
        }
    }

    /// How many triangles the scene places (a mesh counted once per node using it).
    pub fn placed_triangles(&self) -> usize {
        self.nodes
            .iter()
            .map(|n| self.mesh_of(n).triangles.len())
            .sum()
    }
}
