//! Free space: what a long segment's walk reads to cross empty space in strides.
//!
//! A segment crossing a map visits cells in order ([`CellWalk`](super::CellWalk)); where
//! the map knows a cube of cells around the current one to hold no surface cell, the walk
//! skips that cube whole ([`CellWalk::skip_box`](super::CellWalk::skip_box)). Three
//! levels give the cubes, read in this order by [`VoxelMap::look_region`] and
//! [`VoxelMap::look`]:
//!
//! - **regions** of 4×4×4 bricks (32³ cells, [`FreeRegions`]): a byte per region, 64
//!   times smaller than the bricks' and small enough to stay in the cache (128 KiB for
//!   the largest grid), so that far from the surface the walk strides on cached memory;
//! - **bricks** (8³ cells, `VoxelMap::free_bricks`): a byte per brick, near the surface;
//! - in a brick that holds surface cells, its free **blocks** of 4³ cells, from the
//!   brick's surface mask ([`in_free_block`]); other free cells are stepped one by one.
//!
//! All three are derived from the bricks' top-level entries when a map is built or
//! loaded, and are not saved. In a region and in a brick that hold surface cells, the
//! walk also skips the cells before and after the block's slab, the layer in which its
//! triangles lie (`map/slabs.rs`, saved with the map).

use super::VoxelMap;
use super::clearance::chebyshev_distances;
use super::voxel_map::{
    BRICK_BITS, BRICK_SIDE, BrickBits, GRADED, UNIFORM, UNIFORM_PAYLOAD, brick_of, has, local_of,
};

/// How far around a brick with top-level `entry`, in bricks, no brick holds a surface
/// cell (0 for a detailed brick): 1 for a graded brick (it touches a detailed one);
/// otherwise `(r − 1) / 8 + 1` from the entry's reach `r`, capped at 255. That is a bound
/// the reach guarantees: every cell of a brick `k` bricks away lies within `8k` cells of
/// a cell of this one, so within its reach when `8k ≤ r − 1`.
#[inline]
pub(crate) fn free_bricks_of(entry: u32) -> u8 {
    if entry & UNIFORM == 0 {
        0
    } else if entry & GRADED != 0 {
        1
    } else {
        let reach = (entry & UNIFORM_PAYLOAD).max(1);
        ((reach - 1) / BRICK_SIDE + 1).min(u32::from(u8::MAX)) as u8
    }
}

/// Cells along each side of a free block of a detailed brick ([`in_free_block`]).
pub(crate) const BLOCK_SIDE: u32 = 4;

/// Whether the aligned block of 4×4×4 cells of a brick with surface mask `bits` that
/// holds cell `c` (of that brick) holds no surface cell: then a walk can cross it in one
/// stride. (A stride costs about what stepping through three cells does, so smaller
/// blocks are not worth it.)
#[inline]
pub(crate) fn in_free_block(bits: &BrickBits, c: [u32; 3]) -> bool {
    let [x, y, z] = c.map(|v| (v & (BRICK_SIDE - 1)) as usize);
    // Rows of 4 cells along x in 4 rows along y, per mask word (z).
    let (x4, y4, z4) = (x & 4, y & 4, z & 4);
    let quarter = 0x0F0F_0F0F_u64 << (BRICK_SIDE as usize * y4 + x4);
    (bits[z4] | bits[z4 + 1] | bits[z4 + 2] | bits[z4 + 3]) & quarter == 0
}

/// Bricks along each side of a region: `2^REGION_BITS`.
const REGION_BITS: u32 = 2;
/// Cells along each side of a region.
pub(crate) const REGION_SIDE: u32 = 1 << (BRICK_BITS + REGION_BITS);

/// Regions along each axis of a grid of `brick_dims` bricks.
pub(crate) fn region_dims(brick_dims: [u32; 3]) -> [u32; 3] {
    brick_dims.map(|d| d.div_ceil(1 << REGION_BITS))
}

/// For every region of the grid, how far around it, in regions, no region holds a
/// surface cell. Derived from the bricks' top-level entries (a brick holds a surface
/// cell exactly when it is detailed), not saved in a map file.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct FreeRegions {
    /// Regions along each axis.
    dims: [u32; 3],
    /// Per region (x fastest): 0 when it holds a surface cell, `d ≥ 1` when no region
    /// within Chebyshev distance `d − 1` of it (itself included) does; capped at 255.
    around: Vec<u8>,
}

