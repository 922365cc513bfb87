//! Scenes from glTF files: one object per node of the default scene that holds a mesh,
//! placed at the node's world pose, named after the node, with the stiffness and friction
//! of its `extras` when it gives them.
//!
//! A node's world transform is split into a rigid pose and the rest: `world_from_node =
//! pose · shape_from_mesh`, where the pose is a rotation and a translation and
//! `shape_from_mesh` (upper triangular: scale, and the shear that nested rotations and
//! non-uniform scales make) is baked into the object's shape. Nodes that use the same mesh
//! with the same baked part share one shape, so a hundred copies of a part placed rigidly
//! cost one shape.

use std::sync::Arc;

use glam::{DMat3, DQuat};

use super::invalid::ParamError;
use super::material::Material;
use super::object::{ObjectId, SceneObject};
use super::pose::Pose;
use super::shape::Shape;
use crate::map::MapOptions;
use crate::mesh::{GltfNode, GltfScene, Mesh, Weld, weld};

/// Why a glTF file's nodes do not make a scene: the message names the node.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum GltfSceneError {
    /// The node's world transform squashes its mesh flat (a zero scale).
    #[error(
        "node {node} ('{name}'): its world transform is singular (a zero scale), so its mesh has no volume to touch"
    )]
    Singular {
        /// The node's index in the file.
        node: usize,
        /// Its name for reports.
        name: String,
    },
    /// The node's `extras` give a material value that cannot be used.
    #[error("node {node} ('{name}'): extras: {source}")]
    Material {
        /// The node's index in the file.
        node: usize,
        /// Its name for reports.
        name: String,
        /// The value refused.
        source: ParamError,
    },
    /// The node's world placement is outside the domain of a pose (a translation farther
    /// than `ABSURD_DISTANCE_M` from the origin).
    #[error("node {node} ('{name}'): placement: {source}")]
    Placement {
        /// The node's index in the file.
        node: usize,
        /// Its name for reports.
        name: String,
        /// The value refused.
        source: ParamError,
    },
    /// The node's shape cannot be built (its surface or its map).
    #[error("node {node} ('{name}'): {message}")]
    Shape {
        /// The node's index in the file (the first node using the shape).
        node: usize,
        /// Its name for reports.
        name: String,
        /// What failed.
        message: String,
    },
    /// The node's `extras` give a material value that is not a number.
    #[error("node {node} ('{name}'): extras: '{field}' must be a number")]
    NotANumber {
        /// The node's index in the file.
        node: usize,
        /// Its name for reports.
        name: String,
        /// The key.
        field: &'static str,
    },
}

/// One object of a glTF scene, its shape not built yet.
#[derive(Debug, Clone, PartialEq)]
pub struct GltfObject {
    /// The node's name, else its mesh's, else `node N`.
    pub name: String,
    /// The node's index in the file.
    pub node: usize,
    /// Its shape: an index into [`GltfObjects::meshes`].
    pub shape: usize,
    /// `world_from_object`.
    pub pose: Pose,
    /// The material its `extras` give, if they give one.
    pub material: Option<Material>,
}

/// The objects of a glTF scene and the meshes of their shapes (each to be built once).
#[derive(Debug, Clone, PartialEq)]
pub struct GltfObjects {
    /// The distinct shapes' meshes, object frame, metres, not welded.
    pub meshes: Vec<Mesh>,
    /// One object per node with a mesh, in the scene's order.
    pub objects: Vec<GltfObject>,
}

impl GltfObjects {
    /// Builds every distinct shape once (welded as `weld` says, with its map and its clear
    /// zones) and returns the objects ready to insert, with their names: ids from
    /// `first_id` on, in order; the material of their `extras`, else `material`. Objects
    /// that share a shape share one `Arc<Shape>`.
    ///
    /// # Errors
    /// [`GltfSceneError::Shape`] naming the first node of a shape that cannot be built.
    pub fn build(
        &self,
        weld_mode: Weld,
        map: &MapOptions,
        material: Material,
        first_id: u32,
    ) -> Result<Vec<(String, SceneObject)>, GltfSceneError> {
        let mut shapes = Vec::with_capacity(self.meshes.len());
        for (index, mesh) in self.meshes.iter().enumerate() {
            let fail = |message: String| {
                let first = self.objects.iter().find(|o| o.shape == index);
                GltfSceneError::Shape {
                    node: first.map_or(0, |o| o.node),
                    name: first.map_or_else(String::new, |o| o.name.clone()),
                    message,
                }
            };
            let (welded, _) = weld(mesh, weld_mode);
            // The node names the shape in the error; the message is what failed.
            let shape = Shape::from_mesh("", welded, map).map_err(|e| {
                let cause = std::error::Error::source(&e).map(ToString::to_string);
                fail(cause.unwrap_or_else(|| e.to_string()))
            })?;
            shapes.push(Arc::new(shape));
        }
        Ok(self
            .objects
            .iter()
            .zip(first_id..)
            .map(|(o, id)| {
                let object = SceneObject::new(
                    ObjectId(id),
                    shapes[o.shape].clone(),
                    o.pose,
                    o.material.unwrap_or(material),
                );
                (o.name.clone(), object)
            })
            .collect())
    }
}

