//! One object of a scene: its name, shape, pose, material and touchable sides, and its
//! bounding sphere.

use std::sync::Arc;

use glam::DVec3;

use super::material::Material;
use super::pose::Pose;
use super::shape::Shape;
use super::texture::{Relief, Texture};
use crate::mesh::TriId;

/// A stable name for an object of a scene, chosen by the caller.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct ObjectId(pub u32);

/// One object of a scene: a shared shape at a pose, with a material.
#[derive(Debug, Clone)]
pub struct SceneObject {
    /// The caller's name for the object (unique within a scene).
    pub id: ObjectId,
    /// The shape, shared with other objects and threads.
    pub shape: Arc<Shape>,
    /// `world_from_object` now.
    pub pose: Pose,
    /// `world_from_object` at the previous tick (equal to `pose` for an object at rest).
    pub previous_pose: Pose,
    /// How the surface feels (where its shape has no material of its own: a cut volume's
    /// shape carries one per triangle, from the volume's layers).
    pub material: Material,
    /// Which sides of the surface can be touched.
    pub sides: Sides,
    /// The texture felt on the surface, if any.
    pub texture: Option<Texture>,
    /// The scene's count of deformations when this object's shape was last deformed (0:
    /// never), so that a proxy knows which surfaces moved since its last tick.
    pub(crate) deformed_at: u64,
    /// The shape as the last tick before its latest deformation saw it, for a proxy to
    /// ride from (see [`Scene::deform`](super::Scene::deform)).
    pub(crate) previous_shape: Option<Arc<Shape>>,
    /// The scene's tick count when `previous_shape` was kept.
    pub(crate) previous_since: u64,
    /// The scene's count of deformations when this object's shape was last replaced by
    /// one with other triangles ([`Shape::replacing`]; 0: never).
    pub(crate) remeshed_at: u64,
}

/// Which sides of an object's surface the proxy touches.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Sides {
    /// Only the front (the side the face normals point to): the outside of a closed solid,
    /// or the top of an open terrain. The proxy passes through from the back.
    Front,
    /// Both sides: an open sheet felt from either side, or the inside of a closed room.
    Both,
}

impl SceneObject {
    /// How triangle `t` feels: the shape's material there if it has its own, else the
    /// object's ([`Shape::material_on`]).
    ///
    /// # Real-time
    /// No allocation, no lock, no panic.
    #[inline]
    pub(crate) fn material_on(&self, t: TriId) -> &Material {
        self.shape.material_on(t, &self.material)
    }

    /// The material whose saturation depth starts and keeps a hold on the object (see
    /// [`Proxy`](crate::proxy::Proxy)): the object's, or the softest of its shape's own
    /// materials when it has them ([`Shape::hold_material`]).
    #[inline]
    pub(crate) fn hold_material(&self) -> &Material {
        self.shape.hold_material(&self.material)
    }

    /// An object at rest at `pose`: one-sided ([`Sides::Front`]) when its shape is a closed
    /// solid, two-sided otherwise.
    pub fn new(id: ObjectId, shape: Arc<Shape>, pose: Pose, material: Material) -> SceneObject {
        let sides = if shape.is_solid() {
            Sides::Front
        } else {
            Sides::Both
        };
        SceneObject {
            id,
            shape,
            pose,
            previous_pose: pose,
            material,
            sides,
            texture: None,
            deformed_at: 0,
            previous_shape: None,
            previous_since: 0,
            remeshed_at: 0,
        }
    }

    /// The same object with `texture` felt on its surface.
    pub fn with_texture(mut self, texture: Texture) -> SceneObject {
        self.texture = Some(texture);
        self
    }

    /// The same object touched on `sides`.
    pub fn with_sides(mut self, sides: Sides) -> SceneObject {
        self.sides = sides;
        self
    }

    /// The object's texture at the surface point `point` (world frame), at barycentric
    /// `weights` of its triangle `triangle`, its gradient in the world frame projected
    /// into the plane of the unit `normal`; [`Relief::FLAT`] where it has none.
    ///
    /// # Real-time
    /// No allocation; one texture evaluation.
    pub(crate) fn relief(
        &self,
        (triangle, weights): (TriId, [f64; 3]),
        point: DVec3,
        normal: DVec3,
    ) -> Relief {
        let Some(texture) = &self.texture else {
            return Relief::FLAT;
        };
        let pose = &self.pose;
        let r = texture.relief(pose.to_object(point), || {
            self.shape.uv_at(triangle, weights)
        });
        let g = pose.vector_to_world(r.gradient);
        Relief {
            gradient: g - g.dot(normal) * normal,
            ..r
        }
    }

    /// Whether the object moved since the previous tick.
    pub fn moved(&self) -> bool {
        self.pose != self.previous_pose
    }
}

/// The world bounding sphere of `o` at its pose, with its slack.
pub(super) fn sphere_of(o: &SceneObject) -> (DVec3, f64) {
    let shape = &*o.shape;
    (
        o.pose.to_world(shape.bound_centre()),
        shape.bound_radius() * BOUND_SLACK,
    )
}

/// Relative slack on a shape's bounding sphere, covering the rounding of poses.
pub(super) const BOUND_SLACK: f64 = 1.0 + 1e-7;
