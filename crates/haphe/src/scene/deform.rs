//! Deformation: a shape's vertices at new positions, its triangles unchanged. The new
//! shape is made off the servo thread; only what the moved triangles touch is recomputed
//! (frames, shading normals, map cells, clear zones), and the new shape shares the rest
//! with the old one, which stays as it was.

use std::sync::Arc;

use glam::DVec3;

use super::handoff::{EditError, Returned};
use super::object::{ObjectId, sphere_of};
use super::shape::Shape;
use super::world::Scene;
use crate::map::MapError;
use crate::mesh::MAX_COORDINATE;
use crate::par::on_this_thread;

/// Why a deformation was refused. The shape (or scene) is left unchanged.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum DeformError {
    /// Not one position per vertex.
    #[error("{given} vertex positions given, but the shape has {vertices} vertices")]
    Count {
        /// How many positions were given.
        given: usize,
        /// How many vertices the shape has.
        vertices: usize,
    },
    /// A subset's indices and positions differ in number.
    #[error("{indices} vertex indices but {positions} positions")]
    IndicesCount {
        /// How many indices were given.
        indices: usize,
        /// How many positions were given.
        positions: usize,
    },
    /// A vertex index is not one of the shape's.
    #[error("row {row}: vertex index {index} is out of range (the shape has {vertices} vertices)")]
    Index {
        /// The row of the subset.
        row: usize,
        /// The index given there.
        index: u64,
        /// How many vertices the shape has.
        vertices: usize,
    },
    /// A coordinate is NaN, infinite, or beyond the largest a mesh may have.
    #[error("row {row}: a coordinate is not a finite number within ±{MAX_COORDINATE} m")]
    NotFinite {
        /// The first row with such a coordinate.
        row: usize,
    },
    /// No object has this id.
    #[error("no object {0} in the scene")]
    UnknownObject(u32),
    /// The deformed surface left the map's grid and a grown grid would be too large.
    #[error(transparent)]
    Map(#[from] MapError),
}

impl Shape {
    /// The shape with its vertices at `vertices`: one position per vertex, in the order
    /// of [`Surface::vertices`](crate::mesh::Surface::vertices) (metres, object frame).
    /// The triangles, and the texture coordinates, stay; this shape is not changed (other
    /// objects may share it).
    ///
    /// Only what the moved triangles touch is recomputed: their frames, the shading
    /// normals around their corners, the map cells they leave and enter, and the clear
    /// zones they may reach (computed now, so that no tick computes one). A triangle
    /// moved outside the map's grid grows the grid (a rebuild of the map, with room to
    /// spare). The result answers every query as a shape built from scratch on the
    /// deformed mesh does. The work runs on the calling thread alone, never on rayon's
    /// pool, so that a servo loop on another core keeps its core.
    ///
    /// # Errors
    /// [`DeformError::Count`] for a wrong number of positions; [`DeformError::NotFinite`]
    /// naming the first bad row; [`DeformError::Map`] when a grown grid is too large.
    ///
    /// # Examples
    /// ```
    /// use haphe::map::MapOptions;
    /// use haphe::mesh::shapes;
    /// use haphe::scene::Shape;
    /// let shape = Shape::from_mesh("ball", shapes::sphere(0.05, 3), &MapOptions::default()).unwrap();
    /// let wider: Vec<_> = shape.surface().vertices().iter().map(|&p| 1.1 * p).collect();
    /// let breathed = shape.deformed(&wider).unwrap();
    /// assert_eq!(breathed.version(), shape.version() + 1);
    /// ```
    pub fn deformed(&self, vertices: &[DVec3]) -> Result<Shape, DeformError> {
        let count = self.surface.vertex_count();
        if vertices.len() != count {
            return Err(DeformError::Count {
                given: vertices.len(),
                vertices: count,
            });
        }
        check_finite(vertices)?;
        Ok(self.deformed_unchecked(vertices.to_vec())?)
    }

