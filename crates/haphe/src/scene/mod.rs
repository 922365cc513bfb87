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
mod domain;
mod gltf;
mod handoff;
mod invalid;
mod material;
mod moves;
mod number;
mod param;
mod pose;
mod removals;
mod shape;

pub use self::gltf::{GltfObject, GltfObjects, GltfSceneError, gltf_objects};
pub use domain::{ABSURD_DISTANCE_M, ABSURD_FORCE_N, ABSURD_STIFFNESS_N_PER_M, Domain, DomainKind};
pub use handoff::{Edit, EditError, Returned, SceneEditor};
pub use invalid::ParamError;
pub use material::{Material, MaterialBuilder};
pub use moves::ObjectKey;
pub use param::Param;
pub use pose::Pose;
pub use shape::Shape;

use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};

use glam::DVec3;
use rustc_hash::FxHashMap;

use broad::Broad;
pub(crate) use broad::Near;
pub(crate) use clear::others_box;
use removals::RemovalLog;

use crate::mesh::TriId;
use crate::query::{
    Crossing, Probe, SurfacePoint, WalkStatus, distance_to_segment, first_crossing_where,
    nearest_within, walk_to_nearest,
};

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
    /// How the surface feels.
    pub material: Material,
    /// Which sides of the surface can be touched.
    pub sides: Sides,
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
        }
    }

    /// The same object touched on `sides`.
    pub fn with_sides(mut self, sides: Sides) -> SceneObject {
        self.sides = sides;
        self
    }

    /// Whether the object moved since the previous tick.
    pub fn moved(&self) -> bool {
        self.pose != self.previous_pose
    }
}

/// A triangle of one of a scene's objects: the object's index in [`Scene::objects`] and
/// the triangle. What the proxy keeps from tick to tick (the surface it rests on, the
/// contact under it, the contact it holds) and what a hit met.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct SurfaceRef {
    /// Index of the object in the scene.
    pub object: usize,
    /// The triangle, in the object's surface.
    pub triangle: TriId,
}

/// Where a path first meets an object's surface, world frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Hit {
    /// Parameter along the move, `≥ 0`: a crossing within a probe's reach behind the start
    /// counts as 0, one within reach past the end exceeds 1 (see [`Probe`]).
    pub t: f64,
    /// Index of the object in the scene ([`Scene::objects`]).
    pub object: usize,
    /// The triangle met.
    pub triangle: TriId,
    /// The point met, metres, world frame.
    pub point: DVec3,
    /// Unit face normal of the triangle, world frame (out of a solid).
    pub normal: DVec3,
    /// Only the front of the surface is touched (its normal's side is the free side).
    pub one_sided: bool,
}

impl Hit {
    /// The triangle met.
    #[inline]
    pub(crate) fn surface(&self) -> SurfaceRef {
        SurfaceRef {
            object: self.object,
            triangle: self.triangle,
        }
    }

    /// The hit of object `i` at `pose` for `crossing`, found by the probe `probe` (object
    /// frame crossing, world frame hit).
    fn of_crossing(i: usize, pose: &Pose, probe: &Probe, crossing: &Crossing) -> Hit {
        Hit {
            t: probe.move_t(crossing.t),
            object: i,
            triangle: crossing.triangle,
            point: pose.to_world(crossing.point),
            normal: pose.vector_to_world(crossing.face_normal),
            one_sided: probe.entering_only,
        }
    }
}

/// The objects the proxy renders, owned by the servo thread.
///
/// Storage is reserved once ([`Scene::new`]); inserting beyond the capacity is refused,
/// never a reallocation.
#[derive(Debug)]
pub struct Scene {
    objects: Vec<SceneObject>,
    capacity: usize,
    inbox: Option<handoff::Inbox>,
    /// The broad phase over the objects' bounding spheres (slot `i` is object `i`).
    broad: Broad,
    /// Object index by name.
    ids: FxHashMap<u32, u32>,
    /// Indices of the objects whose pose was set since the last [`Scene::begin_tick`],
    /// increasing, each once; `in_moved` marks them.
    moved: Vec<u32>,
    in_moved: Vec<bool>,
    /// The square of the largest translation of a moved object since the previous tick,
    /// square metres, and whether a moved object turned (its path relative to a point is
    /// then not bounded by its translation).
    shift2: f64,
    turned: bool,
    /// A name for this scene, and a count of the changes to the broad phase's cells: a
    /// candidate set found for (`uid`, `epoch`) stays valid while both are the same.
    uid: u64,
    epoch: u64,
    /// The last removals (where the indices went).
    removals: RemovalLog,
}

/// The names of scenes (see `Scene::uid`).
static NEXT_UID: AtomicU64 = AtomicU64::new(1);

impl Scene {
    /// An empty scene with room for `capacity` objects, and the editor that other threads
    /// use to change it (it holds up to `capacity` pending edits).
    pub fn new(capacity: usize) -> (Scene, SceneEditor) {
        let capacity = capacity.max(1);
        let (inbox, editor) = handoff::channel(capacity);
        let mut scene = Scene::local(capacity);
        scene.inbox = Some(inbox);
        (scene, editor)
    }

