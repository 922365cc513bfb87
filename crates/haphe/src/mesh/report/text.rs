//! The human-readable form of a report (what `haphe validate` prints).

use std::fmt;

use super::findings::{MeshReport, Usability};

/// How many places of each defect the text lists before "… and N more".
const LISTED: usize = 8;

/// Text shown as it is by [`list`] (which shows its items' `Debug` form).
struct Verbatim(String);

impl fmt::Debug for Verbatim {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

fn list<T: fmt::Debug>(f: &mut fmt::Formatter<'_>, what: &str, items: &[T]) -> fmt::Result {
    if items.is_empty() {
        return Ok(());
    }
    write!(f, "  {what} ({}):", items.len())?;
    for item in items.iter().take(LISTED) {
        write!(f, " {item:?}")?;
    }
    if items.len() > LISTED {
        write!(f, " … and {} more", items.len() - LISTED)?;
    }
    writeln!(f)
}

/// The text of a report whose surface is known to pass through itself or not (found with
/// the voxel map, [`self_intersections`](crate::query::self_intersections), which the
/// report alone does not run): see [`MeshReport::text`].
pub struct ReportText<'a> {
    report: &'a MeshReport,
    passes_through_itself: bool,
}

impl MeshReport {
    /// The text `haphe validate` prints; a closed, manifold, oriented surface that
    /// `passes_through_itself` gets the verdict that it is not a valid solid after all
    /// (inside and outside are not defined where it does).
    pub fn text(&self, passes_through_itself: bool) -> ReportText<'_> {
        ReportText {
            report: self,
            passes_through_itself,
        }
    }
}

impl fmt::Display for MeshReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.text(false).fmt(f)
    }
}

impl fmt::Display for ReportText<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let verdict = match self.report.usable_as {
            Usability::Solid if self.passes_through_itself => {
                "not a valid solid: closed, but it passes through itself"
            }
            Usability::Solid => "a valid closed solid",
            Usability::Surface => "usable only as an open (two-sided) surface",
            Usability::Unusable => "unusable",
        };
        let report = self.report;
        writeln!(f, "  verdict: {verdict}")?;
        writeln!(
            f,
            "  {} triangles, {} vertices, {} edges, {} component(s), {}",
            report.triangles,
            report.vertices,
            report.edges,
            report.components,
            if report.closed { "closed" } else { "open" }
        )?;
        let [x0, y0, z0] = report.bounds_min;
        let [x1, y1, z1] = report.bounds_max;
        writeln!(
            f,
            "  bounds: [{x0:.6}, {y0:.6}, {z0:.6}] .. [{x1:.6}, {y1:.6}, {z1:.6}] m  (size {:.6} x {:.6} x {:.6} m)",
            x1 - x0,
            y1 - y0,
            z1 - z0
        )?;
        write!(f, "  area: {:.6e} m²", report.area)?;
        match report.volume {
            Some(v) => write!(f, ", volume: {v:.6e} m³")?,
            None => write!(f, ", volume: none (not a closed, oriented surface)")?,
        }
        match report.genus {
            Some(g) => writeln!(f, ", genus: {g}")?,
            None => writeln!(f)?,
        }
        let d = &report.defects;
        if !d.holes.is_empty() {
            writeln!(f, "  holes: {}", holes_text(&d.holes))?;
        }
        list(f, "boundary edges", &d.boundary_edges)?;
        // An edge shared by thousands of triangles shows its first few and their count.
        let edges = |uses: &[super::EdgeUse]| {
            uses.iter()
                .map(|u| {
                    let shown: Vec<String> =
                        u.triangles.iter().take(8).map(u32::to_string).collect();
                    let more = u.triangles.len().saturating_sub(8);
                    let tail = if more > 0 {
                        format!(", … {more} more")
                    } else {
                        String::new()
                    };
                    (u.edge, Verbatim(format!("[{}{tail}]", shown.join(", "))))
                })
                .collect::<Vec<_>>()
        };
        list(
            f,
            "non-manifold edges [edge] [triangles]",
            &edges(&d.nonmanifold_edges),
        )?;
        list(f, "non-manifold vertices", &d.nonmanifold_vertices)?;
        list(
            f,
            "orientation conflicts [edge] [triangles]",
            &edges(&d.orientation_conflicts),
        )?;
        list(
            f,
            "triangles to flip for a consistent orientation",
            &d.faces_to_flip,
        )?;
        list(f, "inside-out components", &d.inverted_components)?;
        list(
            f,
            "solids nested inside another solid (overlapping parts)",
            &d.nested_solids,
        )?;
        list(f, "degenerate triangles", &d.degenerate_triangles)?;
        list(f, "sliver triangles", &d.sliver_triangles)?;
        list(f, "duplicate faces [first, duplicate]", &d.duplicate_faces)?;
        Ok(())
    }
}

/// "1 hole of 4 edges", "3 holes (of 4, 4 and 12 edges)".
pub(super) fn holes_text(holes: &[Vec<u32>]) -> String {
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
