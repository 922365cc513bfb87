//! Iteration over the cells of a map: the surface cells in storage order (offline work:
//! validation, statistics), and the cells of a box with their triangles (the visitor of
//! the queries around a point or a triangle; [`VoxelMap::cast_segment`] is the one along a
//! segment).

use glam::DVec3;

use super::grid::{Grid, floor_to_int};
use super::{CellState, VoxelMap};

/// A box of cells, inclusive integer cell coordinates, not clipped to the grid (so that
/// boxes may be intersected before they are clipped).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct CellBox {
    /// The lowest cell along each axis.
    pub lo: [i64; 3],
    /// The highest cell along each axis (`hi < lo` on an axis: an empty box).
    pub hi: [i64; 3],
}

impl CellBox {
    /// The cells that the box `lo..hi` (metres, object frame) overlaps: the floors of its
    /// corners' grid coordinates.
    #[inline]
    pub(crate) fn around(grid: &Grid, lo: DVec3, hi: DVec3) -> CellBox {
        let (lo, hi) = (grid.to_grid(lo), grid.to_grid(hi));
        CellBox {
            lo: [0, 1, 2].map(|k| floor_to_int(lo[k])),
            hi: [0, 1, 2].map(|k| floor_to_int(hi[k])),
        }
    }

    /// The box grown by `n` cells on every side.
    #[inline]
    pub(crate) fn grown(self, n: i64) -> CellBox {
        CellBox {
            lo: self.lo.map(|c| c.saturating_sub(n)),
            hi: self.hi.map(|c| c.saturating_add(n)),
        }
    }

    /// The cells in both boxes.
    #[inline]
    pub(crate) fn intersect(self, other: CellBox) -> CellBox {
        CellBox {
            lo: [0, 1, 2].map(|k| self.lo[k].max(other.lo[k])),
            hi: [0, 1, 2].map(|k| self.hi[k].min(other.hi[k])),
        }
    }

    /// The number of cells (0 for an empty box).
    #[inline]
    pub(crate) fn count(&self) -> u64 {
        (0..3)
            .map(|k| u64::try_from(self.hi[k] - self.lo[k] + 1).unwrap_or(0))
            .product()
    }
}