    /// An empty scene edited only directly (no editor), with room for `capacity` objects.
    pub fn local(capacity: usize) -> Scene {
        let capacity = capacity.max(1);
        let mut ids = FxHashMap::default();
        // Twice the capacity: a table at most half full clears its removal marks in place
        // instead of growing, so that no insertion ever allocates.
        ids.reserve(2 * capacity);
        Scene {
            objects: Vec::with_capacity(capacity),
            capacity,
            inbox: None,
            broad: Broad::new(capacity),
            ids,
            moved: Vec::with_capacity(capacity),
            in_moved: Vec::with_capacity(capacity),
            shift2: 0.0,
            turned: false,
            uid: NEXT_UID.fetch_add(1, Ordering::Relaxed),
            epoch: 0,
            removals: RemovalLog::new(),
        }
    }

    /// The objects, in insertion order, except that removing an object puts the last one in
    /// its place.
    pub fn objects(&self) -> &[SceneObject] {
        &self.objects
    }

    /// The index of the object named `id`.
    pub fn index_of(&self, id: ObjectId) -> Option<usize> {
        self.ids.get(&id.0).map(|&i| i as usize)
    }

    /// Adds an object.
    ///
    /// # Errors
    /// [`EditError::Full`] at capacity, [`EditError::DuplicateId`] when the name is taken;
    /// the object is handed back.
    #[expect(
        clippy::result_large_err,
        reason = "the object comes back by value: boxing would allocate on the servo thread"
    )]
    pub fn insert(&mut self, object: SceneObject) -> Result<(), (EditError, SceneObject)> {
        if self.index_of(object.id).is_some() {
            return Err((EditError::DuplicateId, object));
        }
        if self.objects.len() >= self.capacity {
            return Err((EditError::Full, object));
        }
        let i = self.objects.len();
        self.ids.insert(object.id.0, i as u32);
        let (centre, radius) = sphere_of(&object);
        self.broad.push(centre, radius);
        self.in_moved.push(false);
        let moved = object.moved();
        self.objects.push(object);
        if moved {
            // Its path since the previous pose is not bounded by a shift: test every mover.
            self.turned = true;
            self.mark_moved(i);
        }
        self.epoch += 1;
        Ok(())
    }

    /// Removes the object named `id` and hands it back. The last object takes its index
    /// (the others keep theirs).
    ///
    /// # Real-time
    /// No allocation; constant time, plus a shift within the list of the objects moved
    /// this tick when the removed or the last object is in it.
    pub fn remove(&mut self, id: ObjectId) -> Option<SceneObject> {
        let i = self.ids.remove(&id.0)? as usize;
        let last = self.objects.len() - 1;
        self.broad.swap_remove(i);
        if self.in_moved[i] {
            self.unlist_moved(i);
        }
        if i != last {
            self.ids.insert(self.objects[last].id.0, i as u32);
            if self.in_moved[last] {
                self.unlist_moved(last);
                self.in_moved.swap_remove(i);
                self.mark_moved(i);
            } else {
                self.in_moved.swap_remove(i);
            }
        } else {
            self.in_moved.pop();
        }
        self.epoch += 1;
        self.removals.record(i, last);
        Some(self.objects.swap_remove(i))
    }

    /// Changes the material of the object named `id`. `false` when there is no such object.
    pub fn set_material(&mut self, id: ObjectId, material: Material) -> bool {
        self.index_of(id)
            .map(|i| self.objects[i].material = material)
            .is_some()
    }

    /// A superset of the objects whose bounding sphere (with its slack) comes within the
    /// box `lo..hi` (world frame, metres), in increasing index order; the whole scene
    /// when there are too many, or the box is very large.
    ///
    /// # Real-time
    /// No allocation; a bounded number of grid cells visited.
    pub(crate) fn near(&self, lo: DVec3, hi: DVec3) -> Near {
        self.broad.query(lo, hi)
    }

    /// [`Scene::near`] written into `near`.
    pub(crate) fn near_into(&self, lo: DVec3, hi: DVec3, near: &mut Near) {
        self.broad.query_into(lo, hi, near);
    }

    /// The last removals, so that indices kept from one tick to the next can follow them.
    pub(crate) fn removals(&self) -> &RemovalLog {
        &self.removals
    }

    /// A name of this scene and of the state of its broad phase: a [`Scene::near`] set
    /// stays valid while this is the same.
    pub(crate) fn broad_epoch(&self) -> (u64, u64) {
        (self.uid, self.epoch)
    }

    /// The indices of the objects whose pose was set since the last
    /// [`Scene::begin_tick`], increasing (a superset of those that [`SceneObject::moved`]).
    pub(crate) fn moved_indices(&self) -> &[u32] {
        &self.moved
    }

    /// A bound on how far any moved object's path reaches from where the object is now,
    /// metres: every moved object kept its rotation and moved at most this far since the
    /// previous tick. `None` when an object turned.
    pub(crate) fn moved_shift(&self) -> Option<f64> {
        (!self.turned).then(|| self.shift2.sqrt())
    }

    /// Starts a servo tick: remembers every pose as the previous one, then applies the
    /// edits sent by the [`SceneEditor`] (at most [`MAX_EDITS_PER_TICK`]). Returns how many
    /// edits were applied.
    ///
    /// Call it once per tick, before ticking the proxy.
    ///
    /// # Real-time
    /// No allocation, no lock, no shape freed here (removed objects go back to the
    /// editor); bounded by [`MAX_EDITS_PER_TICK`].
    pub fn begin_tick(&mut self) -> usize {
        self.settle_moved();
        let Some(mut inbox) = self.inbox.take() else {
            return 0;
        };
        let applied = inbox.apply(self);
        self.inbox = Some(inbox);
        applied
    }

    /// The first place where the proxy move `from → to` (world frame) meets object `i` at
    /// its current pose, tested with a [`Probe`] reaching `reach` metres beyond the move.
    /// `None` when it does not, or when `i` is out of range.
    ///
    /// # Real-time
    /// A bounding-sphere test, then [`first_crossing_where`] in the object frame.
    pub(crate) fn first_hit(&self, i: usize, from: DVec3, to: DVec3, reach: f64) -> Option<Hit> {
        let o = self.objects.get(i)?;
        let shape = &*o.shape;
        let one_sided = o.sides == Sides::Front;
        let probe = Probe::new(from, to, reach, one_sided);
        let centre = o.pose.to_world(shape.bound_centre());
        if distance_to_segment(centre, [probe.p0, probe.p1]) > shape.bound_radius() * BOUND_SLACK {
            return None;
        }
        let a = o.pose.to_object(probe.p0);
        let b = o.pose.to_object(probe.p1);
        first_crossing_where(shape.surface(), shape.map(), a, b, |h| {
            h.entering || !probe.entering_only
        })
        .map(|c| Hit::of_crossing(i, &o.pose, &probe, &c))
    }

    /// The triangle of object `i` nearest to the world point `p` among those within
    /// `radius` metres of it, as a [`Hit`] at the end of a move (`t = 1`) whose point is
    /// the triangle's point closest to `p`: how the proxy notices a surface it came to
    /// rest on (or within a probe's reach of) without crossing it. `None` when there is
    /// none, or when `i` is out of range.
    ///
    /// # Real-time
    /// A bounding-sphere test, then [`nearest_within`] in the object frame.
    pub(crate) fn touching(&self, i: usize, p: DVec3, radius: f64) -> Option<Hit> {
        let o = self.objects.get(i)?;
        let shape = &*o.shape;
        let centre = o.pose.to_world(shape.bound_centre());
        if p.distance(centre) > shape.bound_radius() * BOUND_SLACK + radius {
            return None;
        }
        let near = nearest_within(shape.surface(), shape.map(), o.pose.to_object(p), radius)?;
        Some(Hit {
            t: 1.0,
            object: i,
            triangle: near.triangle,
            point: o.pose.to_world(near.closest.point),
            normal: o
                .pose
                .vector_to_world(shape.surface().frame(near.triangle).normal),
            one_sided: o.sides == Sides::Front,
        })
    }

    /// Where the world point `p` was, relative to object `i`, at the previous tick,
    /// expressed at the object's current pose: `pose · previous_pose⁻¹ · p`. Equal to `p`
    /// for an object at rest (or out of range).
    pub(crate) fn previous_relative(&self, i: usize, p: DVec3) -> DVec3 {
        match self.objects.get(i) {
            Some(o) if o.moved() => o.pose.to_world(o.previous_pose.to_object(p)),
            _ => p,
        }
    }

    /// The locally nearest surface point to the world point `p` of the object of `start`,
    /// walking from its triangle (see [`walk_to_nearest`]); point and normals in the world
    /// frame. `None` when the object is out of range.
    pub(crate) fn surface_point(
        &self,
        start: SurfaceRef,
        p: DVec3,
    ) -> Option<(SurfacePoint, WalkStatus)> {
        let o = self.objects.get(start.object)?;
        let (mut s, status) =
            walk_to_nearest(o.shape.surface(), start.triangle, o.pose.to_object(p));
        s.point = o.pose.to_world(s.point);
        s.face_normal = o.pose.vector_to_world(s.face_normal);
        s.shading_normal = o.pose.vector_to_world(s.shading_normal);
        Some((s, status))
    }
}

/// The world bounding sphere of `o` at its pose, with its slack.
fn sphere_of(o: &SceneObject) -> (DVec3, f64) {
    let shape = &*o.shape;
    (
        o.pose.to_world(shape.bound_centre()),
        shape.bound_radius() * BOUND_SLACK,
    )
}

/// Relative slack on a shape's bounding sphere, covering the rounding of poses.
const BOUND_SLACK: f64 = 1.0 + 1e-7;

/// Most edits applied in one [`Scene::begin_tick`]; the rest wait for the next tick.
pub const MAX_EDITS_PER_TICK: usize = 16;
