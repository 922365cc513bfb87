//! Outside versus inside: the flood fill from the padding, then a check of each enclosed
//! region with the generalised winding number.
//!
//! Both floods work on the sparse layout: a uniform brick (no surface cell, so all its
//! cells connected) is one node; in a detailed brick the reached cells are a bit mask,
//! grown by dilation inside the brick's available cells from the reached cells of its
//! face neighbours. A brick whose mask grows sends its neighbours back to the work list,
//! until nothing changes.

use std::collections::BTreeMap;

use super::CellState;
use super::voxel_map::{
    BRICK_BITS, BrickBits, MASK_WORDS, UNIFORM, UNIFORM_STATE_SHIFT, VoxelMap, brick_coords,
    brick_of, cell_in_brick, entry_state, in_grid_bits, uniform_entry,
};
use crate::mesh::{Surface, winding_number};

/// Largest total work, in triangles × enclosed regions, spent on winding numbers when
/// checking the regions the flood fill leaves inside: about a second on one core (a solid
/// angle costs about 30 ns). A mesh needing more (many separate parts, each its own
/// region, times many triangles) keeps its remaining regions inside unchecked.
pub(crate) const MAX_ENCLOSED_WINDING_WORK: u64 = 1 << 25;

/// A uniform entry reached by the current region (a state no finished map holds).
const VISITED: u32 = UNIFORM | (2 << UNIFORM_STATE_SHIFT);

/// Classifies the non-surface cells of a solid's map. On entry (from
/// [`assemble`](super::build)) uniform bricks are inside and detailed bricks have no
/// inside cells.
///
/// 1. Cells connected to the padding through face-adjacent non-surface cells are outside.
/// 2. Every other connected region of non-surface cells is checked once: the generalised
///    winding number at the centre of its first cell (in brick order), rounded, decides
///    by the non-zero rule whether it is inside (not 0) or outside — a cavity, or a pocket
///    of outside space closed off at the resolution of the grid. An inside region whose
///    winding number is not 1 (where closed parts overlap, or an inside-out part) is also
///    listed in the map's overlap cells. At most [`MAX_ENCLOSED_WINDING_WORK`] triangle
///    evaluations are spent; regions beyond stay inside (taken as winding 1).
///
/// Deterministic. `O(uniform bricks + detailed bricks × passes + regions × triangles)`.
pub(crate) fn flood_fill(map: &mut VoxelMap, surface: &Surface) {
    let bdims = map.brick_dims;
    let dims = map.grid.dims();
    let available = free_cells(map);
    // The entries and inside masks change all through the flood: taken out as vectors
    // and put back at the end.
    let mut bricks = map.bricks.take_vec();
    let top_of_detailed = top_of_detailed(&bricks, map.detailed_count());
    // Inside cells whose winding number is not 1, by top-level brick.
    let mut overlap: BTreeMap<usize, BrickBits> = BTreeMap::new();
    let mut inside_bits = map.inside_bits.take_vec();
    let mut flood = Flood {
        reached: vec![[0; MASK_WORDS]; available.len()],
        available,
        queued: vec![false; bricks.len()],
        work: Vec::new(),
        touched: Vec::new(),
        uniform: Vec::new(),
    };

    // 1. The padding is one connected shell of non-surface cells: cell [0, 0, 0] seeds it.
    flood.grow(
        &mut bricks,
        bdims,
        0,
        0,
        uniform_entry(CellState::Outside, 0),
    );
    flood.take_region();
    for (inside, free) in inside_bits.iter_mut().zip(&flood.available) {
        *inside = *free;
    }

    // 2. The regions left, one by one, in brick order.
    let triangles = surface.triangle_count() as u64;
    let mut budget = MAX_ENCLOSED_WINDING_WORK;
    let mut b = 0;
    while b < bricks.len() && triangles <= budget {
        let entry = bricks[b];
        let seed = if entry & UNIFORM != 0 {
            (entry_state(entry) == CellState::Inside).then_some(0)
        } else {
            first_cell(&flood.available[entry as usize])
        };
        let Some(local) = seed else {
            b += 1;
            continue;
        };
        budget -= triangles;
        flood.grow(&mut bricks, bdims, b, local, VISITED);
        let centre = map
            .grid
            .cell_centre(cell_in_brick(brick_coords(b, bdims), local));
        let winding = winding_number(surface, centre).round();
        let inside = winding != 0.0;
        let (touched, uniform) = flood.take_region();
        if inside && winding != 1.0 {
            for (d, reached) in &touched {
                let bits = overlap
                    .entry(top_of_detailed[*d])
                    .or_insert([0; MASK_WORDS]);
                for (o, r) in bits.iter_mut().zip(reached) {
                    *o |= r;
                }
            }
            for &u in &uniform {
                overlap.insert(u, in_grid_bits(brick_coords(u, bdims), dims));
            }
        }
        if !inside {
            for (d, reached) in touched {
                for (inside, reached) in inside_bits[d].iter_mut().zip(reached) {
                    *inside &= !reached;
                }
            }
            for u in uniform {
                bricks[u] = uniform_entry(CellState::Outside, 0);
            }
        }
    }
    store(map, bricks, inside_bits, overlap);
}

