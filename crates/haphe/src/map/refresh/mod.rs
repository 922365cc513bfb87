//! The map of a deformed surface: the same triangles at new positions.

use glam::DVec3;

use super::build::build_on_grid;
use super::grid::PADDING_SLACK_REL;
use super::voxel_map::{MAX_BRICKS, brick_dims};
use super::{Grid, MapError, VoxelMap};
use crate::mesh::Surface;

/// How much a grid grows when a deformation leaves it: a quarter of the surface's extent
/// on every side, so that a shape that keeps growing rebuilds its map rarely.
const GROWTH_OF_EXTENT: f64 = 0.25;

impl VoxelMap {
    /// The map of `surface`, which is `before` (the surface this map was made for) with
    /// some vertices moved; `moved` lists the triangles that moved, in increasing order.
    ///
    /// On this map's grid while the surface stays inside its interior cells; else on a
    /// grid of the same cell size grown to hold the surface with room to spare (a
    /// rebuild). Either way the map is what [`VoxelMap::build`] makes of `surface` on that
    /// grid, byte for byte; it has no provenance (it was not built from the file).
    ///
    /// # Errors
    /// [`MapError::TooManyCells`] when the grown grid would be too large;
    /// [`MapError::TooManyTriangleRefs`] as for a build.
    pub(crate) fn refreshed(
        &self,
        before: &Surface,
        surface: &Surface,
        moved: &[u32],
    ) -> Result<VoxelMap, MapError> {
        let _ = (before, moved);
        let grid = self.grid_holding(surface)?;
        build_on_grid(surface, grid, self.cell_size_rule, &|_| {})
    }

    /// This map's grid when `surface` lies inside its interior cells (with the padding
    /// slack a build leaves), else a grid of the same cell size grown to hold it.
    fn grid_holding(&self, surface: &Surface) -> Result<Grid, MapError> {
        let (min, max) = surface.bounds();
        let h = self.grid.cell_size();
        let slack = DVec3::splat(h * (1.0 + PADDING_SLACK_REL));
        let (lo, hi) = (self.grid.origin() + slack, self.grid.max_corner() - slack);
        if min.cmpge(lo).all() && max.cmple(hi).all() {
            return Ok(self.grid);
        }
        let spare = GROWTH_OF_EXTENT * (max - min);
        let (min, max) = (min.min(lo) - spare, max.max(hi) + spare);
        let too_many = MapError::TooManyCells {
            cell_size_m: h,
            extent_m: (max - min).to_array(),
        };
        let grid = Grid::padded_around(min, max, h).ok_or(too_many.clone())?;
        let bricks: u64 = brick_dims(grid.dims())
            .iter()
            .map(|&d| u64::from(d))
            .product();
        if bricks > MAX_BRICKS {
            return Err(too_many);
        }
        Ok(grid)
    }
}
