//! The traversal of a segment through the map's cells, in order, for a query that tests the
//! triangles of each surface cell it passes (the shape of a ray cast through a tree: the
//! map walks, the query's visitor tests a cell's triangles and says where to stop).

use glam::DVec3;

use super::walk::{CellStep, CellWalk};
use super::{BLOCK_SIDE, BRICK_SIDE, InBrick, Look, REGION_SIDE, RegionLook, VoxelMap};

/// The part of a segment in one surface cell, handed to the visitor of
/// [`VoxelMap::cast_segment`].
#[derive(Debug, Clone, Copy)]
pub(crate) struct CellPart<'a> {
    /// The triangles listed in the cell.
    pub triangles: &'a [u32],
    /// Whether to take `triangles` from its start: the list is ordered along the
    /// direction of the cell's slab, and a segment moving against it takes it from the end,
    /// so that it meets the triangle it crosses first (the near face of a plate) early.
    pub forward: bool,
    /// Parameter where the part starts: the segment enters the cell (less the margin of
    /// the cell boundaries' rounding) or, with a slab, the layer the cell's triangles lie in.
    pub from: f64,
    /// Parameter where the part ends: where it leaves the cell (plus the margin) or the
    /// slab, or the visitor's `until`, whichever comes first. `from ≤ to`.
    pub to: f64,
}

/// What the visitor of [`VoxelMap::cast_segment`] found in a cell: an answer at parameter
/// `t`, so the walk stops at the first cell the segment enters after `t`; and the
/// parameter `until ≥ t` beyond which the later cells' parts are cut.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Found {
    /// Parameter of the answer along the segment.
    pub t: f64,
    /// Parameter past which the visitor looks no further.
    pub until: f64,
}

