//! The indexed triangle mesh every reader returns.

use glam::DVec3;

use super::limits::MAX_COORDINATE;
use super::{Place, ReadErrorKind};

/// An indexed triangle mesh: positions in metres (object frame) and vertex triples.
///
/// This is plain data with no invariant beyond what [`read_mesh`](super::read_mesh) guarantees: every index is
/// in range and every coordinate is finite. It may be open, non-manifold, inconsistently
/// oriented or degenerate; [`MeshReport::of`](super::MeshReport::of) says which, and [`Surface::new`](super::Surface::new) turns it into
/// the navigable form.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Mesh {
    /// Vertex positions, metres, object frame.
    pub vertices: Vec<DVec3>,
    /// Triangles as vertex indices, counter-clockwise seen from outside.
    pub triangles: Vec<[u32; 3]>,
}

impl Mesh {
    /// The three corner positions of triangle `t` (metres, object frame).
    ///
    /// # Panics
    /// If `t` or one of its indices is out of range (never for a mesh from [`read_mesh`](super::read_mesh)).
    #[inline]
    pub fn corners(&self, t: usize) -> [DVec3; 3] {
        let [a, b, c] = self.triangles[t];
        [
            self.vertices[a as usize],
            self.vertices[b as usize],
            self.vertices[c as usize],
        ]
    }

    /// Axis-aligned bounding box `(min, max)` of the vertices, metres; `None` when empty.
    pub fn bounds(&self) -> Option<(DVec3, DVec3)> {
        let first = *self.vertices.first()?;
        Some(
            self.vertices
                .iter()
                .fold((first, first), |(lo, hi), &p| (lo.min(p), hi.max(p))),
        )
    }

    /// Checks the invariants a reader guarantees: indices in range, coordinates finite and
    /// within [`MAX_COORDINATE`].
    ///
    /// # Errors
    /// The first vertex with a non-finite or too large coordinate, or triangle with an
    /// index out of range.
    pub fn check_indices_and_finite(&self) -> Result<(), ReadErrorKind> {
        if let Some(v) = self.vertices.iter().position(|p| !p.is_finite()) {
            return Err(ReadErrorKind::NonFinite {
                at: Place::Vertex(v),
            });
        }
        if let Some((v, p)) = self
            .vertices
            .iter()
            .enumerate()
            .find(|(_, p)| p.abs().max_element() > MAX_COORDINATE)
        {
            return Err(ReadErrorKind::CoordinateTooLarge {
                at: Place::Vertex(v),
                value: p.abs().max_element(),
            });
        }
        let count = self.vertices.len();
        for (face, tri) in self.triangles.iter().enumerate() {
            if let Some(&index) = tri.iter().find(|&&i| i as usize >= count) {
                return Err(ReadErrorKind::IndexOutOfRange {
                    at: Place::Face(face),
                    index: i64::from(index),
                    count,
                });
            }
        }
        Ok(())
    }
}