impl FreeRegions {
    /// The free regions of a grid of `brick_dims` bricks with top-level `entries`.
    pub(crate) fn derive(entries: &[u32], brick_dims: [u32; 3]) -> FreeRegions {
        let dims = region_dims(brick_dims);
        let [bx, by, bz] = brick_dims.map(|d| d as usize);
        let mut holds_surface = vec![false; dims.iter().map(|&d| d as usize).product()];
        let index = |[x, y, z]: [usize; 3]| (z * dims[1] as usize + y) * dims[0] as usize + x;
        for z in 0..bz {
            for y in 0..by {
                for x in 0..bx {
                    if entries
                        .get((z * by + y) * bx + x)
                        .is_some_and(|&e| e & UNIFORM == 0)
                    {
                        holds_surface[index([x, y, z].map(|v| v >> REGION_BITS))] = true;
                    }
                }
            }
        }
        let around = chebyshev_distances(dims, |r| holds_surface[r])
            .into_iter()
            .map(|d| d.min(u16::from(u8::MAX)) as u8)
            .collect();
        FreeRegions { dims, around }
    }

    /// The index of the region of cell `c` (x fastest), `None` beyond the grid's regions.
    #[inline]
    pub(crate) fn index(&self, c: [u32; 3]) -> Option<usize> {
        let [x, y, z] = c.map(|v| (v >> (BRICK_BITS + REGION_BITS)) as usize);
        let [rx, ry, rz] = self.dims.map(|d| d as usize);
        (x < rx && y < ry && z < rz).then_some((z * ry + y) * rx + x)
    }

    /// How far around the region of cell `c` no region holds a surface cell (see
    /// [`FreeRegions`]); 0 for a cell beyond the grid's regions.
    #[cfg(test)]
    pub(crate) fn around(&self, c: [u32; 3]) -> u8 {
        self.index(c)
            .and_then(|r| self.around.get(r).copied())
            .unwrap_or(0)
    }

    /// Bytes of heap memory held.
    pub(crate) fn heap_bytes(&self) -> usize {
        self.around.capacity()
    }
}

/// What [`VoxelMap::look_region`] tells of a cell's region.
pub(crate) enum RegionLook {
    /// A cell in a cube of regions without surface cells: the cell's region and every
    /// region within Chebyshev distance `around − 1` of it (`around ≥ 1`).
    Free {
        /// See `VoxelMap::free_regions`.
        around: u8,
    },
    /// A cell of a region that holds surface cells (its index, see
    /// `VoxelMap::region_window`).
    Surface(u32),
    /// A cell outside the grid.
    Outside,
}

/// What [`VoxelMap::look`] tells of a cell of a region that holds surface cells.
pub(crate) enum Look<'a> {
    /// A cell in a cube of bricks without surface cells: the cell's brick and every brick
    /// within Chebyshev distance `around − 1` of it (`around ≥ 1`).
    FreeBricks {
        /// See `VoxelMap::free_bricks`.
        around: u8,
    },
    /// A cell of a detailed brick (one that holds surface cells).
    Detailed {
        /// The detailed brick's index (see `VoxelMap::brick_slab`).
        brick: u32,
        /// What the cell is.
        cell: InBrick<'a>,
    },
    /// A cell outside the grid (or of a brick whose entry lies out of range).
    Outside,
}

/// What a cell of a detailed brick is, as [`VoxelMap::look`] tells it.
pub(crate) enum InBrick<'a> {
    /// A surface cell: its triangles and its slab.
    Triangles(&'a [u32], u32),
    /// A free cell in a free block of [`BLOCK_SIDE`]³ cells ([`in_free_block`]).
    FreeBlock,
    /// Another free cell.
    Free,
}

