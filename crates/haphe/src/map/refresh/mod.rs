//! The map of a deformed surface: the same triangles at new positions.
//!
//! On the same grid the map is made again locally, stage by stage as a build makes it,
//! each stage redoing only what the moved triangles can change and copying the rest
//! from the map before:
//!
//! - the (cell, triangle) pairs ([`keys`]): the old lists less the moved triangles, and
//!   the moved triangles binned at their new positions;
//! - inside and outside ([`fill`]): again only in the bricks a moved triangle swept;
//! - the clearances ([`clearance`]): again only within reach of the cells whose surface
//!   state changed;
//! - the slabs ([`slabs`]): again only in the cells, bricks and regions a moved triangle
//!   overlaps, before or after.
//!
//! What is linear in the map's size is a pass over its arrays (the lists, the bricks'
//! entries, the bricks' distances); the geometry (binning, winding numbers, dilations,
//! slabs) follows the moved triangles. The result equals the build's on that grid, byte
//! for byte (`tests.rs` compares them).

mod clearance;
mod fill;
mod keys;
mod slabs;
#[cfg(test)]
mod tests;

use glam::DVec3;

use super::build::{build_on_grid, shrink};
use super::grid::PADDING_SLACK_REL;
use super::voxel_map::{BRICK_BITS, MAX_BRICKS, UNIFORM, brick_dims, brick_of};
use super::{Grid, MapError, VoxelMap};
use crate::mesh::Surface;
use crate::par::on_pool;

/// How much a grid grows when a deformation leaves it: a quarter of the surface's extent
/// on every side, so that a shape that keeps growing rebuilds its map rarely.
const GROWTH_OF_EXTENT: f64 = 0.25;

/// The share of the triangles beyond which a refresh on the same grid is a build: the
/// local refresh of a blob of 200 000 triangles with every vertex moved takes about 1.6
/// times as long as its build (the same binning and slabs, and the passes to splice).
const REBUILD_SHARE: f64 = 0.5;

impl VoxelMap {
    /// The map of `surface`, which is `before` (the surface this map was made for) with
    /// some vertices moved; `moved` lists the triangles that moved, in increasing order.
    ///
    /// On this map's grid while the surface stays inside its interior cells, made again
    /// only where the moved triangles reach (a build when more than half the triangles
    /// moved); else on a grid of the same cell size grown to hold the surface with room
    /// to spare (a build). Either way the map is what [`VoxelMap::build`] makes of `surface` on that
    /// grid, byte for byte; it has no provenance (it was not built from the file).
    ///
    /// # Errors
    /// [`MapError::TooManyCells`] when the grown grid would be too large;
    /// [`MapError::TooManyTriangleRefs`] as for a build.
    ///
    /// # Performance
    /// On the same grid: the geometry (binning, winding numbers, dilations, slabs)
    /// follows the moved triangles and the cells they sweep, plus a few linear passes
    /// over the map's arrays (its lists and its bricks' entries and distances), at
    /// memory speed. Parallel as a build is. Not for a servo tick.
    ///
    /// One case keeps the build's answer only where the build checks every region: a
    /// build that leaves enclosed regions unchecked (beyond
    /// [`MAX_ENCLOSED_WINDING_WORK`](super::fill::MAX_ENCLOSED_WINDING_WORK), thousands
    /// of separate parts) takes them as inside, where a refresh classifies a region it
    /// decides again by its winding number.
    pub(crate) fn refreshed(
        &self,
        before: &Surface,
        surface: &Surface,
        moved: &[u32],
    ) -> Result<VoxelMap, MapError> {
        let grid = self.grid_holding(surface)?;
        let count = self.triangle_count;
        let local = grid == self.grid
            && surface.triangle_count() == count as usize
            && before.triangle_count() == count as usize
            && surface.is_solid() == self.solid
            && moved.windows(2).all(|w| w[0] < w[1])
            && moved.last().is_none_or(|&t| t < count);
        // With most triangles moved, a build does the same work with fewer passes.
        let most = moved.len() as f64 > REBUILD_SHARE * f64::from(count);
        if !local || most {
            return on_pool(|| build_on_grid(surface, grid, self.cell_size_rule, &|_| {}));
        }
        on_pool(|| self.refreshed_here(before, surface, moved))
    }

    /// [`VoxelMap::refreshed`], for the benches (feature `testing`).
    ///
    /// # Errors
    /// Those of [`VoxelMap::refreshed`].
    #[cfg(feature = "testing")]
    #[doc(hidden)]
    pub fn refreshed_after(
        &self,
        before: &Surface,
        surface: &Surface,
        moved: &[u32],
    ) -> Result<VoxelMap, MapError> {
        self.refreshed(before, surface, moved)
    }

