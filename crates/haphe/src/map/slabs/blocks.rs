//! The slab of one block: a surface cell (with its list's order), a brick, a region.

use glam::DVec3;

use super::{FULL_FINE_SLAB, SlabScratch, direction, fine_slab_of, gather, order_along, slab_of};
use crate::map::VoxelMap;
use crate::map::free_space::{REGION_SIDE, region_dims};
use crate::map::voxel_map::{BRICK_SIDE, UNIFORM, brick_coords, cell_in_brick};
use crate::mesh::Surface;

impl VoxelMap {
    /// The slab of surface cell `local` of the detailed brick at top-level index `b`,
    /// whose triangles are `listed` (in increasing order, as a build bins them); leaves
    /// the list ordered along the slab ([`order_along`]) in `scratch.keyed`.
    pub(crate) fn cell_slab(
        &self,
        surface: &Surface,
        b: usize,
        local: usize,
        listed: &[u32],
        scratch: &mut SlabScratch,
    ) -> u32 {
        let bc = brick_coords(b, self.brick_dims);
        let (lo, hi) = self.grid.cell_bounds(cell_in_brick(bc, local));
        gather(surface, listed, &mut scratch.corners);
        let slab = slab_of(&scratch.corners, 0.5 * (lo + hi), self.grid.cell_size());
        order_along(
            direction(slab),
            listed,
            &scratch.corners,
            &mut scratch.keyed,
        );
        slab
    }

    /// The slab of the brick at top-level index `b` over `triangles` (those of its
    /// surface cells, each once, in increasing order).
    pub(crate) fn brick_slab_over(
        &self,
        surface: &Surface,
        b: usize,
        triangles: &[u32],
        scratch: &mut SlabScratch,
    ) -> u32 {
        let side = f64::from(BRICK_SIDE) * self.grid.cell_size();
        let bc = brick_coords(b, self.brick_dims);
        let (lo, _) = self.grid.cell_bounds(cell_in_brick(bc, 0));
        gather(surface, triangles, &mut scratch.corners);
        slab_of(&scratch.corners, lo + DVec3::splat(0.5 * side), side)
    }

    /// The slab of region `r` (x fastest): `of_brick(entry, out)` appends to `out` the
    /// triangles of the detailed brick with top-level `entry`.
    pub(crate) fn region_slab(
        &self,
        surface: &Surface,
        r: usize,
        of_brick: &(dyn Fn(u32, &mut Vec<u32>) + Sync),
    ) -> u64 {
        let [rx, ry, _] = region_dims(self.brick_dims).map(|d| d as usize);
        let region = [r % rx, r / rx % ry, r / (rx * ry)].map(|v| v as u32);
        let mut triangles: Vec<u32> = Vec::new();
        // The bricks of the region, those of the grid.
        let per_side = REGION_SIDE / BRICK_SIDE;
        let [bx, by, bz] = self.brick_dims;
        for z in region[2] * per_side..((region[2] + 1) * per_side).min(bz) {
            for y in region[1] * per_side..((region[1] + 1) * per_side).min(by) {
                for x in region[0] * per_side..((region[0] + 1) * per_side).min(bx) {
                    let b = ((z * by + y) * bx + x) as usize;
                    if let Some(&entry) = self.bricks.get(b)
                        && entry & UNIFORM == 0
                    {
                        of_brick(entry, &mut triangles);
                    }
                }
            }
        }
        if triangles.is_empty() {
            return FULL_FINE_SLAB;
        }
        sort_unique(&mut triangles, &mut Vec::new());
        let side = f64::from(REGION_SIDE) * self.grid.cell_size();
        let (lo, _) = self.grid.cell_bounds(region.map(|v| v * REGION_SIDE));
        let mut corners = Vec::new();
        gather(surface, &triangles, &mut corners);
        fine_slab_of(&corners, lo + DVec3::splat(0.5 * side), side)
    }
}

/// Sorts `list` and drops its repeats, as `sort_unstable` then `dedup`: through a bit per
/// index between its smallest and largest (in `bits`, reused) when they lie close
/// together, as a block's triangles do in a surface put in spatial order; by sorting
/// otherwise.
pub(crate) fn sort_unique(list: &mut Vec<u32>, bits: &mut Vec<u64>) {
    let (lo, hi) = list
        .iter()
        .fold((u32::MAX, 0), |(lo, hi), &t| (lo.min(t), hi.max(t)));
    let span = hi.saturating_sub(lo) as usize + 1;
    if list.len() < 32 || span > 64 * list.len() {
        list.sort_unstable();
        list.dedup();
        return;
    }
    bits.clear();
    bits.resize(span.div_ceil(64), 0);
    for &t in list.iter() {
        let i = (t - lo) as usize;
        bits[i >> 6] |= 1 << (i & 63);
    }
    list.clear();
    for (w, &word) in bits.iter().enumerate() {
        let mut rest = word;
        while rest != 0 {
            list.push(lo + (w * 64) as u32 + rest.trailing_zeros());
            rest &= rest - 1;
        }
    }
}
