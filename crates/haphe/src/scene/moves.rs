//! Moving objects: setting poses by name or by key, and the list of what moved since the
//! previous tick.
//!
//! A move costs a compare and a store when the object stays in its broad-phase cell: the
//! pose is stored, the largest squared shift of the tick is kept (its root is taken when
//! the proxy asks for it), the bounding sphere's cell is recomputed at the level the
//! object already has, and the object is appended to the list of moved objects, which
//! [`Scene::begin_tick`] walks to remember the poses of the previous tick. Only a change of
//! cell relinks the object in the broad phase.
//!
//! An [`ObjectKey`] names an object and remembers its index in the scene, so that moving
//! it needs no lookup by name while the indices stay the same (they change only when an
//! object is removed); on a stale index the key finds the object by name again.

use super::object::ObjectId;
use super::pose::Pose;
use super::world::Scene;

/// An object's name with the index where it was last found in a [`Scene`]: moves the object
/// by [`Scene::set_pose_keyed`] and [`Scene::set_poses`] without a lookup by name.
///
/// The index is a hint: a key is checked against the object's name at that index, and found
/// by name again (and updated) when the scene's indices changed, or when it was made before
/// the object was inserted. A key never moves another object than the one it names.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ObjectKey {
    id: ObjectId,
    index: u32,
}

impl ObjectKey {
    /// A key for the object named `id`, with no index yet: its first use finds it by name.
    pub const fn new(id: ObjectId) -> ObjectKey {
        ObjectKey {
            id,
            index: u32::MAX,
        }
    }

    /// The object's name.
    pub fn id(&self) -> ObjectId {
        self.id
    }
}

impl Scene {
    /// A key for the object named `id`, with its index now; `None` when there is no such
    /// object.
    pub fn key_of(&self, id: ObjectId) -> Option<ObjectKey> {
        self.index_of(id).map(|i| ObjectKey {
            id,
            index: i as u32,
        })
    }

    /// The index of the object named by `key`: its index when the object there has its
    /// name, otherwise found by name (and the key updated).
    #[inline]
    fn resolve(&self, key: &mut ObjectKey) -> Option<usize> {
        let i = key.index as usize;
        if self.objects.get(i).is_some_and(|o| o.id == key.id) {
            return Some(i);
        }
        let i = self.index_of(key.id)?;
        key.index = i as u32;
        Some(i)
    }

    /// Moves the object named `id` to `pose` (the motion since the previous tick is
    /// rendered). `false` when there is no such object.
    ///
    /// # Real-time
    /// Constant time: a lookup by name, then as [`Scene::set_pose_keyed`].
    pub fn set_pose(&mut self, id: ObjectId, pose: Pose) -> bool {
        match self.index_of(id) {
            Some(i) => {
                self.move_object(i, pose);
                true
            }
            None => false,
        }
    }

    /// Moves the object named by `key` to `pose`, as [`Scene::set_pose`] but without a
    /// lookup by name while the key's index is current (the key is updated when it is
    /// not). `false` when there is no such object.
    ///
    /// # Real-time
    /// Constant time: a compare and a store when the object stays in its broad-phase cell,
    /// a relink in the broad phase when it changes cell; unless objects are moved in
    /// decreasing index order within a tick (the list of moved objects is kept sorted).
    #[inline]
    pub fn set_pose_keyed(&mut self, key: &mut ObjectKey, pose: Pose) -> bool {
        match self.resolve(key) {
            Some(i) => {
                self.move_object(i, pose);
                true
            }
            None => false,
        }
    }

    /// Moves many objects, each as [`Scene::set_pose_keyed`] (keys updated in place), in
    /// the order given. Returns how many of the keys named an object of the scene.
    ///
    /// # Real-time
    /// Constant time per object, as [`Scene::set_pose_keyed`]; give the objects in
    /// increasing index order (the order of [`Scene::objects`]) for the cheapest path.
    pub fn set_poses(&mut self, moves: &mut [(ObjectKey, Pose)]) -> usize {
        let mut found = 0;
        for (key, pose) in moves.iter_mut() {
            found += usize::from(self.set_pose_keyed(key, *pose));
        }
        found
    }

    /// Moves object `i` (in range) to `pose`.
    #[inline]
    fn move_object(&mut self, i: usize, pose: Pose) {
        let o = &mut self.objects[i];
        let before = &o.previous_pose;
        let shift2 = pose.translation().distance_squared(before.translation());
        let turned =
            !(pose.is_unrotated() && before.is_unrotated()) && pose.rotation() != before.rotation();
        o.pose = pose;
        let centre = pose.to_world(o.shape.bound_centre());
        // A non-finite shift (never, for valid poses) counts as a turn: test every mover.
        self.turned |= turned || !shift2.is_finite();
        if shift2 > self.shift2 {
            self.shift2 = shift2;
        }
        if self.broad.update(i, centre) {
            self.epoch += 1;
        }
        if !self.in_moved[i] {
            self.mark_moved(i);
        }
    }

    /// Notes that object `i` moved this tick.
    #[inline]
    pub(super) fn mark_moved(&mut self, i: usize) {
        if self.in_moved[i] {
            return;
        }
        self.in_moved[i] = true;
        match self.moved.last() {
            Some(&last) if (last as usize) > i => self.insert_moved(i),
            // The capacity is reserved for every object, each listed at most once.
            _ => self.moved.push(i as u32),
        }
    }

    /// Lists object `i`, below the last one listed, in its place in the sorted list.
    #[cold]
    fn insert_moved(&mut self, i: usize) {
        let k = self.moved.binary_search(&(i as u32)).unwrap_or_else(|k| k);
        self.moved.insert(k, i as u32);
    }

    /// Takes object `i` (listed) off the list of moved objects.
    pub(super) fn unlist_moved(&mut self, i: usize) {
        if let Ok(k) = self.moved.binary_search(&(i as u32)) {
            self.moved.remove(k);
        }
        self.in_moved[i] = false;
    }

    /// Remembers the poses of the objects that moved as their previous poses, and empties
    /// the list of moved objects (the start of [`Scene::begin_tick`]).
    #[inline]
    pub(super) fn settle_moved(&mut self) {
        for &i in &self.moved {
            let o = &mut self.objects[i as usize];
            o.previous_pose = o.pose;
            self.in_moved[i as usize] = false;
        }
        self.moved.clear();
        self.shift2 = 0.0;
        self.turned = false;
    }
}