    /// The shape with the vertices `indices[i]` at `positions[i]`, the others where they
    /// are: [`Shape::deformed`] for a subset.
    ///
    /// # Errors
    /// [`DeformError::IndicesCount`] when the two lengths differ; [`DeformError::Index`]
    /// naming the first index out of range; those of [`Shape::deformed`].
    pub fn deformed_at(&self, indices: &[u32], positions: &[DVec3]) -> Result<Shape, DeformError> {
        if indices.len() != positions.len() {
            return Err(DeformError::IndicesCount {
                indices: indices.len(),
                positions: positions.len(),
            });
        }
        let count = self.surface.vertex_count();
        if let Some(row) = indices.iter().position(|&v| v as usize >= count) {
            return Err(DeformError::Index {
                row,
                index: u64::from(indices[row]),
                vertices: count,
            });
        }
        check_finite(positions)?;
        let mut vertices = self.surface.vertices().to_vec();
        for (&v, &p) in indices.iter().zip(positions) {
            vertices[v as usize] = p;
        }
        Ok(self.deformed_unchecked(vertices)?)
    }

    /// How many deformations made this shape from the one first built (0 for a shape
    /// that was never deformed).
    pub fn version(&self) -> u64 {
        self.version
    }

    /// [`Shape::deformed`] once the positions are checked, on the calling thread alone
    /// (see [`on_this_thread`]).
    fn deformed_unchecked(&self, vertices: Vec<DVec3>) -> Result<Shape, MapError> {
        on_this_thread(|| self.deformed_here(vertices))
    }

    /// [`Shape::deformed_unchecked`]'s work.
    fn deformed_here(&self, vertices: Vec<DVec3>) -> Result<Shape, MapError> {
        let (surface, moved) = self.surface.deformed(vertices);
        let map = self.map.refreshed(&self.surface, &surface, &moved)?;
        let mut shape = Shape::new(surface, map);
        shape.texture_coords = self.texture_coords.clone();
        shape.materials = self.materials.clone();
        shape.version = self.version + 1;
        shape.lineage = self.lineage;
        // Keep the zones no moved triangle can change; the others are computed now.
        let shape = shape.with_zones_kept(self, &moved, Some);
        Ok(shape)
    }
}

impl Scene {
    /// Deforms object `id`: its shape becomes [`Shape::deformed`] of `vertices` (one
    /// position per vertex of its surface, object frame). Other objects sharing the shape
    /// keep it as it was. The refresh runs here, on the caller's thread, and the
    /// deformation is in force from the next tick: a proxy resting on the surface rides
    /// it (it keeps its barycentric point on the triangle under it, at the same height),
    /// and a surface that moved over a proxy pushes it out (see [`Proxy`]).
    ///
    /// Call it between ticks on the thread that owns the scene; from another thread, make
    /// the shape there and send it with [`Edit::SetShape`](super::Edit::SetShape).
    ///
    /// # Errors
    /// [`DeformError::UnknownObject`], or those of [`Shape::deformed`]; the scene is then
    /// unchanged.
    ///
    /// [`Proxy`]: crate::proxy::Proxy
    pub fn deform(&mut self, id: ObjectId, vertices: &[DVec3]) -> Result<(), DeformError> {
        let i = self.index_of(id).ok_or(DeformError::UnknownObject(id.0))?;
        let shape = self.objects[i].shape.deformed(vertices)?;
        self.set_shape(i, Arc::new(shape), false);
        Ok(())
    }

    /// [`Scene::deform`] for a subset of the vertices: vertex `indices[k]` moves to
    /// `positions[k]` ([`Shape::deformed_at`]).
    ///
    /// # Errors
    /// [`DeformError::UnknownObject`], or those of [`Shape::deformed_at`]; the scene is
    /// then unchanged.
    pub fn deform_at(
        &mut self,
        id: ObjectId,
        indices: &[u32],
        positions: &[DVec3],
    ) -> Result<(), DeformError> {
        let i = self.index_of(id).ok_or(DeformError::UnknownObject(id.0))?;
        let shape = self.objects[i].shape.deformed_at(indices, positions)?;
        self.set_shape(i, Arc::new(shape), false);
        Ok(())
    }