    /// [`VoxelMap::refreshed`] made locally whatever share of the triangles moved, on
    /// this map's grid (which must hold `surface`), for the benches (feature `testing`).
    ///
    /// # Errors
    /// Those of [`VoxelMap::refreshed`].
    #[cfg(feature = "testing")]
    #[doc(hidden)]
    pub fn refreshed_locally(
        &self,
        before: &Surface,
        surface: &Surface,
        moved: &[u32],
    ) -> Result<VoxelMap, MapError> {
        on_pool(|| self.refreshed_here(before, surface, moved))
    }

    /// The map a build makes of `surface` on this map's grid, for the benches (feature
    /// `testing`): what [`VoxelMap::refreshed`] equals.
    ///
    /// # Errors
    /// Those of a build.
    #[cfg(feature = "testing")]
    #[doc(hidden)]
    pub fn built_on_this_grid(&self, surface: &Surface) -> Result<VoxelMap, MapError> {
        on_pool(|| build_on_grid(surface, self.grid, self.cell_size_rule, &|_| {}))
    }

    /// [`VoxelMap::refreshed`] on this map's grid, made locally.
    fn refreshed_here(
        &self,
        before: &Surface,
        surface: &Surface,
        moved: &[u32],
    ) -> Result<VoxelMap, MapError> {
        let fresh = keys::fresh_pairs(self, surface, moved);
        let swept = self.swept_bricks(before, surface, moved, &fresh);
        let keys::Spliced { mut map, touched } = keys::spliced(self, moved, &swept, &fresh)?;
        drop(fresh);
        map.triangle_count = self.triangle_count;
        map.cell_size_rule = self.cell_size_rule;
        if self.solid {
            fill::refill(&mut map, self, surface, &swept);
        }
        let changed: Vec<usize> = swept
            .iter()
            .copied()
            .filter(|&b| self.surface_bits_of(b) != map.surface_bits_of(b))
            .collect();
        clearance::reclear(&mut map, self, &changed);
        map.derive_free_space();
        slabs::reslab(&mut map, self, surface, &touched);
        shrink(&mut map);
        Ok(map)
    }

    /// The bricks (top-level indices, increasing) that a moved triangle may have swept
    /// on its way from its corners in `before` to those in `surface`: those meeting the
    /// box of both, one cell wider, and those holding a cell of `fresh` (pairs, cell key
    /// in the upper half).
    fn swept_bricks(
        &self,
        before: &Surface,
        surface: &Surface,
        moved: &[u32],
        fresh: &[u64],
    ) -> Vec<usize> {
        let (dims, bdims) = (self.grid.dims(), self.brick_dims);
        let mut bricks: Vec<usize> = fresh
            .iter()
            .map(|&key| (key >> (32 + 3 * BRICK_BITS)) as usize)
            .collect();
        let last = dims.map(|d| i64::from(d) - 1);
        for &t in moved {
            let corners = before
                .triangles()
                .get(t as usize)
                .into_iter()
                .flat_map(|tri| {
                    tri.iter().flat_map(|&v| {
                        [before.vertices(), surface.vertices()]
                            .map(|vertices| vertices.get(v as usize).copied())
                    })
                })
                .flatten()
                .map(|p| self.grid.to_grid(p));
            let (lo, hi) = corners.fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(p), hi.max(p))
            });
            if !(lo.is_finite() && hi.is_finite()) {
                continue;
            }
            let cell = |x: f64, a: usize| (x.floor() as i64).clamp(0, last[a]) as u32;
            let from: [u32; 3] = std::array::from_fn(|a| cell(lo[a] - 1.0, a) >> BRICK_BITS);
            let to: [u32; 3] = std::array::from_fn(|a| cell(hi[a] + 1.0, a) >> BRICK_BITS);
            for z in from[2]..=to[2] {
                for y in from[1]..=to[1] {
                    for x in from[0]..=to[0] {
                        bricks.push(brick_of([x, y, z].map(|v| v << BRICK_BITS), bdims));
                    }
                }
            }
        }
        bricks.sort_unstable();
        bricks.dedup();
        bricks
    }

    /// The surface cells of the brick at top-level index `b` (none for a uniform brick).
    fn surface_bits_of(&self, b: usize) -> super::voxel_map::BrickBits {
        self.bricks
            .get(b)
            .filter(|&&e| e & UNIFORM == 0)
            .and_then(|&e| self.surface_bits.get(e as usize))
            .copied()
            .unwrap_or_default()
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
