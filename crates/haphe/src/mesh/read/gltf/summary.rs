//! What `haphe validate` says of a glTF file beside the flattened mesh: per node of the
//! default scene, its mesh, triangles, transform and whether the mesh is closed; and the
//! primitives skipped.

use serde::Serialize;

use super::scene::{GltfScene, SkippedPrimitive};
use crate::mesh::{MeshReport, Weld, weld};

/// One node with a mesh, as `haphe validate` reports it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GltfNodeSummary {
    /// The node's index in the file.
    pub node: usize,
    /// Its name, else its mesh's, else `node N`.
    pub name: String,
    /// Its mesh's index in the file.
    pub mesh: usize,
    /// The mesh's triangles.
    pub triangles: usize,
    /// Whether the mesh, welded, is closed (every edge shared by exactly two triangles).
    pub closed: bool,
    /// The world transform's translation, metres.
    pub translation: [f64; 3],
    /// Its rotation as a unit quaternion `[x, y, z, w]` (of the transform's best
    /// decomposition into scale, rotation and translation; see `exact_trs`).
    pub rotation: [f64; 4],
    /// Its scale along the node's axes (negative on one axis for a mirror).
    pub scale: [f64; 3],
    /// Whether scale, rotation and translation rebuild the transform (no shear).
    pub exact_trs: bool,
}

/// A glTF file's scene as `haphe validate` reports it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct GltfSummary {
    /// The scene read (`None`: the file has no scene; its root nodes were read).
    pub scene: Option<usize>,
    /// The nodes with a mesh, in the scene's order.
    pub nodes: Vec<GltfNodeSummary>,
    /// The primitives not read (points, lines).
    pub skipped: Vec<SkippedSummary>,
}

/// A skipped primitive, as serialised.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct SkippedSummary {
    /// The mesh.
    pub mesh: usize,
    /// The primitive within the mesh.
    pub primitive: usize,
    /// Its mode (`POINTS`, `LINES`, `LINE_LOOP`, `LINE_STRIP`).
    pub mode: &'static str,
}

impl From<&SkippedPrimitive> for SkippedSummary {
    fn from(s: &SkippedPrimitive) -> SkippedSummary {
        SkippedSummary {
            mesh: s.mesh,
            primitive: s.primitive,
            mode: s.mode,
        }
    }
}

/// How far a rebuilt transform may be from the node's, relative to its largest entry, to
/// count as exactly scale, rotation and translation.
const TRS_REBUILD_RELATIVE: f64 = 1e-9;

impl GltfScene {
    /// The report of each node (each distinct mesh welded as `weld_mode` says and
    /// analysed once).
    pub fn summary(&self, weld_mode: Weld) -> GltfSummary {
        let mut closed: Vec<Option<bool>> = vec![None; self.meshes.len()];
        let nodes = self
            .nodes
            .iter()
            .map(|node| {
                let mesh = self.mesh_of(node);
                let is_closed = *closed[node.mesh]
                    .get_or_insert_with(|| MeshReport::of(&weld(mesh, weld_mode).0).closed);
                let t = node.world_from_node;
                let (scale, rotation, translation) = t.to_scale_rotation_translation();
                let rebuilt =
                    glam::DAffine3::from_scale_rotation_translation(scale, rotation, translation);
                let size = t
                    .matrix3
                    .abs()
                    .to_cols_array()
                    .iter()
                    .fold(0.0f64, |m, &v| m.max(v));
                GltfNodeSummary {
                    node: node.index,
                    name: node.label(),
                    mesh: node.mesh,
                    triangles: mesh.triangles.len(),
                    closed: is_closed,
                    translation: translation.to_array(),
                    rotation: rotation.to_array(),
                    scale: scale.to_array(),
                    exact_trs: rebuilt.matrix3.abs_diff_eq(
                        t.matrix3,
                        TRS_REBUILD_RELATIVE * size.max(f64::MIN_POSITIVE),
                    ),
                }
            })
            .collect();
        GltfSummary {
            scene: self.scene,
            nodes,
            skipped: self.skipped.iter().map(SkippedSummary::from).collect(),
        }
    }
}