impl VoxelMap {
    /// The triangle list of every surface cell, in storage order (each list ordered along
    /// its cell's slab, as [`VoxelMap::triangles_in`] gives it). For offline work such as
    /// finding self-intersections; a tick looks cells up by coordinates with
    /// [`VoxelMap::triangles_in`].
    pub fn surface_cell_triangles(&self) -> impl ExactSizeIterator<Item = &[u32]> + '_ {
        self.triangle_start.windows(2).map(|w| {
            self.triangle_refs
                .get(w[0] as usize..w[1] as usize)
                .unwrap_or(&[])
        })
    }

    /// The cells of `cells` that lie in the grid; `None` when there are none.
    #[inline]
    pub(crate) fn clip_cells(&self, cells: CellBox) -> Option<CellBox> {
        let dims = self.grid().dims();
        let clipped = CellBox {
            lo: cells.lo.map(|c| c.max(0)),
            hi: [0, 1, 2].map(|k| cells.hi[k].min(i64::from(dims[k]) - 1)),
        };
        (0..3)
            .all(|k| clipped.lo[k] <= clipped.hi[k])
            .then_some(clipped)
    }

    /// Calls `visit` with each cell of `cells` in the grid that lists triangles, and its
    /// triangles (as [`VoxelMap::triangles_in`] gives them), in order of `x`, then `y`,
    /// then `z`.
    ///
    /// # Real-time
    /// No allocation, no panic; one cell lookup per cell of the clipped box (a caller
    /// bounds the box: [`CellBox::count`]).
    #[inline]
    pub(crate) fn visit_cells(&self, cells: CellBox, mut visit: impl FnMut([u32; 3], &[u32])) {
        let Some(cells) = self.clip_cells(cells) else {
            return;
        };
        let (lo, hi) = (cells.lo.map(|c| c as u32), cells.hi.map(|c| c as u32));
        for x in lo[0]..=hi[0] {
            for y in lo[1]..=hi[1] {
                for z in lo[2]..=hi[2] {
                    let triangles = self.triangles_in([x, y, z]);
                    if !triangles.is_empty() {
                        visit([x, y, z], triangles);
                    }
                }
            }
        }
    }

    /// Calls `visit` with each cell of `within` (clipped to the grid) at Chebyshev distance
    /// exactly `ring` from the cell `centre` (which may lie outside the grid) that lists
    /// triangles, and its triangles; returns the number of cells looked up (the work
    /// done). The search of [`nearest_within`](crate::query::nearest_within), ring by ring.
    ///
    /// # Real-time
    /// No allocation, no panic; at most `(2·ring + 1)³ − (2·ring − 1)³` cell lookups.
    pub(crate) fn visit_ring(
        &self,
        centre: [i64; 3],
        ring: i64,
        within: CellBox,
        mut visit: impl FnMut([u32; 3], &[u32]),
    ) -> u64 {
        let ring_box = CellBox {
            lo: centre.map(|c| c.saturating_sub(ring)),
            hi: centre.map(|c| c.saturating_add(ring)),
        };
        let Some(cells) = self.clip_cells(ring_box.intersect(within)) else {
            return 0;
        };
        let mut looked_up = 0;
        let mut look = |c: [i64; 3]| {
            looked_up += 1;
            let c = c.map(|x| x as u32);
            let triangles = self.triangles_in(c);
            if !triangles.is_empty() {
                visit(c, triangles);
            }
        };
        for x in cells.lo[0]..=cells.hi[0] {
            for y in cells.lo[1]..=cells.hi[1] {
                if (x - centre[0]).abs() == ring || (y - centre[1]).abs() == ring {
                    for z in cells.lo[2]..=cells.hi[2] {
                        look([x, y, z]);
                    }
                } else {
                    // Only the two faces of the ring along z (distinct: here `ring > 0`),
                    // where they are in the box.
                    for z in [centre[2] - ring, centre[2] + ring] {
                        if (cells.lo[2]..=cells.hi[2]).contains(&z) {
                            look([x, y, z]);
                        }
                    }
                }
            }
        }
        looked_up
    }

    /// The nearest cell to `cell` (by Chebyshev ring up to `max_ring`, then by distance,
    /// then by index order) whose winding number is known: not a surface cell nor an
    /// [overlap cell](VoxelMap::is_overlap); with its state. The start of an inside/outside
    /// count from a surface cell.
    ///
    /// # Real-time
    /// No allocation, no panic; at most `(2·max_ring + 1)³` cell lookups.
    pub(crate) fn nearest_known_cell(
        &self,
        cell: [u32; 3],
        max_ring: u32,
    ) -> Option<([u32; 3], CellState)> {
        let dims = self.grid().dims().map(i64::from);
        let c = cell.map(i64::from);
        // The six face neighbours first, in the order the ring below visits them: the
        // nearest cells of the first ring, so the first known one is what the whole ring
        // would give.
        for (axis, step) in [(0, -1), (1, -1), (2, -1), (2, 1), (1, 1), (0, 1)] {
            let mut n = c;
            n[axis] += step;
            if (0..dims[axis]).contains(&n[axis]) {
                let n = n.map(|x| x as u32);
                if let Some(state) = self.known_state(n) {
                    return Some((n, state));
                }
            }
        }
        (1..=i64::from(max_ring)).find_map(|r| self.nearest_known_on_ring(c, r))
    }

    /// The nearest cell of known winding number on the Chebyshev ring `r` around `c` (by
    /// distance, then index order).
    fn nearest_known_on_ring(&self, c: [i64; 3], r: i64) -> Option<([u32; 3], CellState)> {
        let dims = self.grid().dims().map(i64::from);
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
                    let distance2 = dx * dx + dy * dy + dz * dz;
                    if best.is_none_or(|(_, _, d)| distance2 < d)
                        && let Some(state) = self.known_state(n)
                    {
                        best = Some((n, state, distance2));
                    }
                }
            }
        }
        best.map(|(n, state, _)| (n, state))
    }

    /// The state of cell `n` when its winding number is known: not a surface cell, nor an
    /// overlap cell.
    #[inline]
    fn known_state(&self, n: [u32; 3]) -> Option<CellState> {
        match self.state(n) {
            CellState::Surface => None,
            CellState::Inside if self.is_overlap(n) => None,
            state => Some(state),
        }
    }

    /// Whether a face neighbour of `cell` (clamped to the grid) is an
    /// [overlap cell](VoxelMap::is_overlap).
    pub(crate) fn borders_overlap(&self, cell: [u32; 3]) -> bool {
        let dims = self.grid().dims();
        [
            (0, false),
            (1, false),
            (2, false),
            (0, true),
            (1, true),
            (2, true),
        ]
        .into_iter()
        .any(|(axis, up)| {
            let mut n = cell;
            n[axis] = if up {
                cell[axis]
                    .saturating_add(1)
                    .min(dims[axis].saturating_sub(1))
            } else {
                cell[axis].saturating_sub(1)
            };
            self.is_overlap(n)
        })
    }
}
