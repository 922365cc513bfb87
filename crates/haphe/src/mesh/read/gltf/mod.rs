//! glTF 2.0 (`.gltf` and `.glb`), from bytes.
//!
//! [`read_gltf`] reads the default scene: the meshes its nodes use, each in its own frame,
//! and the nodes that place them, with their world transforms (matrices or translation,
//! rotation and scale, nested). [`GltfScene::flatten`] puts every placed mesh into one mesh
//! in world coordinates, which is what [`read_mesh`](super::read_mesh) returns for a glTF
//! file; a scene keeps one object per node (see `scene::gltf_objects`).
//!
//! - Triangles, triangle strips and triangle fans are read; points and lines are skipped
//!   and listed in [`GltfScene::skipped`].
//! - Indices of any unsigned type; positions as floats, or as (normalised) integers of
//!   `KHR_mesh_quantization`; sparse accessors.
//! - Buffers come from the `.glb`'s binary chunk, `data:` URIs, or side-car files that the
//!   caller fetches through a [`Resolve`]: the reader opens no files.
//! - A file that requires an extension haphe does not read is refused, by the extension's
//!   name (`KHR_draco_mesh_compression` among them); extensions that change only how a
//!   surface looks (materials, textures) are ignored.
//!
//! The JSON is parsed by the `gltf` crate's document types; everything read from the
//! buffers is checked here (ranges, counts, indices), and counts are held to limits before
//! anything is allocated ([`MAX_TRIANGLES`]).

mod accessor;
mod container;
mod limits;
mod nodes;
mod places;
mod primitive;
mod scene;
mod summary;

pub(crate) use container::GLB_MAGIC;
pub use container::{NoSideCars, Resolve};
pub use limits::MAX_TRIANGLES;
pub use scene::{GltfNode, GltfScene, SkippedPrimitive};
pub use summary::{GltfNodeSummary, GltfSummary, SkippedSummary};

use gltf::json;

use crate::mesh::read::textured::VertexTextureCoords;
use crate::mesh::{Mesh, Place, ReadError, ReadErrorKind, Units};

/// Required extensions that change only how a surface looks, which haphe may ignore.
const APPEARANCE_EXTENSIONS: &[&str] = &[
    "KHR_materials_anisotropy",
    "KHR_materials_clearcoat",
    "KHR_materials_diffuse_transmission",
    "KHR_materials_dispersion",
    "KHR_materials_emissive_strength",
    "KHR_materials_ior",
    "KHR_materials_iridescence",
    "KHR_materials_pbrSpecularGlossiness",
    "KHR_materials_sheen",
    "KHR_materials_specular",
    "KHR_materials_transmission",
    "KHR_materials_unlit",
    "KHR_materials_variants",
    "KHR_materials_volume",
    "KHR_texture_basisu",
    "KHR_texture_transform",
    "EXT_texture_webp",
    "EXT_texture_avif",
];

/// Required extensions that haphe reads.
const READ_EXTENSIONS: &[&str] = &["KHR_mesh_quantization"];

/// Refuses a file that requires an extension haphe does not read, by its name.
fn check_required_extensions(root: &json::Root) -> Result<(), ReadErrorKind> {
    for name in &root.extensions_required {
        if READ_EXTENSIONS.contains(&name.as_str())
            || APPEARANCE_EXTENSIONS.contains(&name.as_str())
        {
            continue;
        }
        let message = if name == primitive::DRACO {
            format!(
                "the file requires {name} (Draco-compressed geometry), which haphe does not \
                 decode; export the file without Draco compression"
            )
        } else {
            format!("the file requires the extension {name}, which haphe does not read")
        };
        return Err(ReadErrorKind::Unsupported {
            at: Place::Header,
            message,
        });
    }
    Ok(())
}

/// Which buffers the accessors of `meshes` (marked `true`) read from. References that do
/// not exist are left for the accessor reader to report with their place.
fn needed_buffers(root: &json::Root, meshes: &[bool]) -> Vec<bool> {
    let mut needed = vec![false; root.buffers.len()];
    let mut mark_view = |view: usize| {
        if let Some(v) = root.buffer_views.get(view)
            && let Some(slot) = needed.get_mut(v.buffer.value())
        {
            *slot = true;
        }
    };
    let used = root
        .meshes
        .iter()
        .zip(meshes)
        .filter(|(_, used)| **used)
        .flat_map(|(mesh, _)| &mesh.primitives);
    for primitive in used {
        let accessors = primitive.attributes.values().chain(&primitive.indices);
        for accessor in accessors.filter_map(|a| root.accessors.get(a.value())) {
            if let Some(view) = accessor.buffer_view {
                mark_view(view.value());
            }
            if let Some(sparse) = &accessor.sparse {
                mark_view(sparse.indices.buffer_view.value());
                mark_view(sparse.values.buffer_view.value());
            }
        }
    }
    needed
}

