//! Repairing a mesh into a closed solid, each change reported: vertices welded within a
//! tolerance, degenerate and duplicate triangles dropped, triangles flipped for a
//! consistent orientation, holes filled up to a size, and inside-out parts turned outward.
//! What `haphe repair` runs; the validation report names the same flips and holes
//! ([`Defects::faces_to_flip`](super::report::Defects::faces_to_flip),
//! [`Defects::holes`](super::report::Defects::holes)).

mod holes;
mod orient;

pub(crate) use holes::hole_loops;
pub(crate) use orient::faces_to_flip;

use super::edges::EdgeTable;
use super::report::{MeshReport, Usability};
use super::weld::{find, union};
use super::{Mesh, Weld, weld};

/// The largest hole [`repair`] fills by default, in edges: a missing quad has 4, a
/// missing fan around a vertex of valence 6 has 6; a larger opening is usually meant
/// (a pipe's end, a cut) and is refused unless asked for.
pub const DEFAULT_MAX_HOLE_EDGES: usize = 16;

/// The default weld tolerance of [`repair`], relative to the bounding box's diagonal:
/// vertices closer than a millionth of the model's size are one.
pub const DEFAULT_WELD_RELATIVE: f64 = 1e-6;

/// What [`repair`] may do.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RepairOptions {
    /// Vertices closer than this (metres) are welded; `None`:
    /// [`DEFAULT_WELD_RELATIVE`] times the bounding box's diagonal.
    pub weld_tolerance: Option<f64>,
    /// The largest hole filled, in edges; a larger one is refused
    /// ([`RepairError::HoleTooLarge`]).
    pub max_hole_edges: usize,
}

impl Default for RepairOptions {
    fn default() -> Self {
        RepairOptions {
            weld_tolerance: None,
            max_hole_edges: DEFAULT_MAX_HOLE_EDGES,
        }
    }
}

/// One change [`repair`] made. Triangle indices are those of the mesh given (its faces
/// in file order), vertex indices those after welding.
#[derive(Debug, Clone, PartialEq)]
pub enum Change {
    /// Vertices merged into another within `tolerance` metres (0 merged: said too, with
    /// the tolerance used).
    Welded {
        /// Vertices merged.
        merged: usize,
        /// The tolerance used, metres.
        tolerance: f64,
    },
    /// Triangles of (practically) no area or with a repeated vertex, dropped.
    DroppedDegenerate {
        /// The triangles.
        triangles: Vec<u32>,
    },
    /// Triangles with the same three vertices as an earlier one, dropped.
    DroppedDuplicate {
        /// The triangles.
        triangles: Vec<u32>,
    },
    /// Triangles flipped for a consistent orientation.
    Flipped {
        /// The triangles.
        triangles: Vec<u32>,
    },
    /// A hole closed.
    FilledHole {
        /// Its boundary's vertices (as many as its edges).
        vertices: Vec<u32>,
        /// The triangles added.
        triangles: usize,
    },
    /// A closed part whose normals pointed in, turned outward (every triangle flipped).
    TurnedOutward {
        /// Its triangles.
        triangles: Vec<u32>,
    },
}

impl std::fmt::Display for Change {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Change::Welded { merged, tolerance } => write!(
                f,
                "welded {merged} vertices into others within {tolerance:.3e} m"
            ),
            Change::DroppedDegenerate { triangles } => write!(
                f,
                "dropped {} degenerate triangle(s): {}",
                triangles.len(),
                listed(triangles)
            ),
            Change::DroppedDuplicate { triangles } => write!(
                f,
                "dropped {} duplicate triangle(s): {}",
                triangles.len(),
                listed(triangles)
            ),
            Change::Flipped { triangles } => write!(
                f,
                "flipped {} triangle(s) for a consistent orientation: {}",
                triangles.len(),
                listed(triangles)
            ),
            Change::FilledHole {
                vertices,
                triangles,
            } => write!(
                f,
                "filled a hole of {} edges (vertices {}) with {triangles} triangle(s)",
                vertices.len(),
                listed(vertices)
            ),
            Change::TurnedOutward { triangles } => write!(
                f,
                "turned an inside-out part of {} triangle(s) outward (first triangle {})",
                triangles.len(),
                triangles.first().copied().unwrap_or(0)
            ),
        }
    }
}

