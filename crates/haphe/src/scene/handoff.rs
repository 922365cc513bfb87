//! The wait-free hand-off of scene edits from other threads to the servo thread.

use std::sync::Arc;

use rtrb::{Consumer, Producer, RingBuffer};

use super::material::Material;
use super::object::{ObjectId, SceneObject};
use super::pose::Pose;
use super::shape::Shape;

/// Most edits applied in one [`Scene::begin_tick`](super::Scene::begin_tick); the rest wait for the next tick.
pub const MAX_EDITS_PER_TICK: usize = 16;

/// A change to a scene, sent from another thread.
#[derive(Debug)]
pub enum Edit {
    /// Add an object (refused, and handed back, when the scene is full or the name taken).
    Insert(SceneObject),
    /// Remove the object with this name (it is handed back to the editor).
    Remove(ObjectId),
    /// Move an object; the motion since the previous tick is rendered.
    SetPose(ObjectId, Pose),
    /// Change how an object feels.
    SetMaterial(ObjectId, Material),
    /// Give an object a new version of its shape, made on the editor's thread: deformed
    /// ([`Shape::deformed`]) or with other triangles ([`Shape::replacing`]); the refresh
    /// is done before the edit is sent. In force from the first tick that applies it;
    /// the version it replaces comes back ([`Returned::Replaced`]). Refused, and handed
    /// back, for an unknown object, or a shape that is neither a deformation (same counts
    /// of vertices and triangles) nor a version replacing the object's.
    SetShape(ObjectId, Arc<Shape>),
}

/// Why an edit was refused.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum EditError {
    /// The scene holds as many objects as it has room for.
    #[error("the scene is full")]
    Full,
    /// Another object has that name.
    #[error("an object with that id is already in the scene")]
    DuplicateId,
    /// Too many edits are waiting for the servo thread; try again after a tick.
    #[error("too many edits are waiting for the servo thread")]
    Busy,
    /// No object has that id.
    #[error("no object with that id is in the scene")]
    UnknownObject,
    /// A shape sent as a new version has other counts of vertices or triangles than the
    /// object's, and was not made by [`Shape::replacing`] from a version of it.
    #[error(
        "the shape is not a new version of the object's: other counts of vertices or \
         triangles, and not made to replace it"
    )]
    NotADeformation,
}

/// What comes back from the servo thread: removed objects, refused insertions, replaced
/// and refused shapes.
#[derive(Debug)]
#[non_exhaustive]
pub enum Returned {
    /// An object removed from the scene.
    Removed(SceneObject),
    /// An insertion the scene refused, and why.
    Refused(SceneObject, EditError),
    /// The shape an object had before a [`Edit::SetShape`], to be dropped off the servo
    /// thread.
    Replaced(ObjectId, Arc<Shape>),
    /// A shape the scene refused as a deformation, and why.
    RefusedShape(ObjectId, Arc<Shape>, EditError),
}

/// The servo thread's end of the hand-off.
#[derive(Debug)]
pub(super) struct Inbox {
    edits: Consumer<Edit>,
    returns: Producer<Returned>,
}

/// Changes a [`Scene`](super::Scene) from another thread: edits go through a wait-free ring buffer and are
/// applied at the start of the next servo tick; objects leaving the scene come back here
/// to be dropped ([`SceneEditor::collect`]), so no shape is ever freed on the servo thread.
#[derive(Debug)]
pub struct SceneEditor {
    edits: Producer<Edit>,
    returns: Consumer<Returned>,
}

pub(super) fn channel(capacity: usize) -> (Inbox, SceneEditor) {
    let (edit_tx, edit_rx) = RingBuffer::new(capacity);
    // Every edit can return at most one object, so this ring never refuses one that the
    // edit ring accepted, as long as the editor collects.
    let (ret_tx, ret_rx) = RingBuffer::new(capacity);
    (
        Inbox {
            edits: edit_rx,
            returns: ret_tx,
        },
        SceneEditor {
            edits: edit_tx,
            returns: ret_rx,
        },
    )
}

impl SceneEditor {
    /// Sends an edit to the servo thread.
    ///
    /// # Errors
    /// [`EditError::Busy`] when the ring is full (the servo thread is not ticking, or the
    /// editor does not [`collect`](SceneEditor::collect)); the edit is handed back.
    #[expect(
        clippy::result_large_err,
        reason = "the edit comes back by value: boxing would allocate"
    )]
    pub fn send(&mut self, edit: Edit) -> Result<(), (EditError, Edit)> {
        self.edits
            .push(edit)
            .map_err(|rtrb::PushError::Full(e)| (EditError::Busy, e))
    }

    /// Takes back the objects that left the scene (removed, or refused insertions), so
    /// that they are dropped on this thread. Call it regularly.
    pub fn collect(&mut self) -> Vec<Returned> {
        let mut out = Vec::new();
        while let Ok(r) = self.returns.pop() {
            out.push(r);
        }
        out
    }

    /// Edits sent and not yet applied.
    pub fn pending(&self) -> usize {
        self.edits.buffer().capacity() - self.edits.slots()
    }
}

impl Inbox {
    /// The next edit, when one waits and the return ring has room for what it may hand
    /// back (an edit that may hand an object back waits while the ring is full).
    #[inline]
    pub(super) fn next(&mut self) -> Option<Edit> {
        if self.returns.slots() == 0 {
            return None;
        }
        self.edits.pop().ok()
    }

    /// Hands an object back to the editor.
    #[inline]
    pub(super) fn give_back(&mut self, back: Returned) {
        // A slot was free before the edit was taken (see `next`) and only this thread
        // fills the ring.
        let _ = self.returns.push(back);
    }
}