/// The free (non-surface, in-grid) cells of each detailed brick.
fn free_cells(map: &VoxelMap) -> Vec<BrickBits> {
    let bdims = map.brick_dims;
    let dims = map.grid.dims();
    let mut available: Vec<BrickBits> = vec![[0; MASK_WORDS]; map.detailed_count()];
    for (b, &entry) in map.bricks.iter().enumerate() {
        if entry & UNIFORM == 0
            && let (Some(free), Some(surface)) = (
                available.get_mut(entry as usize),
                map.surface_bits.get(entry as usize),
            )
        {
            let in_grid = in_grid_bits(brick_coords(b, bdims), dims);
            for z in 0..MASK_WORDS {
                free[z] = in_grid[z] & !surface[z];
            }
        }
    }
    available
}

/// The top-level index of each of the `detailed` detailed bricks among `bricks` (those
/// entries never change in the flood).
fn top_of_detailed(bricks: &[u32], detailed: usize) -> Vec<usize> {
    let mut top_of_detailed = vec![0usize; detailed];
    for (b, &entry) in bricks.iter().enumerate() {
        if entry & UNIFORM == 0
            && let Some(top) = top_of_detailed.get_mut(entry as usize)
        {
            *top = b;
        }
    }
    top_of_detailed
}

/// Puts the flood's results back in the map: the regions still marked visited are inside.
fn store(
    map: &mut VoxelMap,
    mut bricks: Vec<u32>,
    inside_bits: Vec<BrickBits>,
    overlap: BTreeMap<usize, BrickBits>,
) {
    for entry in &mut bricks {
        if *entry == VISITED {
            *entry = uniform_entry(CellState::Inside, 0);
        }
    }
    map.bricks = bricks.into();
    map.inside_bits = inside_bits.into();
    map.overlap_bricks = overlap
        .keys()
        .map(|&b| b as u32)
        .collect::<Vec<u32>>()
        .into();
    map.overlap_bits = overlap.into_values().collect::<Vec<BrickBits>>().into();
}

/// The first set cell of `bits`.
pub(super) fn first_cell(bits: &BrickBits) -> Option<usize> {
    let z = bits.iter().position(|&w| w != 0)?;
    Some(z * 64 + bits[z].trailing_zeros() as usize)
}

/// The state of one flood: the cells still available, those reached by the current
/// region, the work list.
struct Flood {
    /// Per detailed brick: free cells not yet in any region.
    available: Vec<BrickBits>,
    /// Per detailed brick: the cells the current region has reached.
    reached: Vec<BrickBits>,
    queued: Vec<bool>,
    work: Vec<usize>,
    /// Detailed bricks the current region has reached.
    touched: Vec<usize>,
    /// Uniform bricks the current region has reached.
    uniform: Vec<usize>,
}

impl Flood {
    /// Grows a region from cell `local` of brick `seed` through face-adjacent available
    /// cells and uniform inside bricks; reached uniform bricks get `mark` as entry.
    fn grow(&mut self, bricks: &mut [u32], bdims: [u32; 3], seed: usize, local: usize, mark: u32) {
        let entry = bricks[seed];
        if entry & UNIFORM == 0 {
            let d = entry as usize;
            self.reached[d][local >> 6] |= 1 << (local & 63);
            self.touched.push(d);
        }
        self.reach_brick(bricks, seed, mark);
        if !self.queued[seed] {
            self.queued[seed] = true;
            self.work.push(seed);
        }
        while let Some(b) = self.work.pop() {
            self.queued[b] = false;
            let bc = brick_coords(b, bdims);
            let entry = bricks[b];
            let neighbours = FACES.map(|(axis, up)| {
                step(bc, axis, up, bdims).map(|n| brick_of(n.map(|x| x << BRICK_BITS), bdims))
            });
            if entry & UNIFORM != 0 {
                // Reached as a whole: every neighbour can gain from it.
                for nb in neighbours.into_iter().flatten() {
                    self.reach_brick(bricks, nb, mark);
                }
                continue;
            }
            let d = entry as usize;
            let mut seeds = self.reached[d];
            for (face, nb) in neighbours.iter().enumerate() {
                let Some(nb) = *nb else { continue };
                let n_entry = bricks[nb];
                let layer = if n_entry == mark {
                    FULL
                } else if n_entry & UNIFORM == 0 {
                    self.reached[n_entry as usize]
                } else {
                    continue;
                };
                add_face_seeds(&mut seeds, &layer, face);
            }
            let grown = flood_brick(seeds, &self.available[d]);
            if grown == self.reached[d] {
                continue;
            }
            if self.reached[d] == [0; MASK_WORDS] {
                self.touched.push(d);
            }
            self.reached[d] = grown;
            for (face, nb) in neighbours.iter().enumerate() {
                let Some(nb) = *nb else { continue };
                if touches_face(&grown, face) {
                    self.reach_brick(bricks, nb, mark);
                }
            }
        }
    }