/// How finely the baked part of a transform is rounded, relative to its largest entry (a
/// power of two, so rounding is exact): transforms that differ by less (rounding in the
/// file's arithmetic) bake the same shape, and a rotation's leftover is exactly the
/// identity.
const BAKE_ROUNDING_BITS: i32 = 40;

/// `linear = rotation · baked`, the rotation proper and `baked` upper triangular, rounded
/// (see [`BAKE_ROUNDING_BITS`]); `None` for a singular `linear`.
fn split_rotation(linear: DMat3) -> Option<(DQuat, DMat3, [i64; 10])> {
    let (c0, c1) = (linear.x_axis, linear.y_axis);
    let scale = c0.length().max(c1.length()).max(linear.z_axis.length());
    // Relative to the columns' lengths: a determinant this small is a flattened mesh.
    const SINGULAR_RELATIVE: f64 = 1e-12;
    if scale.is_nan()
        || scale <= 0.0
        || linear.determinant().abs() <= SINGULAR_RELATIVE * scale.powi(3)
    {
        return None;
    }
    let q0 = c0.normalize();
    let q1 = (c1 - q0 * q0.dot(c1)).normalize();
    let rotation = DMat3::from_cols(q0, q1, q0.cross(q1));
    let baked = rotation.transpose() * linear;
    let exponent = baked
        .abs()
        .to_cols_array()
        .iter()
        .fold(0.0f64, |m, &v| m.max(v))
        .log2()
        .floor() as i32;
    let step = 2f64.powi(exponent - BAKE_ROUNDING_BITS);
    let mut key = [0i64; 10];
    key[9] = i64::from(exponent);
    let rounded: [f64; 9] = std::array::from_fn(|i| {
        let q = (baked.to_cols_array()[i] / step).round();
        key[i] = q as i64;
        q * step
    });
    Some((
        DQuat::from_mat3(&rotation),
        DMat3::from_cols_array(&rounded),
        key,
    ))
}

/// `mesh` under `baked`, its triangles turned over if `baked` mirrors.
fn bake(mesh: &Mesh, baked: DMat3) -> Mesh {
    let mirrors = baked.determinant() < 0.0;
    Mesh {
        vertices: mesh.vertices.iter().map(|&p| baked * p).collect(),
        triangles: mesh
            .triangles
            .iter()
            .map(|&[a, b, c]| if mirrors { [a, c, b] } else { [a, b, c] })
            .collect(),
    }
}

/// The material a node's `extras` give: `stiffness` (N/m), `damping` (N·s/m),
/// `friction` (both coefficients), `static_friction`, `dynamic_friction`; other keys are
/// the application's and are ignored. `None` when none of these is given.
fn material_of(node: &GltfNode) -> Result<Option<Material>, GltfSceneError> {
    let Some(text) = &node.extras else {
        return Ok(None);
    };
    let Ok(serde_json::Value::Object(map)) = serde_json::from_str::<serde_json::Value>(text) else {
        return Ok(None);
    };
    let number = |field: &'static str| -> Result<Option<f64>, GltfSceneError> {
        match map.get(field) {
            None => Ok(None),
            Some(v) => v.as_f64().map(Some).ok_or(GltfSceneError::NotANumber {
                node: node.index,
                name: node.label(),
                field,
            }),
        }
    };
    let stiffness = number("stiffness")?;
    let damping = number("damping")?;
    let friction = number("friction")?;
    let static_friction = number("static_friction")?.or(friction);
    let dynamic_friction = number("dynamic_friction")?.or(friction);
    if [stiffness, damping, static_friction, dynamic_friction]
        .iter()
        .all(Option::is_none)
    {
        return Ok(None);
    }
    let base = Material::default();
    let static_friction = static_friction.unwrap_or(base.static_friction());
    Material::builder()
        .stiffness(stiffness.unwrap_or(base.stiffness()))
        .damping(damping.unwrap_or(base.damping()))
        // A lone static coefficient also caps the dynamic one.
        .friction(
            static_friction,
            dynamic_friction.unwrap_or(base.dynamic_friction().min(static_friction)),
        )
        .build()
        .map(Some)
        .map_err(|source| GltfSceneError::Material {
            node: node.index,
            name: node.label(),
            source,
        })
}