/// At most eight indices, then "… and N more".
pub(crate) fn listed(items: &[u32]) -> String {
    let shown: Vec<String> = items.iter().take(8).map(u32::to_string).collect();
    match items.len().saturating_sub(8) {
        0 => shown.join(" "),
        more => format!("{} … and {more} more", shown.join(" ")),
    }
}

/// Why [`repair`] made no mesh.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum RepairError {
    /// A hole larger than [`RepairOptions::max_hole_edges`].
    #[error(
        "a hole of {edges} edges (vertices {}) is larger than the limit of {limit} edges: \
         not filled",
        listed(vertices)
    )]
    HoleTooLarge {
        /// Its edges.
        edges: usize,
        /// Its boundary's vertices.
        vertices: Vec<u32>,
        /// The limit.
        limit: usize,
    },
    /// The weld tolerance is not a non-negative distance.
    #[error("the weld tolerance must be a non-negative distance in metres, not {0}")]
    WeldTolerance(f64),
    /// Problems no step fixes (non-manifold edges or vertices, parts inside others).
    #[error("not repaired into a closed solid: {}", problems.join("; "))]
    NotSolid {
        /// The validation's problems after the repair.
        problems: Vec<String>,
    },
}

/// A repaired mesh: a closed solid, with the changes that made it and its report.
#[derive(Debug, Clone)]
pub struct Repaired {
    /// The mesh (vertices welded, triangles kept in their order, then the holes' patches).
    pub mesh: Mesh,
    /// What was done, in order.
    pub changes: Vec<Change>,
    /// The repaired mesh's validation report (a [`Usability::Solid`]).
    pub report: MeshReport,
}

/// Repairs `mesh` into a closed solid: welds its vertices
/// ([`RepairOptions::weld_tolerance`]), drops degenerate and duplicate triangles, flips
/// the triangles that disagree with their neighbours (the smaller class of each part),
/// fills every hole of at most [`RepairOptions::max_hole_edges`] edges, and turns
/// inside-out parts outward, so the volume is positive and the normals point out.
///
/// # Errors
/// [`RepairError`]: a hole above the limit (nothing is filled), a bad tolerance, or a
/// defect no step repairs (the problems listed).
pub fn repair(mesh: &Mesh, options: &RepairOptions) -> Result<Repaired, RepairError> {
    let mut changes = Vec::new();
    // Weld.
    let tolerance = match options.weld_tolerance {
        Some(t) if t.is_finite() && t >= 0.0 => t,
        Some(t) => return Err(RepairError::WeldTolerance(t)),
        None => mesh
            .bounds()
            .map_or(0.0, |(lo, hi)| DEFAULT_WELD_RELATIVE * lo.distance(hi)),
    };
    let (mut mesh, stats) = weld(mesh, Weld::Tolerance(tolerance));
    changes.push(Change::Welded {
        merged: stats.merged,
        tolerance,
    });
    // The input index of every triangle kept.
    let mut origin: Vec<u32> = (0..mesh.triangles.len() as u32).collect();

    // Degenerate, then duplicate triangles.
    drop_unusable(&mut mesh, &mut origin, &mut changes);

    // Orientation.
    let flips = faces_to_flip(&mesh.triangles, &EdgeTable::build(&mesh.triangles));
    if !flips.is_empty() {
        for &t in &flips {
            mesh.triangles[t as usize].swap(1, 2);
        }
        changes.push(Change::Flipped {
            triangles: flips.iter().map(|&t| origin[t as usize]).collect(),
        });
    }

    // Holes: every one checked against the limit before any is filled.
    let loops = hole_loops(&EdgeTable::build(&mesh.triangles));
    if let Some(big) = loops.iter().find(|l| l.len() > options.max_hole_edges) {
        return Err(RepairError::HoleTooLarge {
            edges: big.len(),
            vertices: big.clone(),
            limit: options.max_hole_edges,
        });
    }
    for cycle in loops {
        let patch = holes::fill(&cycle, &mesh.vertices);
        changes.push(Change::FilledHole {
            vertices: cycle,
            triangles: patch.len(),
        });
        mesh.triangles.extend(patch);
    }

    // Inside-out closed parts turned outward.
    turn_outward(&mut mesh, &origin, &mut changes);
    let report = MeshReport::of(&mesh);
    if report.usable_as != Usability::Solid {
        return Err(RepairError::NotSolid {
            problems: report.problems(),
        });
    }
    Ok(Repaired {
        mesh,
        changes,
        report,
    })
}