    /// A brick next to reached cells: a uniform inside brick joins the region (its entry
    /// becomes `mark`); either kind goes on the work list (once).
    fn reach_brick(&mut self, bricks: &mut [u32], b: usize, mark: u32) {
        let entry = bricks[b];
        if entry & UNIFORM != 0 {
            if entry_state(entry) != CellState::Inside || entry == mark {
                return;
            }
            bricks[b] = mark;
            self.uniform.push(b);
        }
        if !self.queued[b] {
            self.queued[b] = true;
            self.work.push(b);
        }
    }

    /// Ends the current region: its cells leave the available ones; returns the reached
    /// cells per detailed brick and the reached uniform bricks.
    fn take_region(&mut self) -> (Vec<(usize, BrickBits)>, Vec<usize>) {
        let touched: Vec<(usize, BrickBits)> = self
            .touched
            .drain(..)
            .map(|d| {
                let reached = std::mem::take(&mut self.reached[d]);
                for (free, taken) in self.available[d].iter_mut().zip(reached) {
                    *free &= !taken;
                }
                (d, reached)
            })
            .collect();
        (touched, std::mem::take(&mut self.uniform))
    }
}

/// Every bit set.
const FULL: BrickBits = [u64::MAX; MASK_WORDS];

/// Rows `y = 0` and `y = 7` of a word.
const ROW_Y0: u64 = 0xff;
const ROW_Y7: u64 = 0xff << 56;

/// Bits at `x = 0` and at `x = 7` of every row.
pub(super) const COLUMN_X0: u64 = 0x0101_0101_0101_0101;
pub(super) const COLUMN_X7: u64 = 0x8080_8080_8080_8080;

/// Adds to `seeds` the cells next to the cells `layer` of the neighbour across face
/// `face` (index into [`FACES`]: −x, +x, −y, +y, −z, +z).
pub(super) fn add_face_seeds(seeds: &mut BrickBits, layer: &BrickBits, face: usize) {
    let last = MASK_WORDS - 1;
    match face {
        0 => (0..=last).for_each(|z| seeds[z] |= (layer[z] & COLUMN_X7) >> 7),
        1 => (0..=last).for_each(|z| seeds[z] |= (layer[z] & COLUMN_X0) << 7),
        2 => (0..=last).for_each(|z| seeds[z] |= layer[z] >> 56),
        3 => (0..=last).for_each(|z| seeds[z] |= (layer[z] & ROW_Y0) << 56),
        4 => seeds[0] |= layer[last],
        _ => seeds[last] |= layer[0],
    }
}

/// Whether `bits` has a cell on face `face` (see [`add_face_seeds`]).
pub(super) fn touches_face(bits: &BrickBits, face: usize) -> bool {
    let last = MASK_WORDS - 1;
    match face {
        0 => bits.iter().any(|&w| w & COLUMN_X0 != 0),
        1 => bits.iter().any(|&w| w & COLUMN_X7 != 0),
        2 => bits.iter().any(|&w| w & ROW_Y0 != 0),
        3 => bits.iter().any(|&w| w & ROW_Y7 != 0),
        4 => bits[0] != 0,
        _ => bits[last] != 0,
    }
}

/// The cells of `free` connected to `seeds ∩ free` through face-adjacent cells of `free`,
/// within one brick.
pub(super) fn flood_brick(seeds: BrickBits, free: &BrickBits) -> BrickBits {
    let last = MASK_WORDS - 1;
    let mut bits = seeds;
    for z in 0..=last {
        bits[z] &= free[z];
    }
    loop {
        let mut next = bits;
        for z in 0..=last {
            let w = bits[z];
            let mut grown =
                w | ((w << 1) & !COLUMN_X0) | ((w >> 1) & !COLUMN_X7) | (w << 8) | (w >> 8);
            if z > 0 {
                grown |= bits[z - 1];
            }
            if z < last {
                grown |= bits[z + 1];
            }
            next[z] = grown & free[z];
        }
        if next == bits {
            return bits;
        }
        bits = next;
    }
}

/// The six face directions: axis and whether towards larger indices.
pub(super) const FACES: [(usize, bool); 6] = [
    (0, false),
    (0, true),
    (1, false),
    (1, true),
    (2, false),
    (2, true),
];

/// The neighbour of `c` one step along `axis`, if inside a grid of `dims`.
#[inline]
pub(super) fn step(c: [u32; 3], axis: usize, up: bool, dims: [u32; 3]) -> Option<[u32; 3]> {
    let mut n = c;
    if up {
        n[axis] = c[axis].checked_add(1).filter(|&x| x < dims[axis])?;
    } else {
        n[axis] = c[axis].checked_sub(1)?;
    }
    Some(n)
}
