//! Building a voxel map: choose the cell size ([`super::cell_size`]), bin the (cell,
//! triangle) pairs ([`super::bin`]), assemble the bricks, then the flood fill and the
//! clearance ([`super::fill`]).

use crate::par::*;

use super::bin::{bin_triangles, sort_by_cell};
use super::cell_size::SizeModel;
use super::clearance::compute_clearance;
use super::fill::flood_fill;
use super::grid::Grid;
use super::voxel_map::{
    BRICK_BITS, BRICK_CELLS, BrickBits, MASK_WORDS, VoxelMap, brick_dims, uniform_entry,
};
use super::{CellSizeRule, CellState, MapError, MapOptions};
use crate::mesh::Surface;

/// Progress fraction reached at the end of each phase.
pub(super) const PROGRESS_BINNED: f64 = 0.6;
const PROGRESS_SORTED: f64 = 0.75;
const PROGRESS_ASSEMBLED: f64 = 0.8;
const PROGRESS_FILLED: f64 = 0.9;

impl VoxelMap {
    /// Builds the voxel map of `surface` (object frame).
    ///
    /// Equivalent to [`VoxelMap::build_with_progress`] without a progress callback.
    ///
    /// # Errors
    /// See [`VoxelMap::build_with_progress`].
    ///
    /// # Examples
    /// ```
    /// use haphe::map::{CellState, MapOptions, VoxelMap};
    /// use haphe::mesh::{shapes, Surface, SurfaceOptions};
    /// let surface = Surface::new(shapes::sphere(0.1, 3), &SurfaceOptions::default()).unwrap();
    /// let map = VoxelMap::build(&surface, &MapOptions::default()).unwrap();
    /// let centre = map.grid().cell_of(haphe::DVec3::ZERO).unwrap();
    /// assert_eq!(map.state(centre), CellState::Inside);
    /// assert!(map.clearance(centre) > 1);
    /// let far = map.grid().cell_of(haphe::DVec3::new(0.0, 0.0, 0.1)).unwrap();
    /// assert_eq!(map.state(far), CellState::Surface);
    /// assert!(!map.triangles_in(far).is_empty());
    /// ```
    pub fn build(surface: &Surface, options: &MapOptions) -> Result<VoxelMap, MapError> {
        VoxelMap::build_with_progress(surface, options, &|_| {})
    }

    /// Builds the voxel map of `surface` (object frame), reporting progress.
    ///
    /// `progress` is called with the fraction done, from 0 to 1, one call at a time (on
    /// the thread that runs the build: a thread of rayon's pool, or the calling thread
    /// when that is one or without the `parallel` feature), non-decreasing, about 25 times — except that in the rare case
    /// where the finished map turns out larger than the budget and an automatic cell size
    /// must grow, the fraction starts again from 0 for the next attempt.
    ///
    /// The result depends only on the surface and the options, never on the number of
    /// threads: the same inputs give the same map, byte for byte.
    ///
    /// # Errors
    /// - [`MapError::InvalidCellSize`], [`MapError::InvalidTrianglesPerCell`] for bad
    ///   options;
    /// - [`MapError::TooManyCells`] when a given cell size makes too large a grid;
    /// - [`MapError::OverBudget`] when the map does not fit
    ///   [`MapOptions::memory_budget_bytes`] with the given cell size, or with any cell
    ///   size for an automatic one;
    /// - [`MapError::TooManyTriangleRefs`] beyond 2³² (cell, triangle) pairs.
    ///
    /// # Performance
    /// Parallel (rayon, feature `parallel`), `O(T + P log P + B + D)` for `T` triangles, `P` (cell, triangle)
    /// pairs, `B` bricks and `D` cells in bricks near the surface; about 0.6 s per million
    /// triangles on two cores. Peak memory is the finished map plus about 16 bytes per
    /// pair (the pairs, and their sorted copy). Not for a servo tick.
    pub fn build_with_progress(
        surface: &Surface,
        options: &MapOptions,
        progress: &(dyn Fn(f64) + Sync),
    ) -> Result<VoxelMap, MapError> {
        if !(options.triangles_per_cell.is_finite() && options.triangles_per_cell >= 1.0) {
            return Err(MapError::InvalidTrianglesPerCell {
                value: options.triangles_per_cell,
            });
        }
        on_pool(|| build_on_pool(surface, options, progress))
    }
}

/// [`VoxelMap::build_with_progress`] once the options are checked.
fn build_on_pool(
    surface: &Surface,
    options: &MapOptions,
    progress: &(dyn Fn(f64) + Sync),
) -> Result<VoxelMap, MapError> {
    let model = SizeModel::of(surface);
    let budget = options.memory_budget_bytes;
    let (mut grid, mut rule) = match options.cell_size_m {
        Some(h) => (model.given_grid(h, budget)?, CellSizeRule::Given),
        None => model.automatic_grid(options.triangles_per_cell, 0, budget)?,
    };
    loop {
        progress(0.0);
        let map = build_on_grid(surface, grid, rule, progress)?;
        let bytes = map.heap_bytes();
        if bytes <= budget {
            progress(1.0);
            return Ok(map);
        }
        match rule {
            CellSizeRule::Given => {
                return Err(MapError::OverBudget {
                    cell_size_m: grid.cell_size(),
                    needed_bytes: bytes as u64,
                    budget_bytes: budget,
                });
            }
            CellSizeRule::Automatic { enlargements, .. } => {
                (grid, rule) =
                    model.automatic_grid(options.triangles_per_cell, enlargements + 1, budget)?;
            }
        }
    }
}