impl VoxelMap {
    /// Walks the cells of the segment `p0 → p1` (metres, object frame) in order (3D-DDA)
    /// and calls `visit` with the part of the segment in each surface cell that lists
    /// triangles, until the walk leaves the grid or enters a cell beyond the last
    /// [`Found::t`] (with the margin of the cell boundaries' rounding).
    ///
    /// With `stride`, free space costs little: the walk crosses a cube of the map known to
    /// hold no surface cell in one stride — far from the surface a cube of regions of 32³
    /// cells, nearer a cube of bricks of 8³ cells (both derived from where the surface
    /// cells are, the bricks' through [`VoxelMap::reach`]), and in a brick that holds
    /// surface cells a free block of 4³ cells of its surface mask — so crossing empty
    /// space takes a few strides however fine the grid, reading mostly memory that stays
    /// in the cache. In a region and in a brick that hold surface cells, the cells before
    /// the segment reaches the layer in which the block's triangles lie (its slab, four
    /// bytes) and after it leaves it are skipped in one stride each; in a surface cell, a
    /// part that passes beside the cell's slab is not visited, and one that passes through
    /// it is cut to the slab. Without `stride` (a short segment, crossing too few cells
    /// for these look-ups to pay), the walk goes cell by cell and hands over whole parts.
    /// It never reads the clearances of free cells, which are cold when the segment comes
    /// from far away.
    ///
    /// # Real-time
    /// No allocation, no lock, no panic; visits at most the grid's
    /// `dims[0] + dims[1] + dims[2]` cells.
    #[inline(always)]
    pub(crate) fn cast_segment(
        &self,
        p0: DVec3,
        p1: DVec3,
        stride: bool,
        mut visit: impl FnMut(CellPart<'_>) -> Option<Found>,
    ) {
        // A hit found in a cell may lie a little past the cell's exit (the triangle reaches
        // into later cells); the walk stops once the answer is before the current cell's
        // entry, with a margin for the rounding of the cell boundaries' parameters.
        let margin = self.boundary_margin(p0, p1);
        let h = self.grid().cell_size();
        let mut walk = self.grid().walk(p0, p1);
        let (mut answer, mut until) = (f64::INFINITY, 1.0);
        // The parts of the segment in the slabs of the region and of the brick it is in.
        let (mut regions, mut bricks) = (Window::new(), Window::new());
        while let Some(step) = walk.next() {
            if answer < step.t_enter - margin {
                break;
            }
            let mut slab = None;
            let triangles = if stride {
                match self.look_region(step.cell) {
                    RegionLook::Outside => continue,
                    RegionLook::Free { around } => {
                        let (lo, hi) = block_box(step.cell, REGION_SIDE, around);
                        walk.skip_box(lo, hi);
                        continue;
                    }
                    RegionLook::Surface(region) => {
                        let window = || self.region_window(region, step.cell, p0, p1);
                        if !regions.admits(&mut walk, &step, region, REGION_SIDE, margin, window) {
                            continue;
                        }
                    }
                }
                match self.look(step.cell) {
                    Look::Outside => continue,
                    Look::FreeBricks { around } => {
                        let (lo, hi) = block_box(step.cell, BRICK_SIDE, around);
                        walk.skip_box(lo, hi);
                        continue;
                    }
                    Look::Detailed { brick, cell } => {
                        let window = || self.brick_window(brick, step.cell, p0, p1);
                        if !bricks.admits(&mut walk, &step, brick, BRICK_SIDE, margin, window) {
                            continue;
                        }
                        match cell {
                            InBrick::Triangles(triangles, s) => {
                                slab = Some(s);
                                triangles
                            }
                            InBrick::FreeBlock => {
                                let (lo, hi) = block_box(step.cell, BLOCK_SIDE, 1);
                                walk.skip_box(lo, hi);
                                continue;
                            }
                            InBrick::Free => continue,
                        }
                    }
                }
            } else {
                self.triangles_in(step.cell)
            };
            if triangles.is_empty() {
                continue;
            }
            // The part of the segment in this cell (with the margin of its boundaries'
            // rounding), up to where the visitor still looks. A triangle crossed at a
            // point in this cell is crossed on that part; one crossed elsewhere is listed
            // by the cell it is crossed in too.
            let (mut from, mut to) = (
                (step.t_enter - margin).max(0.0),
                (step.t_exit + margin).min(until),
            );
            // The slab of the cell: where in it its triangles lie. A part of the segment
            // wholly on one side meets none of them in this cell; one that passes through
            // it can meet them only where it is in the slab (the segment's parameters in
            // the slab, found as for a brick's or a region's).
            let mut forward = true;
            if let Some(slab) = slab {
                let (lo, hi) = self.grid().cell_bounds(step.cell);
                let Some((a, b, along)) =
                    super::slabs::interval_toward(slab, 0.5 * (lo + hi), h, p0, p1)
                else {
                    continue;
                };
                (from, to) = (from.max(a), to.min(b));
                if from > to {
                    continue;
                }
                forward = along;
            }
            let part = CellPart {
                triangles,
                forward,
                from,
                to,
            };
            if let Some(found) = visit(part) {
                (answer, until) = (found.t, found.until);
            }
        }
    }

    /// Parameter margin covering the rounding of cell-boundary parameters along the
    /// segment `p0 → p1`: a millionth of a cell, in units of `t`.
    #[inline]
    pub(crate) fn boundary_margin(&self, p0: DVec3, p1: DVec3) -> f64 {
        let length = p0.distance(p1);
        if length > 0.0 {
            1e-6 * self.grid().cell_size() / length
        } else {
            0.0
        }
    }
}

/// The box of cells of the cube of blocks around `cell`, a cell of a block of `side`
/// cells along each side (a brick, a region of bricks or a free block of a brick,
/// aligned on multiples of `side`), within Chebyshev distance `around − 1` (in blocks)
/// of its block: the cube that [`VoxelMap::look`]'s `around` says holds no surface cell.
#[inline]
fn block_box(cell: [u32; 3], side: u32, around: u8) -> ([i64; 3], [i64; 3]) {
    let side = i64::from(side);
    let around = i64::from(around.max(1) - 1) * side;
    let lo = cell.map(|c| i64::from(c) / side * side - around);
    (lo, lo.map(|c| c + 2 * around + side - 1))
}

/// The part of a long segment that lies in the slab of the block its walk is in (a
/// region of bricks or a detailed brick, see `slabs.rs`): the walk skips the block's
/// cells before and after it.
struct Window {
    /// The block of the window (its index; `u32::MAX` before the first).
    block: u32,
    /// The parameter where the segment enters the block's slab, less the margin of the
    /// cells' boundaries (`+∞` when it never does).
    from: f64,
    /// Where it leaves the slab, plus the margin (`−∞` when it never enters).
    to: f64,
}

impl Window {
    fn new() -> Window {
        Window {
            block: u32::MAX,
            from: f64::NEG_INFINITY,
            to: f64::INFINITY,
        }
    }

    /// Whether the walk must look further at the cell of `step`, a cell of block `block`
    /// of `side` cells whose slab `window` gives the parameters of: not when the part of
    /// the segment in the cell lies before the slab or after it, and then the walk is
    /// moved on, to where the segment enters the slab or out of the block. A straight
    /// segment never comes back to a block it left, so the window of a block is found
    /// once, on entering it.
    #[inline]
    fn admits(
        &mut self,
        walk: &mut CellWalk,
        step: &CellStep,
        block: u32,
        side: u32,
        margin: f64,
        window: impl FnOnce() -> Option<(f64, f64)>,
    ) -> bool {
        if block != self.block {
            self.block = block;
            (self.from, self.to) = match window() {
                Some((from, to)) => (from - margin, to + margin),
                None => (f64::INFINITY, f64::NEG_INFINITY),
            };
        }
        if step.t_enter > self.to {
            let (lo, hi) = block_box(step.cell, side, 1);
            walk.skip_box(lo, hi);
            false
        } else if step.t_exit < self.from {
            walk.skip_box_until(block_box(step.cell, side, 1), self.from);
            false
        } else {
            true
        }
    }
}