impl VoxelMap {
    /// What a long segment's walk needs first of cell `c`: its region's byte of free
    /// regions around it, which stays in the cache. Clearances are not read: they bound
    /// the distance cell by cell, in memory that is cold when a segment comes from far
    /// away.
    #[inline]
    pub(crate) fn look_region(&self, c: [u32; 3]) -> RegionLook {
        if !self.grid.contains(c) {
            return RegionLook::Outside;
        }
        match self.free_regions.index(c) {
            Some(r) => match self.free_regions.around.get(r) {
                Some(&around) if around > 0 => RegionLook::Free { around },
                _ => RegionLook::Surface(r as u32),
            },
            None => RegionLook::Outside,
        }
    }

    /// What a long segment's walk needs of cell `c` of a region that holds surface cells
    /// ([`look_region`](Self::look_region)), reading as little as it can: its brick's
    /// byte of free bricks around it; and only in a detailed brick its top-level entry
    /// and surface mask (and, for a surface cell, where its triangle list lies and its
    /// slab; not the list itself).
    #[inline]
    pub(crate) fn look(&self, c: [u32; 3]) -> Look<'_> {
        if !self.grid.contains(c) {
            return Look::Outside;
        }
        let b = brick_of(c, self.brick_dims);
        if let Some(&bricks) = self.free_bricks.get(b)
            && bricks > 0
        {
            return Look::FreeBricks { around: bricks };
        }
        // A detailed brick: its entry is its index.
        let Some(&brick) = self.bricks.get(b).filter(|&&e| e & UNIFORM == 0) else {
            return Look::Outside;
        };
        let local = local_of(c);
        let Some(bits) = self.surface_bits.get(brick as usize) else {
            return Look::Outside;
        };
        let cell = if !has(bits, local) {
            if in_free_block(bits, c) {
                InBrick::FreeBlock
            } else {
                InBrick::Free
            }
        } else {
            match self.listed_at(brick as usize, local) {
                Some((triangles, s)) => InBrick::Triangles(triangles, self.slab(s)),
                None => InBrick::Free,
            }
        };
        Look::Detailed { brick, cell }
    }

    /// Sets [`free_bricks`](Self::free_bricks) and [`free_regions`](Self::free_regions)
    /// from the top-level entries.
    pub(crate) fn derive_free_space(&mut self) {
        self.free_bricks = self.bricks.iter().map(|&e| free_bricks_of(e)).collect();
        self.free_regions = FreeRegions::derive(&self.bricks, self.brick_dims);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::{MapOptions, VoxelMap, decode, encode};
    use crate::mesh::shapes::Catalog;
    use crate::mesh::{Surface, SurfaceOptions};

    /// Maps of three shapes fine enough for strides of several bricks and regions, each
    /// as built and as loaded from its file.
    fn built_and_loaded() -> Vec<(Catalog, [VoxelMap; 2])> {
        [
            (Catalog::Blob, 20_000, 0.0005),
            (Catalog::Sphere, 2_000, 0.001),
            (Catalog::ThinPlate, 2_000, 0.0005),
        ]
        .into_iter()
        .map(|(shape, triangles, cell)| {
            let surface = Surface::new(shape.with_triangles(triangles), &SurfaceOptions::default())
                .expect("a surface");
            let options = MapOptions {
                cell_size_m: Some(cell),
                ..MapOptions::default()
            };
            let built = VoxelMap::build(&surface, &options).expect("a map");
            let (_, loaded) = decode(&encode(&surface, &built)).expect("loads");
            (shape, [built, loaded])
        })
        .collect()
    }

    /// The free bricks around each brick (`VoxelMap::free_bricks`, derived from the
    /// entries) are never more than the true distance to the nearest detailed brick, 0
    /// exactly on detailed bricks, and equal to it from three bricks out, where the
    /// entries store it.
    #[test]
    fn free_bricks_bound_the_distance_to_the_surface() {
        let mut far = 0;
        for (shape, maps) in built_and_loaded() {
            for map in &maps {
                let distances =
                    chebyshev_distances(map.brick_dims, |b| map.bricks[b] & UNIFORM == 0);
                assert_eq!(map.free_bricks.len(), map.bricks.len());
                for (b, (&free, &d)) in map.free_bricks.iter().zip(&distances).enumerate() {
                    let d = d.min(u16::from(u8::MAX)) as u8;
                    assert_eq!(free == 0, d == 0, "{shape:?}, brick {b}");
                    assert!(free <= d, "{shape:?}, brick {b}: {free} > {d}");
                    if d >= 3 {
                        assert_eq!(free, d, "{shape:?}, brick {b}");
                        far += 1;
                    }
                }
            }
        }
        assert!(far > 20, "{far}");
    }

    /// Every region's count equals the Chebyshev distance, in regions, to the nearest
    /// region with a surface cell, by brute force over the grid's surface cells (capped
    /// as stored); and some regions are far enough for a stride of several regions.
    #[test]
    fn free_regions_are_the_distance_to_the_surface() {
        let mut far = 0;
        for (shape, maps) in built_and_loaded() {
            let dims = maps[0].grid().dims();
            let side = REGION_SIDE;
            let mut surface_regions = Vec::new();
            for z in 0..dims[2] {
                for y in 0..dims[1] {
                    for x in 0..dims[0] {
                        if !maps[0].triangles_in([x, y, z]).is_empty() {
                            surface_regions.push([x, y, z].map(|v| i64::from(v / side)));
                        }
                    }
                }
            }
            surface_regions.dedup();
            let regions = dims.map(|d| d.div_ceil(side));
            for map in &maps {
                assert_eq!(map.free_regions.dims, regions, "{shape:?}");
                for z in 0..regions[2] {
                    for y in 0..regions[1] {
                        for x in 0..regions[0] {
                            let here = [x, y, z].map(i64::from);
                            let brute = surface_regions
                                .iter()
                                .map(|r| (0..3).map(|k| (r[k] - here[k]).abs()).max().unwrap_or(0))
                                .min()
                                .unwrap_or(i64::MAX)
                                .min(255) as u8;
                            let cell = [x, y, z].map(|v| v * side);
                            assert_eq!(map.free_regions.around(cell), brute, "{shape:?} {here:?}");
                            far += usize::from(brute >= 2);
                        }
                    }
                }
            }
        }
        assert!(far > 20, "{far}");
    }

    /// On random surface masks of a brick, a free cell's block of 4³ cells is reported
    /// free exactly when no cell of it is a surface cell (brute force over the block).
    #[test]
    fn free_blocks_hold_no_surface_cell() {
        use crate::map::voxel_map::BRICK_CELLS;
        use crate::rng::SplitMix64;
        let mut random = SplitMix64::new(11);
        let mut free = 0;
        for case in 0..200 {
            let density = [0.002, 0.01, 0.05, 0.2][case % 4];
            let mut bits: BrickBits = Default::default();
            for local in 0..BRICK_CELLS {
                if random.next_unit() < density {
                    bits[local >> 6] |= 1 << (local & 63);
                }
            }
            // Cells of a brick somewhere in a grid (the brick's offset must not matter).
            let offset = [3, 0, 7].map(|k: u32| k * BRICK_SIDE);
            for local in 0..BRICK_CELLS {
                if has(&bits, local) {
                    continue;
                }
                let at = [local & 7, (local >> 3) & 7, local >> 6];
                let c: [u32; 3] = std::array::from_fn(|k| offset[k] + at[k] as u32);
                let block_is_free = (0..BRICK_CELLS).all(|other| {
                    let o = [other & 7, (other >> 3) & 7, other >> 6];
                    (0..3).any(|k| o[k] / 4 != at[k] / 4) || !has(&bits, other)
                });
                assert_eq!(
                    in_free_block(&bits, c),
                    block_is_free,
                    "case {case}, cell {at:?}"
                );
                free += usize::from(block_is_free);
            }
        }
        assert!(free > 1000, "{free}");
    }

    /// A cell beyond the grid's regions reads 0 (no stride), never another region's count.
    #[test]
    fn cells_beyond_the_regions_read_zero() {
        let entries = vec![UNIFORM; 8 * 8 * 8];
        let regions = FreeRegions::derive(&entries, [8, 8, 8]);
        assert_eq!(regions.dims, [2, 2, 2]);
        assert_eq!(regions.around([0, 0, 0]), 255);
        assert_eq!(regions.around([64, 0, 0]), 0);
        assert_eq!(regions.around([0, 64, 0]), 0);
        assert_eq!(regions.around([0, 0, 64]), 0);
    }
}
