//! The 3D-DDA: the cells a segment passes through, in order.

use glam::DVec3;

use super::grid::{Grid, floor_to_int};

/// One cell a segment passes through, with the part of the segment inside it: the points
/// `p0 + t·(p1 − p0)` for `t` in `[t_enter, t_exit]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CellStep {
    /// The cell.
    pub cell: [u32; 3],
    /// Segment parameter where the segment enters the cell (0 at `p0`).
    pub t_enter: f64,
    /// Segment parameter where it leaves the cell (1 at `p1`).
    pub t_exit: f64,
}

/// The cells a segment passes through, from its start to its end: a 3D-DDA (Amanatides &
/// Woo, *A Fast Voxel Traversal Algorithm*, 1987) in cell units, made by [`Grid::walk`].
///
/// Consecutive cells share a face; the parameter intervals follow each other without gaps,
/// from where the segment enters the grid box to where it leaves it (or ends). Where the
/// segment passes exactly through a cell edge or corner, the walk steps one axis at a time
/// and visits one of the cells around it with an empty interval. Rounding can attribute a
/// point within about `1e-16` relative of a cell face to the neighbouring cell; the map
/// lists triangles with `OVERLAP_TOLERANCE_REL` to spare,
/// so a triangle that the segment meets is listed in a cell the walk visits.
///
/// A walk can also skip a block of cells known to list no triangle
/// ([`CellWalk::skip_cube`]), the way [`first_crossing`](crate::query::first_crossing)
/// crosses free space by the map's [`clearance`](super::VoxelMap::clearance).
///
/// # Real-time
/// No allocation, no panic; at most `dims[0] + dims[1] + dims[2]` steps, with or without
/// skips.
#[derive(Debug, Clone)]
pub struct CellWalk {
    /// `p0` in cell units.
    a: [f64; 3],
    /// `p1 − p0` in cell units.
    d: [f64; 3],
    /// `1 / d` per axis (infinite along an axis the segment does not move on): walks
    /// and skips find parameters by multiplying with it.
    inv_d: [f64; 3],
    /// How far a skip pulls a box's far face back into the box, per axis, cells, signed
    /// as the walk's steps (see [`SKIP_MARGIN`]).
    pull: [f64; 3],
    /// The cell returned last (the walk's first cell before any).
    last: [i64; 3],
    cell: [i64; 3],
    step: [i64; 3],
    t_max: [f64; 3],
    t_delta: [f64; 3],
    t: f64,
    t_end: f64,
    dims: [i64; 3],
    remaining: u32,
}

/// The most steps a walk of a grid of `dims` cells takes: `dims[0] + dims[1] + dims[2] + 1`.
///
/// Never reached by a walk, with or without [skips](CellWalk::skip_cube): each step but
/// the last moves the walk one cell along one axis, a skip moves it at least one cell
/// along one axis, and neither ever moves it back, so a walk takes at most
/// `dims[0] + dims[1] + dims[2] − 2` steps. The cap bounds the cost of a walk whatever
/// rounding does.
fn step_cap(dims: [u32; 3]) -> u32 {
    dims.iter().sum::<u32>() + 1
}

impl Grid {
    /// The cells the segment from `p0` to `p1` (metres, object frame) passes through, in
    /// order ([`CellWalk`]). Empty when the segment misses the grid box or a point is not
    /// finite.
    ///
    /// # Examples
    /// ```
    /// use haphe::DVec3;
    /// use haphe::map::Grid;
    /// let grid = Grid::new(DVec3::ZERO, 1.0, [4, 4, 4]).unwrap();
    /// let cells: Vec<[u32; 3]> = grid
    ///     .walk(DVec3::new(0.5, 0.5, 0.5), DVec3::new(2.5, 1.5, 0.5))
    ///     .map(|step| step.cell)
    ///     .collect();
    /// assert_eq!(cells, [[0, 0, 0], [1, 0, 0], [1, 1, 0], [2, 1, 0]]);
    /// ```
    #[doc(hidden)]
    pub fn walk(&self, p0: DVec3, p1: DVec3) -> CellWalk {
        let dims = self.dims().map(i64::from);
        let empty = CellWalk {
            a: [0.0; 3],
            d: [0.0; 3],
            inv_d: [f64::INFINITY; 3],
            pull: [0.0; 3],
            last: [0; 3],
            cell: [0; 3],
            step: [0; 3],
            t_max: [f64::INFINITY; 3],
            t_delta: [f64::INFINITY; 3],
            t: 1.0,
            t_end: 0.0,
            dims,
            remaining: 0,
        };
        let (a, b) = (self.to_grid(p0), self.to_grid(p1));
        let d = b - a;
        let inv_d = d.recip();
        let Some((t0, t1)) = self.clip_along(a, d, inv_d) else {
            return empty;
        };
        let start = a + t0 * d;
        let margin = SKIP_MARGIN + SKIP_MARGIN_REL * (2.0 * a.abs() + d.abs());
        let mut walk = CellWalk {
            a: a.to_array(),
            d: d.to_array(),
            inv_d: inv_d.to_array(),
            t: t0,
            t_end: t1,
            remaining: step_cap(self.dims()),
            ..empty
        };
        // Selects rather than branches: a segment's directions are not predictable
        // from one query to the next.
        for axis in 0..3 {
            let cell = floor_to_int(start[axis]).clamp(0, dims[axis] - 1);
            walk.cell[axis] = cell;
            walk.last[axis] = cell;
            let (up, down) = (d[axis] > 0.0, d[axis] < 0.0);
            let step = i64::from(up) - i64::from(down);
            walk.step[axis] = step;
            walk.pull[axis] = step as f64 * margin[axis];
            let exit = (cell + i64::from(up)) as f64;
            let t_max = (exit - a[axis]) * inv_d[axis];
            walk.t_max[axis] = if step == 0 { f64::INFINITY } else { t_max };
            // |1 / d|: infinite along an axis the segment does not move on.
            walk.t_delta[axis] = inv_d[axis].abs();
        }
        walk
    }
}

