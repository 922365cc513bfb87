//! The [`Scene`]: the objects the servo thread owns, their names, the broad phase over
//! their bounding spheres, and the end of the edit hand-off that applies edits.

use std::sync::atomic::{AtomicU64, Ordering};

use glam::DVec3;
use rustc_hash::FxHashMap;

use super::broad::{Broad, Near};
use super::effect::{Effect, MAX_EFFECTS};
use super::handoff::{self, Edit, Inbox, MAX_EDITS_PER_TICK, Returned, SceneEditor};
use super::hit::{Hit, SurfaceRef};
use super::object::Sides;
use super::object::{BOUND_SLACK, ObjectId, SceneObject, sphere_of};
use super::removals::RemovalLog;
use super::{EditError, Material, Texture};
use crate::query::{
    Probe, SurfacePoint, WalkStatus, distance_to_segment, first_crossing_where,
    nearest_within_bounded, walk_to_nearest,
};

/// The objects the proxy renders, owned by the servo thread.
///
/// Storage is reserved once ([`Scene::new`]); inserting beyond the capacity is refused,
/// never a reallocation.
#[derive(Debug)]
pub struct Scene {
    pub(super) objects: Vec<SceneObject>,
    pub(super) capacity: usize,
    pub(super) inbox: Option<Inbox>,
    /// The broad phase over the objects' bounding spheres (slot `i` is object `i`).
    pub(super) broad: Broad,
    /// Object index by name.
    pub(super) ids: FxHashMap<u32, u32>,
    /// Indices of the objects whose pose was set since the last [`Scene::begin_tick`],
    /// increasing, each once; `in_moved` marks them.
    pub(super) moved: Vec<u32>,
    pub(super) in_moved: Vec<bool>,
    /// The square of the largest translation of a moved object since the previous tick,
    /// square metres, and whether a moved object turned (its path relative to a point is
    /// then not bounded by its translation).
    pub(super) shift2: f64,
    pub(super) turned: bool,
    /// A name for this scene, and a count of the changes to the broad phase's cells: a
    /// candidate set found for (`uid`, `epoch`) stays valid while both are the same.
    pub(super) uid: u64,
    pub(super) epoch: u64,
    /// The last removals (where the indices went).
    pub(super) removals: RemovalLog,
    /// The force effects (room for `MAX_EFFECTS`, reserved).
    pub(super) effects: Vec<Effect>,
    /// How many deformations the scene has applied (see [`Scene::deform`]).
    pub(super) deformations: u64,
    /// How many ticks the scene has begun.
    pub(super) ticks: u64,
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
            effects: Vec::with_capacity(MAX_EFFECTS),
            deformations: 0,
            ticks: 0,
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

    /// Changes the texture of the object named `id` (`None`: none). `false` when there is
    /// no such object.
    pub fn set_texture(&mut self, id: ObjectId, texture: Option<Texture>) -> bool {
        self.index_of(id)
            .map(|i| self.objects[i].texture = texture)
            .is_some()
    }

    /// Adds a force effect (see [`Effect`]).
    ///
    /// # Errors
    /// [`EditError::Full`] when the scene holds `MAX_EFFECTS` (16) already.
    pub fn add_effect(&mut self, effect: Effect) -> Result<(), EditError> {
        if self.effects.len() >= MAX_EFFECTS {
            return Err(EditError::Full);
        }
        self.effects.push(effect);
        Ok(())
    }

    /// The force effects, in the order added.
    pub fn effects(&self) -> &[Effect] {
        &self.effects
    }

    /// Removes every force effect.
    pub fn clear_effects(&mut self) {
        self.effects.clear();
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
        self.ticks += 1;
        let Some(mut inbox) = self.inbox.take() else {
            return 0;
        };
        let applied = self.apply_edits(&mut inbox);
        self.inbox = Some(inbox);
        applied
    }

    /// Applies at most [`MAX_EDITS_PER_TICK`] edits from `inbox`, handing back what
    /// leaves the scene.
    fn apply_edits(&mut self, inbox: &mut Inbox) -> usize {
        let mut applied = 0;
        while applied < MAX_EDITS_PER_TICK {
            let Some(edit) = inbox.next() else { break };
            applied += 1;
            let back = match edit {
                Edit::Insert(object) => self
                    .insert(object)
                    .err()
                    .map(|(why, o)| Returned::Refused(o, why)),
                Edit::Remove(id) => self.remove(id).map(Returned::Removed),
                Edit::SetPose(id, pose) => {
                    self.set_pose(id, pose);
                    None
                }
                Edit::SetMaterial(id, material) => {
                    self.set_material(id, material);
                    None
                }
                Edit::SetShape(id, shape) => self.replace_shape(id, shape),
            };
            if let Some(back) = back {
                inbox.give_back(back);
            }
        }
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
    /// A bounding-sphere test, then [`nearest_within_bounded`] in the object frame.
    pub(crate) fn touching(&self, i: usize, p: DVec3, radius: f64) -> Option<Hit> {
        let o = self.objects.get(i)?;
        let shape = &*o.shape;
        let centre = o.pose.to_world(shape.bound_centre());
        if p.distance(centre) > shape.bound_radius() * BOUND_SLACK + radius {
            return None;
        }
        let near =
            nearest_within_bounded(shape.surface(), shape.map(), o.pose.to_object(p), radius)?;
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
    /// frame. `None` when the object is out of range. Always inlined: the tick calls it once,
    /// and a call returns the surface point through memory.
    #[inline(always)]
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
