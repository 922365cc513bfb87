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
/// lists triangles with [`OVERLAP_TOLERANCE_REL`](super::OVERLAP_TOLERANCE_REL) to spare,
/// so a triangle that the segment meets is listed in a cell the walk visits.
///
/// # Real-time
/// No allocation, no panic; at most `dims[0] + dims[1] + dims[2]` steps.
#[derive(Debug, Clone)]
pub struct CellWalk {
    cell: [i64; 3],
    step: [i64; 3],
    t_max: [f64; 3],
    t_delta: [f64; 3],
    t: f64,
    t_end: f64,
    dims: [i64; 3],
    remaining: u32,
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
    pub fn walk(&self, p0: DVec3, p1: DVec3) -> CellWalk {
        let dims = self.dims().map(i64::from);
        let empty = CellWalk {
            cell: [0; 3],
            step: [0; 3],
            t_max: [f64::INFINITY; 3],
            t_delta: [f64::INFINITY; 3],
            t: 1.0,
            t_end: 0.0,
            dims,
            remaining: 0,
        };
        let Some((t0, t1)) = self.clip_segment(p0, p1) else {
            return empty;
        };
        let (a, b) = (self.to_grid(p0), self.to_grid(p1));
        let d = b - a;
        let start = a + t0 * d;
        let mut walk = CellWalk {
            t: t0,
            t_end: t1,
            remaining: self.dims().iter().sum::<u32>() + 1,
            ..empty
        };
        for axis in 0..3 {
            let cell = floor_to_int(start[axis]).clamp(0, dims[axis] - 1);
            walk.cell[axis] = cell;
            if d[axis] > 0.0 {
                walk.step[axis] = 1;
                walk.t_max[axis] = (cell as f64 + 1.0 - a[axis]) / d[axis];
                walk.t_delta[axis] = 1.0 / d[axis];
            } else if d[axis] < 0.0 {
                walk.step[axis] = -1;
                walk.t_max[axis] = (cell as f64 - a[axis]) / d[axis];
                walk.t_delta[axis] = -1.0 / d[axis];
            }
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

#[cfg(test)]
mod tests {
    use super::*;

    fn grid() -> Grid {
        Grid::new(DVec3::new(-1.0, -1.0, -1.0), 0.5, [4, 4, 4]).expect("valid")
    }

    #[test]
    fn a_segment_inside_one_cell_visits_it_once() {
        let g = grid();
        let steps: Vec<CellStep> = g
            .walk(DVec3::new(-0.9, -0.9, -0.9), DVec3::new(-0.6, -0.7, -0.8))
            .collect();
        assert_eq!(
            steps,
            [CellStep {
                cell: [0, 0, 0],
                t_enter: 0.0,
                t_exit: 1.0
            }]
        );
    }

    #[test]
    fn a_segment_across_the_grid_enters_and_leaves_at_the_box() {
        let g = grid();
        let steps: Vec<CellStep> = g
            .walk(DVec3::new(-2.0, -0.25, 0.25), DVec3::new(2.0, -0.25, 0.25))
            .collect();
        assert_eq!(steps.len(), 4);
        assert_eq!(steps[0].t_enter, 0.25);
        assert_eq!(steps[3].t_exit, 0.75);
        for (i, s) in steps.iter().enumerate() {
            assert_eq!(s.cell, [i as u32, 1, 2]);
        }
        for w in steps.windows(2) {
            assert_eq!(w[0].t_exit, w[1].t_enter);
        }
    }

    #[test]
    fn a_diagonal_through_corners_steps_one_axis_at_a_time() {
        let g = grid();
        let steps: Vec<CellStep> = g
            .walk(DVec3::new(-1.0, -1.0, -1.0), DVec3::new(1.0, 1.0, 1.0))
            .collect();
        assert_eq!(steps.first().map(|s| s.cell), Some([0, 0, 0]));
        assert_eq!(steps.last().map(|s| s.cell), Some([3, 3, 3]));
        assert_eq!(steps.len(), 10);
        for w in steps.windows(2) {
            let moved: u32 = (0..3).map(|a| w[0].cell[a].abs_diff(w[1].cell[a])).sum();
            assert_eq!(moved, 1, "{w:?}");
        }
    }

    #[test]
    fn missing_or_non_finite_segments_visit_nothing() {
        let g = grid();
        assert_eq!(g.walk(DVec3::splat(2.0), DVec3::splat(3.0)).count(), 0);
        assert_eq!(g.walk(DVec3::NAN, DVec3::ZERO).count(), 0);
        assert_eq!(g.walk(DVec3::ZERO, DVec3::INFINITY).count(), 0);
        // A point segment inside the grid visits its cell.
        assert_eq!(g.walk(DVec3::ZERO, DVec3::ZERO).count(), 1);
    }

    #[test]
    fn backwards_segments_visit_the_reverse_cells() {
        let g = grid();
        let (p, q) = (DVec3::new(-0.8, 0.3, -0.1), DVec3::new(0.9, -0.7, 0.6));
        let forward: Vec<[u32; 3]> = g.walk(p, q).map(|s| s.cell).collect();
        let mut backward: Vec<[u32; 3]> = g.walk(q, p).map(|s| s.cell).collect();
        backward.reverse();
        assert_eq!(forward, backward);
    }
}