/// Drops the degenerate triangles, then the duplicates, of `mesh` (with their entries of
/// `origin`), saying so in `changes`.
fn drop_unusable(mesh: &mut Mesh, origin: &mut Vec<u32>, changes: &mut Vec<Change>) {
    let report = MeshReport::of(mesh);
    let degenerate = report.defects.degenerate_triangles.clone();
    if !degenerate.is_empty() {
        let dropped = degenerate.iter().map(|&t| origin[t as usize]).collect();
        keep_except(mesh, origin, &degenerate);
        changes.push(Change::DroppedDegenerate { triangles: dropped });
    }
    let report = MeshReport::of(mesh);
    let duplicates: Vec<u32> = report
        .defects
        .duplicate_faces
        .iter()
        .map(|&[_, dup]| dup)
        .collect();
    if !duplicates.is_empty() {
        let dropped = duplicates.iter().map(|&t| origin[t as usize]).collect();
        keep_except(mesh, origin, &duplicates);
        changes.push(Change::DroppedDuplicate { triangles: dropped });
    }
}

/// Flips every triangle of each closed part of `mesh` whose normals point in (inside out,
/// not a cavity), saying so in `changes` (triangles named by `origin`, the patches by
/// their own index).
fn turn_outward(mesh: &mut Mesh, origin: &[u32], changes: &mut Vec<Change>) {
    let report = MeshReport::of(mesh);
    if report.defects.inverted_components.is_empty() {
        return;
    }
    let part = parts(&mesh.triangles);
    for &c in &report.defects.inverted_components {
        let Some(first) = report
            .component_list
            .get(c as usize)
            .map(|c| c.first_triangle)
        else {
            continue;
        };
        let which = part[first as usize];
        let members: Vec<u32> = (0..mesh.triangles.len() as u32)
            .filter(|&t| part[t as usize] == which)
            .collect();
        for &t in &members {
            mesh.triangles[t as usize].swap(1, 2);
        }
        changes.push(Change::TurnedOutward {
            triangles: members
                .iter()
                .map(|&t| origin.get(t as usize).copied().unwrap_or(t))
                .collect(),
        });
    }
}

/// Drops the triangles `drop` (sorted indices) from `mesh` and their entries of `origin`.
fn keep_except(mesh: &mut Mesh, origin: &mut Vec<u32>, drop: &[u32]) {
    let mut keep = vec![true; mesh.triangles.len()];
    for &t in drop {
        keep[t as usize] = false;
    }
    let mut i = 0;
    mesh.triangles.retain(|_| {
        i += 1;
        keep[i - 1]
    });
    let mut i = 0;
    origin.retain(|_| {
        i += 1;
        keep[i - 1]
    });
}