/// The objects of a glTF scene: one per node with a mesh, at its world pose, with its
/// shape's mesh baked (scale and shear) and shared between nodes that bake the same mesh
/// the same way.
///
/// # Errors
/// A [`GltfSceneError`] naming the node: a singular world transform, or a material in its
/// `extras` that is not usable.
pub fn gltf_objects(scene: &GltfScene) -> Result<GltfObjects, GltfSceneError> {
    let mut keys: Vec<(usize, [i64; 10])> = Vec::new();
    let mut out = GltfObjects {
        meshes: Vec::new(),
        objects: Vec::with_capacity(scene.nodes.len()),
    };
    for node in &scene.nodes {
        let Some((rotation, baked, key)) = split_rotation(node.world_from_node.matrix3) else {
            return Err(GltfSceneError::Singular {
                node: node.index,
                name: node.label(),
            });
        };
        let key = (node.mesh, key);
        let shape = match keys.iter().position(|k| *k == key) {
            Some(i) => i,
            None => {
                let mesh = bake(scene.mesh_of(node), baked);
                mesh.check_indices_and_finite()
                    .map_err(|e| GltfSceneError::Shape {
                        node: node.index,
                        name: node.label(),
                        message: e.to_string(),
                    })?;
                keys.push(key);
                out.meshes.push(mesh);
                out.meshes.len() - 1
            }
        };
        out.objects.push(GltfObject {
            name: node.label(),
            node: node.index,
            shape,
            pose: Pose::new(rotation, node.world_from_node.translation).map_err(|source| {
                GltfSceneError::Placement {
                    node: node.index,
                    name: node.label(),
                    source,
                }
            })?,
            material: material_of(node)?,
        });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::{DAffine3, DVec3};

    #[test]
    fn a_transform_splits_into_a_rotation_and_a_baked_part_that_rebuild_it() {
        let transforms = [
            DAffine3::from_scale_rotation_translation(
                DVec3::new(1.0, 2.0, 3.0),
                DQuat::from_rotation_y(0.7),
                DVec3::ZERO,
            ),
            // Non-uniform scale under a rotation under another scale: a shear.
            DAffine3::from_scale(DVec3::new(2.0, 1.0, 1.0))
                * DAffine3::from_rotation_z(0.5)
                * DAffine3::from_scale(DVec3::new(1.0, 3.0, 0.5)),
            // A mirror.
            DAffine3::from_scale(DVec3::new(-1.0, 1.0, 1.0)) * DAffine3::from_rotation_x(1.0),
        ];
        for t in transforms {
            let (rotation, baked, _) = split_rotation(t.matrix3).expect("regular");
            let rebuilt = DMat3::from_quat(rotation) * baked;
            assert!(
                rebuilt.abs_diff_eq(t.matrix3, 1e-12),
                "{rebuilt} {}",
                t.matrix3
            );
            // Upper triangular: what is baked has no rotation left in it.
            assert!(baked.x_axis.y.abs() < 1e-12 && baked.x_axis.z.abs() < 1e-12);
            assert!(baked.y_axis.z.abs() < 1e-12);
            assert_eq!(
                baked.determinant() < 0.0,
                t.matrix3.determinant() < 0.0,
                "the mirror stays in the baked part"
            );
        }
    }

    #[test]
    fn a_rotation_bakes_exactly_the_identity() {
        for angle in [0.1, 1.0, 2.5, -3.0] {
            let r = DQuat::from_euler(glam::EulerRot::XYZ, angle, 0.3 * angle, -angle);
            let (_, baked, _) = split_rotation(DMat3::from_quat(r)).expect("regular");
            assert_eq!(baked, DMat3::IDENTITY, "angle {angle}");
        }
    }

    #[test]
    fn a_zero_scale_is_singular() {
        assert!(split_rotation(DMat3::from_diagonal(DVec3::new(1.0, 0.0, 1.0))).is_none());
    }
}