    /// How many deformations the scene has applied.
    #[inline]
    pub(crate) fn deformations(&self) -> u64 {
        self.deformations
    }

    /// [`Edit::SetShape`](super::Edit::SetShape) on the servo thread: what goes back to
    /// the editor, a shape no longer used or the one refused.
    pub(super) fn replace_shape(&mut self, id: ObjectId, shape: Arc<Shape>) -> Option<Returned> {
        let Some(i) = self.index_of(id) else {
            return Some(Returned::RefusedShape(id, shape, EditError::UnknownObject));
        };
        match version_kind(&self.objects[i].shape, &shape) {
            Some(remeshed) => self
                .set_shape(i, shape, remeshed)
                .map(|s| Returned::Replaced(id, s)),
            None => Some(Returned::RefusedShape(
                id,
                shape,
                EditError::NotADeformation,
            )),
        }
    }

    /// Gives object `id` `shape`, a new version of its shape made on this thread: deformed
    /// ([`Shape::deformed`]) or with other triangles ([`Shape::replacing`]), in force from
    /// the next tick, as [`Edit::SetShape`](super::Edit::SetShape) does from another
    /// thread. Returns the shape replaced, if no proxy needs it any more.
    ///
    /// # Errors
    /// [`EditError::UnknownObject`]; [`EditError::NotADeformation`] for a shape that is
    /// neither a deformation of the object's nor a version replacing it. The scene is
    /// then unchanged.
    pub fn replace(
        &mut self,
        id: ObjectId,
        shape: Arc<Shape>,
    ) -> Result<Option<Arc<Shape>>, EditError> {
        let i = self.index_of(id).ok_or(EditError::UnknownObject)?;
        let remeshed =
            version_kind(&self.objects[i].shape, &shape).ok_or(EditError::NotADeformation)?;
        Ok(self.set_shape(i, shape, remeshed))
    }

    /// Gives object `i` `shape`, keeping the one the last tick saw as its previous shape
    /// (for a proxy to ride from); returns the shape no longer kept, if any.
    ///
    /// # Real-time
    /// No allocation; a relink in the broad phase.
    fn set_shape(&mut self, i: usize, shape: Arc<Shape>, remeshed: bool) -> Option<Arc<Shape>> {
        self.deformations += 1;
        let ticks = self.ticks;
        let o = &mut self.objects[i];
        let current = std::mem::replace(&mut o.shape, shape);
        // Deformed twice between two ticks: the shape in between was never seen.
        let unused = if o.previous_shape.is_some() && o.previous_since == ticks {
            Some(current)
        } else {
            o.previous_since = ticks;
            o.previous_shape.replace(current)
        };
        o.deformed_at = self.deformations;
        if remeshed {
            o.remeshed_at = self.deformations;
        }
        let (centre, radius) = sphere_of(o);
        self.broad.reshape(i, centre, radius);
        // The bounding sphere changed: sets of nearby objects kept from earlier ticks are
        // found again.
        self.epoch += 1;
        unused
    }
}

/// Whether `new` may follow `current` as an object's shape: `Some(false)` for a
/// deformation (the same counts of vertices and triangles), `Some(true)` for a version
/// made by [`Shape::replacing`] from the same first build, `None` otherwise.
fn version_kind(current: &Shape, new: &Shape) -> Option<bool> {
    let (old, now) = (current.surface(), new.surface());
    if new.remeshed && new.lineage == current.lineage {
        Some(true)
    } else if old.vertex_count() == now.vertex_count()
        && old.triangle_count() == now.triangle_count()
    {
        Some(false)
    } else {
        None
    }
}

/// The first row with a coordinate that is not finite or beyond [`MAX_COORDINATE`].
fn check_finite(positions: &[DVec3]) -> Result<(), DeformError> {
    match positions
        .iter()
        .position(|p| !(p.is_finite() && p.abs().max_element() <= MAX_COORDINATE))
    {
        Some(row) => Err(DeformError::NotFinite { row }),
        None => Ok(()),
    }
}