/// The part (triangles joined through shared edges) of every triangle, numbered by
/// union-find roots.
fn parts(triangles: &[[u32; 3]]) -> Vec<u32> {
    let table = EdgeTable::build(triangles);
    let mut parent: Vec<u32> = (0..triangles.len() as u32).collect();
    for group in table.groups() {
        for pair in group.windows(2) {
            union(&mut parent, pair[0].tri, pair[1].tri);
        }
    }
    (0..triangles.len() as u32)
        .map(|t| find(&mut parent, t))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::shapes;
    use glam::DVec3;

    /// A box of 12 triangles with the quad of triangles 0 and 1 missing, triangle 5
    /// flipped and triangle 7 given twice.
    fn broken_box() -> Mesh {
        let mut mesh = shapes::cuboid(DVec3::splat(0.1), [1, 1, 1]);
        mesh.triangles[5].swap(1, 2);
        let again = mesh.triangles[7];
        mesh.triangles.push(again);
        mesh.triangles.drain(0..2);
        mesh
    }

    #[test]
    fn a_flipped_face_a_missing_quad_and_a_duplicate_make_a_closed_solid() {
        let whole = shapes::cuboid(DVec3::splat(0.1), [1, 1, 1]);
        let volume = MeshReport::of(&whole).volume.expect("a solid");
        let broken = broken_box();
        let before = MeshReport::of(&broken);
        assert_eq!(before.usable_as, Usability::Surface);
        // Validation names what repair changes.
        assert_eq!(before.defects.faces_to_flip, vec![3]);
        assert_eq!(before.defects.holes.len(), 1);
        assert_eq!(before.defects.holes[0].len(), 4);
        let r = repair(&broken, &RepairOptions::default()).expect("repaired");
        assert_eq!(r.report.usable_as, Usability::Solid, "{}", r.report);
        assert!((r.report.volume.expect("closed") - volume).abs() < 1e-9 * volume);
        assert_eq!(r.mesh.triangles.len(), 12);
        let kinds: Vec<String> = r.changes.iter().map(ToString::to_string).collect();
        assert!(kinds[0].starts_with("welded 0 vertices"), "{kinds:?}");
        assert!(
            r.changes.contains(&Change::DroppedDuplicate {
                triangles: vec![10]
            }),
            "{kinds:?}"
        );
        assert!(
            r.changes.contains(&Change::Flipped { triangles: vec![3] }),
            "{kinds:?}"
        );
        assert!(
            r.changes
                .iter()
                .any(|c| matches!(c, Change::FilledHole { vertices, triangles: 2 } if vertices.len() == 4)),
            "{kinds:?}"
        );
    }

    #[test]
    fn an_inside_out_box_is_turned_and_a_large_hole_refused() {
        let mut mesh = shapes::cuboid(DVec3::splat(0.1), [1, 1, 1]);
        for t in mesh.triangles.iter_mut() {
            t.swap(1, 2);
        }
        let r = repair(&mesh, &RepairOptions::default()).expect("repaired");
        assert!(r.report.volume.is_some_and(|v| v > 0.0));
        assert!(
            matches!(&r.changes[1], Change::TurnedOutward { triangles } if triangles.len() == 12)
        );
        // A 4×4 face missing: a hole of 16 edges; the limit 8 refuses it.
        let mut open = shapes::cuboid(DVec3::splat(0.1), [4, 4, 4]);
        let before = open.triangles.len();
        let top = MeshReport::of(&open);
        assert_eq!(top.usable_as, Usability::Solid);
        open.triangles.truncate(before - 32);
        let loops = MeshReport::of(&open).defects.holes;
        assert_eq!(loops.len(), 1, "{loops:?}");
        let edges = loops[0].len();
        let limited = RepairOptions {
            max_hole_edges: edges - 1,
            ..RepairOptions::default()
        };
        // (The vertices of the removed face's interior are gone after welding, so the
        // indices differ from the report's.)
        assert!(matches!(
            repair(&open, &limited).map(|r| r.changes),
            Err(RepairError::HoleTooLarge { edges: e, vertices, limit })
                if e == edges && vertices.len() == edges && limit == edges - 1
        ));
        let filled = RepairOptions {
            max_hole_edges: edges,
            ..RepairOptions::default()
        };
        assert_eq!(
            repair(&open, &filled).expect("filled").report.usable_as,
            Usability::Solid
        );
    }

    #[test]
    fn near_coincident_vertices_are_welded_within_the_tolerance_stated() {
        let mut mesh = shapes::cuboid(DVec3::splat(0.1), [1, 1, 1]);
        // Triangle 0 gets its own copy of its first corner, 1 nm away.
        let v = mesh.triangles[0][0] as usize;
        mesh.vertices.push(mesh.vertices[v] + DVec3::splat(1e-9));
        mesh.triangles[0][0] = (mesh.vertices.len() - 1) as u32;
        assert!(!MeshReport::of(&mesh).closed);
        let r = repair(&mesh, &RepairOptions::default()).expect("repaired");
        let (lo, hi) = mesh.bounds().expect("vertices");
        let size = lo.distance(hi);
        assert_eq!(
            r.changes[0],
            Change::Welded {
                merged: 1,
                tolerance: DEFAULT_WELD_RELATIVE * size
            }
        );
        assert_eq!(r.report.usable_as, Usability::Solid);
    }
}