fn extras_text(extras: &json::extras::Extras) -> Option<String> {
    extras.as_ref().map(|raw| raw.get().to_owned())
}

/// Reads the default scene of a glTF 2.0 file (`.gltf` or `.glb`) from its bytes; side-car
/// buffers are fetched through `resolver`. `units` scales the file's numbers to metres
/// (glTF's unit is the metre, the default).
///
/// # Errors
/// A [`ReadError`] naming `file` and the place (scene, node, mesh, primitive, accessor,
/// buffer view, buffer): JSON that is not a glTF document, a required extension haphe does
/// not read, a buffer shorter than its `byteLength` or a side-car file that cannot be had,
/// an accessor reaching past its buffer, an index out of range, a node graph that is not a
/// forest (two parents, a cycle), a transform that is not finite, counts over the limits
/// ([`MAX_TRIANGLES`]), or no triangles at all.
pub fn read_gltf(
    file: &str,
    bytes: &[u8],
    units: Units,
    resolver: &mut dyn Resolve,
) -> Result<GltfScene, ReadError> {
    read(bytes, units, resolver).map_err(|kind| ReadError {
        file: file.to_owned(),
        kind,
    })
}

fn read(
    bytes: &[u8],
    units: Units,
    resolver: &mut dyn Resolve,
) -> Result<GltfScene, ReadErrorKind> {
    let scale = units.metres_per_unit();
    if !(scale.is_finite() && scale > 0.0) {
        return Err(ReadErrorKind::Syntax {
            at: Place::Header,
            message: format!("the unit factor {scale} is not a positive finite number"),
        });
    }
    let container = container::open(bytes)?;
    let root = &container.root;
    check_required_extensions(root)?;
    let (scene, placed) = nodes::placed_nodes(root)?;
    let mut used = vec![false; root.meshes.len()];
    for p in &placed {
        used[p.mesh] = true;
    }
    let data = container::load_buffers(&container, &needed_buffers(root, &used), resolver)?;
    let mut accessors = accessor::Accessors {
        root,
        buffers: &data,
        decoded: 0,
        unbacked: 0,
    };
    let mut skipped = Vec::new();
    let mut meshes: Vec<Option<Mesh>> = vec![None; root.meshes.len()];
    let mut texture_coords: Vec<Option<VertexTextureCoords>> = vec![None; root.meshes.len()];
    for (index, slot) in meshes.iter_mut().enumerate() {
        if used[index] {
            let (mut mesh, texture) = primitive::read_mesh(&mut accessors, index, &mut skipped)?;
            texture_coords[index] = texture;
            if scale != 1.0 {
                for p in &mut mesh.vertices {
                    *p *= scale;
                }
            }
            *slot = Some(mesh);
        }
    }
    let nodes: Vec<GltfNode> = placed
        .into_iter()
        .map(|p| {
            let node = &root.nodes[p.node];
            let mesh = &root.meshes[p.mesh];
            let mut world_from_node = p.world_from_node;
            world_from_node.translation *= scale;
            GltfNode {
                index: p.node,
                name: node.name.clone(),
                mesh: p.mesh,
                mesh_name: mesh.name.clone(),
                world_from_node,
                extras: extras_text(&node.extras).or_else(|| extras_text(&mesh.extras)),
            }
        })
        .collect();
    let out = GltfScene {
        scene,
        meshes,
        nodes,
        skipped,
        texture_coords,
    };
    let triangles = out.placed_triangles();
    if triangles > MAX_TRIANGLES {
        return Err(ReadErrorKind::TooLarge {
            at: Place::Header,
            message: format!(
                "the scene's nodes place {triangles} triangles, more than the limit of \
                 {MAX_TRIANGLES}"
            ),
        });
    }
    if triangles == 0 && !out.skipped.is_empty() {
        return Err(ReadErrorKind::Invalid {
            at: Place::Header,
            message: format!(
                "no triangles: the scene's meshes draw only points or lines ({} primitives \
                 skipped)",
                out.skipped.len()
            ),
        });
    }
    if triangles == 0 {
        return Err(ReadErrorKind::NoFaces {
            vertices: out.meshes.iter().flatten().map(|m| m.vertices.len()).sum(),
        });
    }
    Ok(out)
}