impl Iterator for CellWalk {
    type Item = CellStep;

    #[inline]
    fn next(&mut self) -> Option<CellStep> {
        if self.remaining == 0 || self.t > self.t_end {
            return None;
        }
        self.remaining -= 1;
        let axis = if self.t_max[0] <= self.t_max[1] && self.t_max[0] <= self.t_max[2] {
            0
        } else if self.t_max[1] <= self.t_max[2] {
            1
        } else {
            2
        };
        let cell = self.cell.map(|c| c as u32);
        self.last = self.cell;
        let t_enter = self.t;
        let t_exit = self.t_max[axis].min(self.t_end).max(t_enter);
        // Step to the next cell, or finish when the segment ends first or leaves the grid.
        let next = self.cell[axis] + self.step[axis];
        if self.t_max[axis] > self.t_end || !(0..self.dims[axis]).contains(&next) {
            self.remaining = 0;
        } else {
            self.cell[axis] = next;
            self.t = t_exit;
            self.t_max[axis] += self.t_delta[axis];
        }
        Some(CellStep {
            cell,
            t_enter,
            t_exit,
        })
    }
}

/// How far, in cells, [`CellWalk::skip_cube`] stops short of the cube's far face, plus
/// [`SKIP_MARGIN_REL`] of the coordinates in cell units: far above the rounding of the
/// parameter where the segment reaches the face (a few `1e-16` of those coordinates), so
/// that rounding can only shorten a skip, never carry it past a cell of the cube. Set per
/// axis when a walk starts, from `2 |a| + |d|` (start `a`, extent `d`, cell units), which
/// bounds `|a| + |face|` for any face the segment reaches before its end.
const SKIP_MARGIN: f64 = 1e-6;

/// See [`SKIP_MARGIN`]: about 4 500 times the unit roundoff.
const SKIP_MARGIN_REL: f64 = 1e-12;

impl CellWalk {
    /// Skips the cells within Chebyshev distance `radius` (in cells) of the cell the walk
    /// returned last, which the caller knows list no triangle (for instance because that
    /// cell's [`clearance`](super::VoxelMap::clearance) is `radius + 1`): the walk goes on
    /// from where the segment leaves that cube of `2·radius + 1` cells a side, re-seeded
    /// there as [`Grid::walk`] seeds a walk, and its next step is the first cell it
    /// reaches beyond the cube (that step's `t_enter` is a hair, about a millionth of a
    /// cell, before the cube's face). A segment that ends in the cube or leaves the grid
    /// from it ends the walk.
    ///
    /// Every cell beyond the cube in which the walk would have spent a non-empty interval
    /// it still visits, in order, for the same interval (up to the rounding of its ends).
    /// Where the segment passes exactly through a cell edge or corner (the cube's own
    /// included), the cell the walk visits there with an empty interval may be another of
    /// the cells around it than without the skip: all of them touch the segment.
    ///
    /// The parameter where the segment leaves the cube is computed for a face pulled a
    /// millionth of a cell (plus `1e-12` of the coordinates in cell units) into the cube,
    /// so that rounding can only make the skip shorter. Does nothing when `radius` is 0,
    /// when the walk is over, or when rounding leaves no progress to make.
    ///
    /// # Real-time
    /// Constant time, no allocation, no panic. A skip advances the walk by at least one
    /// cell along one axis and never moves it back along any, so the walk still ends
    /// within `dims[0] + dims[1] + dims[2]` steps.
    pub fn skip_cube(&mut self, radius: u32) {
        if self.remaining == 0 || radius == 0 {
            return;
        }
        let r = i64::from(radius);
        self.skip_box(self.last.map(|c| c - r), self.last.map(|c| c + r));
    }

