//! The validation report: every defect of a mesh, with where it is.
//!
//! [`MeshReport::of`] never fails: a mesh with defects gets a report that lists them, and
//! [`MeshReport::usability`] says what haphe can do with it (a solid, only a two-sided
//! surface, or nothing).

mod analyse;
mod findings;
pub(crate) use analyse::analyse_with_edges;
pub use findings::{ComponentReport, Defects, EdgeUse, MeshReport, Usability};
mod nesting;
mod text;
#[doc(hidden)]
pub use text::ReportText;
use text::holes_text;

#[doc(hidden)]
pub use super::frame::{DEGENERATE_MAX_RELATIVE_HEIGHT, SLIVER_MAX_RELATIVE_HEIGHT};

use super::Mesh;

impl MeshReport {
    /// Validates `mesh` and lists every defect.
    ///
    /// # Performance
    /// `O(n log n)` in the number of triangles, parallel where it pays; about a tenth of a
    /// second per million triangles. Nesting of closed components (which decides whether
    /// a negative-volume component is a cavity or inside out) is computed when
    /// components × triangles stays below 2·10⁸.
    pub fn of(mesh: &Mesh) -> MeshReport {
        analyse::analyse(mesh)
    }

    /// What haphe can do with the mesh (the same as [`MeshReport::usable_as`]).
    pub fn usability(&self) -> Usability {
        self.usable_as
    }

    /// Why the mesh is not a valid closed solid, one sentence per reason (empty for a
    /// solid).
    pub fn problems(&self) -> Vec<String> {
        let holes = format!(
            "boundary edge(s): the mesh is open ({})",
            holes_text(&self.defects.holes)
        );
        let flips = &self.defects.faces_to_flip;
        let orientation = format!(
            "edge(s) between inconsistently oriented triangles: flip {} triangle(s) ({})",
            flips.len(),
            crate::mesh::repair::listed(flips)
        );
        let mut out = Vec::new();
        let mut say = |n: usize, what: &str| {
            if n > 0 {
                out.push(format!("{n} {what}"));
            }
        };
        say(self.boundary_edges, &holes);
        say(self.nonmanifold_edges, "non-manifold edge(s)");
        say(self.nonmanifold_vertices, "non-manifold vertex(es)");
        say(self.orientation_conflicts, &orientation);
        say(self.inverted_components, "inside-out component(s)");
        say(self.duplicate_faces, "duplicate face(s)");
        if self.usable_as == Usability::Unusable {
            out.push("no triangle has a usable area".to_owned());
        }
        out
    }
}