/// Builds the map on a chosen grid.
pub(super) fn build_on_grid(
    surface: &Surface,
    grid: Grid,
    rule: CellSizeRule,
    progress: &(dyn Fn(f64) + Sync),
) -> Result<VoxelMap, MapError> {
    let keys = bin_triangles(surface, &grid, progress);
    let refs = keys.iter().map(|part| part.len() as u64).sum::<u64>();
    if refs >= u64::from(u32::MAX) {
        return Err(MapError::TooManyTriangleRefs { refs });
    }
    let keys = sort_by_cell(keys, key_bits(&grid));
    progress(PROGRESS_SORTED);

    let solid = surface.is_solid();
    let mut map = assemble(&keys, grid, solid);
    map.triangle_refs = keys
        .par_iter()
        .map(|&k| k as u32)
        .collect::<Vec<u32>>()
        .into();
    drop(keys);
    map.triangle_count = surface.triangle_count() as u32;
    map.cell_size_rule = rule;
    progress(PROGRESS_ASSEMBLED);

    if solid {
        flood_fill(&mut map, surface);
    }
    progress(PROGRESS_FILLED);
    compute_clearance(&mut map);
    map.derive_free_space();
    map.derive_slabs(surface);
    shrink(&mut map);
    Ok(map)
}

/// Frees the spare capacity of a finished map's arrays.
pub(super) fn shrink(map: &mut VoxelMap) {
    map.bricks.modify(Vec::shrink_to_fit);
    map.surface_bits.modify(Vec::shrink_to_fit);
    map.inside_bits.modify(Vec::shrink_to_fit);
    map.surface_before.modify(Vec::shrink_to_fit);
    map.surface_first.modify(Vec::shrink_to_fit);
    map.triangle_start.modify(Vec::shrink_to_fit);
    map.triangle_refs.modify(Vec::shrink_to_fit);
    map.slabs.modify(Vec::shrink_to_fit);
    map.clearances.modify(Vec::shrink_to_fit);
}

/// The bits a cell key of `grid` uses (see [`bin_triangles`]).
pub(super) fn key_bits(grid: &Grid) -> u32 {
    u64::BITS
        - (brick_dims(grid.dims())
            .iter()
            .map(|&d| u64::from(d))
            .product::<u64>()
            * BRICK_CELLS as u64)
            .leading_zeros()
}

/// The map's arrays from the sorted keys: a detailed brick for every brick with a surface
/// cell (in brick order), with its surface mask, the surface cells' triangle starts, and
/// the counts of surface cells before each mask word. Inside masks start empty (the flood
/// fill sets them); uniform bricks start inside for a solid and outside otherwise.
pub(super) fn assemble(keys: &[u64], grid: Grid, solid: bool) -> VoxelMap {
    let bdims = brick_dims(grid.dims());
    let brick_count = bdims.iter().map(|&d| d as usize).product();
    let free = if solid {
        CellState::Inside
    } else {
        CellState::Outside
    };
    let mut bricks = vec![uniform_entry(free, 0); brick_count];
    let mut surface_bits: Vec<BrickBits> = Vec::new();
    let mut surface_first: Vec<u32> = Vec::new();
    let mut triangle_start: Vec<u32> = Vec::new();
    let (mut current_brick, mut current_cell) = (u64::MAX, u64::MAX);
    for (r, &key) in keys.iter().enumerate() {
        let cell_key = key >> 32;
        if cell_key == current_cell {
            continue;
        }
        current_cell = cell_key;
        let brick = cell_key >> (3 * BRICK_BITS);
        if brick != current_brick {
            current_brick = brick;
            bricks[brick as usize] = surface_bits.len() as u32;
            surface_first.push(triangle_start.len() as u32);
            surface_bits.push([0; MASK_WORDS]);
        }
        let local = (cell_key as usize) & (BRICK_CELLS - 1);
        if let Some(bits) = surface_bits.last_mut() {
            bits[local >> 6] |= 1 << (local & 63);
        }
        triangle_start.push(r as u32);
    }
    surface_first.push(triangle_start.len() as u32);
    triangle_start.push(keys.len() as u32);
    assembled(
        grid,
        solid,
        bricks,
        surface_bits,
        surface_first,
        triangle_start,
    )
}

/// A map of the detailed bricks `surface_bits` (in brick order, their top-level
/// `bricks` entries their indices, the others uniform), their cells' starts, and no
/// triangle list yet, as [`assemble`] hands it over.
pub(super) fn assembled(
    grid: Grid,
    solid: bool,
    bricks: Vec<u32>,
    surface_bits: Vec<BrickBits>,
    surface_first: Vec<u32>,
    triangle_start: Vec<u32>,
) -> VoxelMap {
    let bdims = brick_dims(grid.dims());
    let surface_before: Vec<[u16; MASK_WORDS]> = surface_bits
        .iter()
        .map(|bits| {
            let mut before = [0u16; MASK_WORDS];
            for z in 1..MASK_WORDS {
                before[z] = before[z - 1] + bits[z - 1].count_ones() as u16;
            }
            before
        })
        .collect();
    VoxelMap {
        grid,
        brick_dims: bdims,
        bricks: bricks.into(),
        free_bricks: Vec::new(),
        free_regions: Default::default(),
        slabs: Default::default(),
        brick_slabs: Default::default(),
        region_slabs: Default::default(),
        inside_bits: vec![[0; MASK_WORDS]; surface_bits.len()].into(),
        overlap_bricks: Default::default(),
        overlap_bits: Default::default(),
        surface_bits: surface_bits.into(),
        surface_before: surface_before.into(),
        surface_first: surface_first.into(),
        clearances: Default::default(),
        triangle_start: triangle_start.into(),
        triangle_refs: Default::default(),
        triangle_count: 0,
        solid,
        cell_size_rule: CellSizeRule::Given,
        provenance: None,
    }
}