    /// Skips the box of cells from `lo` to `hi` (inclusive, cell indices, `lo ≤ hi` along
    /// every axis), which holds the cell the walk returned last and which the caller knows
    /// lists no triangle (a brick of the map without surface cells, say): as
    /// [`skip_cube`](Self::skip_cube) does for a cube around that cell, the walk goes on
    /// from where the segment leaves the box, and its next step is the first cell beyond.
    /// Does nothing when the box does not hold the last cell, when the walk is over, or
    /// when rounding leaves no progress to make.
    ///
    /// # Real-time
    /// Constant time, no allocation, no panic; the walk still ends within
    /// `dims[0] + dims[1] + dims[2]` steps.
    pub fn skip_box(&mut self, lo: [i64; 3], hi: [i64; 3]) {
        self.skip_box_until((lo, hi), f64::INFINITY);
    }

    /// [`skip_box`](Self::skip_box), but stopping at parameter `stop` when the segment is
    /// still in the box there: the walk then goes on from the cell of the box holding the
    /// point at `stop`, whose step starts at `stop` (the caller knows the segment crosses
    /// nothing in the box before `stop`). Does nothing when `stop` is not past the walk's
    /// current parameter (or is NaN).
    ///
    /// # Real-time
    /// As [`skip_box`](Self::skip_box).
    pub fn skip_box_until(&mut self, (lo, hi): ([i64; 3], [i64; 3]), stop: f64) {
        if self.remaining == 0 {
            return;
        }
        // Where the segment reaches the box's far faces (lower faces where the walk goes
        // down an axis), pulled into the box by the margin: it leaves by the first.
        let (mut t_leave, mut leave_axis) = (f64::INFINITY, 0);
        let mut outside = false;
        for k in 0..3 {
            outside |= (self.last[k] < lo[k]) | (self.last[k] > hi[k]);
            let face = if self.step[k] > 0 { hi[k] + 1 } else { lo[k] } as f64;
            let reach = (face - self.pull[k] - self.a[k]) * self.inv_d[k];
            // An axis the segment does not move on is never left (its `reach` may be
            // NaN: `inv_d` is infinite there).
            let reach = if self.step[k] == 0 {
                f64::INFINITY
            } else {
                reach
            };
            outside |= reach.is_nan();
            let nearer = reach < t_leave;
            t_leave = if nearer { reach } else { t_leave };
            leave_axis = if nearer { k } else { leave_axis };
        }
        if outside {
            return;
        }
        if stop < t_leave || stop.is_nan() {
            if stop > self.t {
                self.reseed(lo, hi, stop, NO_AXIS, 0);
            }
            return;
        }
        if t_leave <= self.t {
            return;
        }
        let beyond = if self.step[leave_axis] > 0 {
            hi[leave_axis] + 1
        } else {
            lo[leave_axis] - 1
        };
        if t_leave >= self.t_end || !(0..self.dims[leave_axis]).contains(&beyond) {
            self.remaining = 0;
            return;
        }
        self.reseed(lo, hi, t_leave, leave_axis, beyond);
    }

    /// Moves the walk on to parameter `t`, in the cell of the point there (never behind
    /// the walk nor beyond the box `lo..=hi` or the grid, where rounding could put it);
    /// along axis `leave` (an axis the segment leaves the box by, or [`NO_AXIS`]), in
    /// cell `beyond`. Seeded as `Grid::walk` seeds a walk (an axis the segment does not
    /// move on keeps its cell and its infinite exit).
    #[inline]
    fn reseed(&mut self, lo: [i64; 3], hi: [i64; 3], t: f64, leave: usize, beyond: i64) {
        for k in 0..3 {
            let s = self.step[k];
            let at = floor_to_int(self.a[k] + t * self.d[k]);
            // Up: not behind the walk, not past the box or the grid; down: the mirror.
            let up = at.max(self.cell[k]).min(hi[k]).min(self.dims[k] - 1);
            let down = at.min(self.cell[k]).max(lo[k]).max(0);
            let cell = if s > 0 { up } else { down };
            let cell = if k == leave { beyond } else { cell };
            // An axis the segment does not move on keeps its cell and its infinite exit.
            let exit = (cell + i64::from(s > 0)) as f64;
            let t_max = (exit - self.a[k]) * self.inv_d[k];
            self.cell[k] = if s == 0 { self.cell[k] } else { cell };
            self.t_max[k] = if s == 0 { self.t_max[k] } else { t_max };
        }
        self.t = t;
    }
}

/// The `leave` argument of [`CellWalk::reseed`] when the segment leaves the box by no axis.
const NO_AXIS: usize = 3;

#[cfg(test)]
mod tests;
