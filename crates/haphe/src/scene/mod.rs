//! Stage 4 — scenes: many objects, each a shared immutable [`Shape`] placed by a rigid
//! [`Pose`] and given a [`Material`], changed from other threads without locking the
//! servo thread.
//!
//! The servo thread owns the [`Scene`]; another thread holds its [`SceneEditor`] and sends
//! edits (insert, remove, move, change material) through a wait-free ring buffer. The
//! scene applies them at the start of a tick ([`Scene::begin_tick`]) and sends every
//! removed object back to the editor, so that no shape is ever freed on the servo thread.
//!
//! Motion counts: `begin_tick` remembers each object's pose of the previous tick, so the
//! proxy tests its path in the object's frame between the two poses and a moving object
//! pushes the proxy instead of jumping over it.
//!
//! # Broad phase
//!
//! The scene keeps its objects' bounding spheres in a world broad phase (a hierarchical
//! loose hashed grid, see `broad.rs`), so that a tick asks only about the objects near the
//! proxy: `Scene::near` returns a superset of the objects whose bounding sphere meets a
//! box, and every per-tick query over objects goes through it (the proxy keeps the set
//! found on one tick for the next while nothing moved out of it, see
//! [`Proxy`](crate::proxy::Proxy)). Moving an object updates its cell in constant time;
//! every array of the broad phase, and the table from names to indices, is reserved for
//! the capacity when the scene is made, so no edit allocates on the servo thread. Only
//! the objects that moved since the previous tick are visited by [`Scene::begin_tick`]
//! and the carry. The answers are those of testing every object in index order, which
//! the property tests check against that linear path.

mod broad;
mod clear;
mod deform;
mod domain;
mod effect;
mod extent;
mod gltf;
mod handoff;
mod hit;
mod invalid;
mod material;
mod moves;
mod number;
mod object;
mod param;
mod pose;
mod removals;
mod shape;
mod spec;
mod texture;
mod texture_coords;
mod tool;
mod world;
mod zones_kept;

#[doc(hidden)]
pub use self::gltf::{GltfObject, GltfObjects, GltfSceneError, gltf_objects};
pub use deform::DeformError;
pub use domain::DEFAULT_MAX_FORCE_N;
#[doc(hidden)]
pub use domain::{ABSURD_DISTANCE_M, ABSURD_FORCE_N, ABSURD_STIFFNESS_N_PER_M};
#[doc(hidden)]
pub use domain::{Domain, DomainKind};
pub(crate) use effect::EffectKind;
#[doc(hidden)]
pub use effect::MAX_EFFECTS;
pub use effect::{Effect, Zone};
#[doc(hidden)]
pub use handoff::MAX_EDITS_PER_TICK;
pub use handoff::{Edit, EditError, Returned, SceneEditor};
pub(crate) use hit::{Hit, SurfaceRef};
pub use invalid::ParamError;
pub use material::{Material, MaterialBuilder};
#[doc(hidden)]
pub use moves::ObjectKey;
pub use object::{ObjectId, SceneObject, Sides};
pub use param::Param;
pub use pose::Pose;
pub use shape::{Shape, ShapeError};
pub use spec::SpecError;
pub(crate) use spec::{Spec, number};
pub(crate) use texture::Relief;
pub use texture::{HeightImage, Texture};
pub use world::Scene;

pub(crate) use broad::Near;
pub(crate) use clear::others_box;
#[allow(unused_imports)] // Used by the textures, which read it.
pub(crate) use texture_coords::UvPoint;
