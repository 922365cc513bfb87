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

#[doc(hidden)]
pub use super::frame::{DEGENERATE_MAX_RELATIVE_HEIGHT, SLIVER_MAX_RELATIVE_HEIGHT};

use super::Mesh;

/// "1 hole of 4 edges", "3 holes (of 4, 4 and 12 edges)".
pub(crate) fn holes_text(holes: &[Vec<u32>]) -> String {
    match holes {
        [] => "no hole".to_owned(),
        [one] => format!("1 hole of {} edges", one.len()),
        many => {
            let mut sizes: Vec<String> = many.iter().take(8).map(|h| h.len().to_string()).collect();
            if many.len() > 8 {
                sizes.push(format!("… {} more", many.len() - 8));
            }
            let last = sizes.pop().unwrap_or_default();
            format!(
                "{} holes (of {} and {last} edges)",
                many.len(),
                sizes.join(", ")
            )
        }
    }
}

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
