//! Inside or outside by the non-zero winding rule: from the cell state, or by counting
//! signed crossings to a cell whose winding number is known.

use glam::DVec3;

use super::crossing::Tested;
use super::{Segment, intersect_segment_triangle};
use crate::map::{CellState, VoxelMap};
use crate::mesh::{Surface, TriId};

/// Whether a point is inside a solid.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    /// Outside the object (or anywhere off an open surface, which has no inside).
    Outside,
    /// Inside a closed solid: the winding number is not 0 (inside any of its closed parts,
    /// the non-zero rule).
    Inside,
}

/// How a classification was reached.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SideStatus {
    /// From the cell's state: no triangle tested.
    Cell,
    /// By counting signed crossings to a nearby cell of known winding number.
    Counted,
    /// No cell of known winding number within 4 cells (`MAX_SEARCH_RING`) or too many triangles on
    /// the way: the answer is the best guess (the nearest known cell's state; with none,
    /// inside when the cell borders an [overlap cell](VoxelMap::is_overlap)).
    BoundHit,
}

/// How far (in cells, Chebyshev rings) a surface-cell query searches for a cell whose
/// state is known.
pub const MAX_SEARCH_RING: u32 = 4;

/// Offset of the counting target inside the known cell, in cells from its centre: an
/// irrational-looking vector so the counting segment is rarely parallel to the
/// axis-aligned faces of CAD meshes. (The count is exact either way — a face seen edge-on
/// is never hit and its neighbours catch the crossing — but segments off the faces' planes
/// stay on the fast path of the segment test.)
const TARGET_JITTER: [f64; 3] = [0.123_456_7, -0.176_543_2, 0.211_111_3];

/// Classifies `p` (metres, object frame) as inside or outside the surface.
///
/// Inside means a winding number other than 0 (the non-zero rule): a point inside any of
/// a mesh's closed parts is inside, also where parts overlap; a cavity (a part inside
/// another, facing inwards) is outside. (A mesh with an inside-out part on its own is not
/// a solid, [`Surface::is_solid`], and has no inside.)
///
/// Beyond the surface's bounding box ([`Surface::bounds`]) the point is outside; outside
/// the grid and in outside/inside cells the cell answers. In a surface cell of a solid,
/// the segment from `p` to a point in the nearest cell of known winding number (an outside
/// cell, 0, or an inside cell that is not an [overlap cell](VoxelMap::is_overlap), 1) is
/// tested against the cell's triangles with the watertight test, and each crossing adds
/// one (leaving a part) or subtracts one (entering it) to that cell's winding number to
/// give `p`'s. Points exactly on the surface may go either way. An open (non-solid)
/// surface has no inside.
///
/// # Real-time
/// No allocation, no lock, no panic; at most `(2·MAX_SEARCH_RING + 1)³` cell lookups and
/// one bounded segment walk.
pub fn classify_point(surface: &Surface, map: &VoxelMap, p: DVec3) -> (Side, SideStatus) {
    if super::bounds::beyond_bounds(surface, p, p, 0.0) {
        return (Side::Outside, SideStatus::Cell);
    }
    let Some(cell) = map.grid().cell_of(p) else {
        return (Side::Outside, SideStatus::Cell);
    };
    match map.state(cell) {
        CellState::Outside => return (Side::Outside, SideStatus::Cell),
        CellState::Inside => return (Side::Inside, SideStatus::Cell),
        CellState::Surface => {}
    }
    if !surface.is_solid() {
        return (Side::Outside, SideStatus::Cell);
    }
    let Some((known, state)) = map.nearest_known_cell(cell, MAX_SEARCH_RING) else {
        // No cell of known winding near: inside if the cell borders where parts overlap.
        let guess = if map.borders_overlap(cell) {
            Side::Inside
        } else {
            Side::Outside
        };
        return (guess, SideStatus::BoundHit);
    };
    let (known_side, known_winding) = if state == CellState::Inside {
        (Side::Inside, 1i64)
    } else {
        (Side::Outside, 0)
    };
    let h = map.grid().cell_size();
    let target = map.grid().cell_centre(known) + DVec3::from_array(TARGET_JITTER) * h;
    let segment = Segment::new(p, target);
    let mut tested = Tested::new();
    // The winding number of `p`: the target's, plus one per part the segment leaves, minus
    // one per part it enters.
    let mut winding = known_winding;
    let margin = super::crossing::plane_margin(map);
    map.cast_segment(p, target, false, |part| {
        for &t in part.triangles {
            if tested.insert(t)
                && !super::crossing::cannot_cross(surface, t, p, target, margin)
                && let Some(hit) = intersect_segment_triangle(&segment, surface.corners(TriId(t)))
            {
                winding += if hit.entering { -1 } else { 1 };
            }
        }
        None
    });
    if tested.overflowed() {
        return (known_side, SideStatus::BoundHit);
    }
    let side = if winding != 0 {
        Side::Inside
    } else {
        Side::Outside
    };
    (side, SideStatus::Counted)
}
