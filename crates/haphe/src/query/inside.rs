//! Inside or outside: from the cell state, or by counting crossings to a cell whose state
//! is known.

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
    /// Inside a closed solid.
    Inside,
}

/// How a classification was reached.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SideStatus {
    /// From the cell's state: no triangle tested.
    Cell,
    /// By counting crossings to a nearby cell of known state.
    Counted,
    /// No known cell within [`MAX_SEARCH_RING`] or too many triangles on the way: the
    /// answer is the best guess (the nearest known cell's state).
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
/// Beyond the surface's bounding box ([`Surface::bounds`]) the point is outside; outside
/// the grid and in outside/inside cells the cell answers. In a surface cell of a
/// solid, crossings of the segment from `p` to a point in the nearest non-surface cell are
/// counted with the watertight test: an odd count flips that cell's state. Points exactly
/// on the surface may go either way. An open (non-solid) surface has no inside.
///
/// # Real-time
/// No allocation, no lock, no panic; at most `(2·MAX_SEARCH_RING + 1)³` cell lookups and
/// one bounded segment walk.
pub fn classify_point(surface: &Surface, map: &VoxelMap, p: DVec3) -> (Side, SideStatus) {
    if super::beyond_bounds(surface, p, p, 0.0) {
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
    let Some((known, state)) = nearest_known_cell(map, cell) else {
        return (Side::Outside, SideStatus::BoundHit);
    };
    let known_side = if state == CellState::Inside {
        Side::Inside
    } else {
        Side::Outside
    };
    let h = map.grid().cell_size();
    let target = map.grid().cell_centre(known) + DVec3::from_array(TARGET_JITTER) * h;
    let segment = Segment::new(p, target);
    let mut tested = Tested::new();
    let mut crossings = 0usize;
    let margin = super::crossing::plane_margin(map);
    for visit in map.grid().walk(p, target) {
        for &t in map.triangles_in(visit.cell) {
            if tested.insert(t)
                && !super::crossing::cannot_cross(surface, t, p, target, margin)
                && intersect_segment_triangle(&segment, surface.corners(TriId(t))).is_some()
            {
                crossings += 1;
            }
        }
    }
    if tested.overflowed() {
        return (known_side, SideStatus::BoundHit);
    }
    let side = match (known_side, crossings % 2 == 1) {
        (s, false) => s,
        (Side::Inside, true) => Side::Outside,
        (Side::Outside, true) => Side::Inside,
    };
    (side, SideStatus::Counted)
}

/// The nearest cell (by Chebyshev ring, then by index order) that is not a surface cell.
fn nearest_known_cell(map: &VoxelMap, cell: [u32; 3]) -> Option<([u32; 3], CellState)> {
    let dims = map.grid().dims().map(i64::from);
    let c = cell.map(i64::from);
    // The six face neighbours first, in the order the ring below visits them: the nearest
    // cells of the first ring, so the first known one is what the whole ring would give.
    for (axis, step) in [(0, -1), (1, -1), (2, -1), (2, 1), (1, 1), (0, 1)] {
        let mut n = c;
        n[axis] += step;
        if (0..dims[axis]).contains(&n[axis]) {
            let n = n.map(|x| x as u32);
            let state = map.state(n);
            if state != CellState::Surface {
                return Some((n, state));
            }
        }
    }
    for r in 1..=MAX_SEARCH_RING as i64 {
        let mut best: Option<([u32; 3], CellState, i64)> = None;
        for dx in -r..=r {
            for dy in -r..=r {
                for dz in -r..=r {
                    if dx.abs().max(dy.abs()).max(dz.abs()) != r {
                        continue;
                    }
                    let n = [c[0] + dx, c[1] + dy, c[2] + dz];
                    if (0..3).any(|k| n[k] < 0 || n[k] >= dims[k]) {
                        continue;
                    }
                    let n = n.map(|x| x as u32);
                    let state = map.state(n);
                    let distance2 = dx * dx + dy * dy + dz * dz;
                    if state != CellState::Surface && best.is_none_or(|(_, _, d)| distance2 < d) {
                        best = Some((n, state, distance2));
                    }
                }
            }
        }
        if let Some((n, state, _)) = best {
            return Some((n, state));
        }
    }
    None
}

/// Generalised winding number of `p` with respect to the surface (1 inside a closed
/// outward-oriented solid, 0 outside; fractional near holes): the oracle for
/// [`classify_point`].
///
/// # Performance
/// `O(n)`: for tests and verification, never for a tick.
pub fn winding_number(surface: &Surface, p: DVec3) -> f64 {
    let total: f64 = (0..surface.triangle_count() as u32)
        .map(|t| crate::mesh::solid_angle(surface.corners(TriId(t)), p))
        .sum();
    total / (4.0 * std::f64::consts::PI)
}
