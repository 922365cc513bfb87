//! Inside and outside after a deformation, decided again only where a moved triangle may
//! have swept.
//!
//! A point's winding number changes only when the surface passes through it: a moved
//! triangle, on its way from its old corners to its new ones, stays in the box of both.
//! A cell of no such box keeps its winding number, so its state (inside, outside, in an
//! overlap) is the old map's. The cells of the bricks that meet a box (the dirty bricks)
//! are classified again as the build does: face-adjacent non-surface cells share their
//! winding number, so each connected group of them (grown as bit masks, as the build's
//! flood grows them) takes the state of a clean non-surface cell next to it, or, with
//! none, the winding number at its first cell.

use super::super::CellState;
use super::super::fill::{FACES, add_face_seeds, first_cell, flood_brick, step, touches_face};
use super::super::voxel_map::{
    BRICK_BITS, BrickBits, MASK_WORDS, UNIFORM, VoxelMap, brick_coords, brick_of, cell_in_brick,
    entry_state, in_grid_bits, uniform_entry,
};
use crate::mesh::{Surface, winding_number};

/// No slot: a clean brick.
const CLEAN: u32 = u32::MAX;

/// Classifies the non-surface cells of `map` (a solid's, as assembled: uniform bricks
/// inside, no inside cells in detailed bricks), the map of `surface` on the grid of `old`,
/// whose state it keeps outside the bricks `dirty` (top-level indices, increasing).
pub(super) fn refill(map: &mut VoxelMap, old: &VoxelMap, surface: &Surface, dirty: &[usize]) {
    let mut slot_of = vec![CLEAN; map.bricks.len()];
    for (s, &b) in dirty.iter().enumerate() {
        slot_of[b] = s as u32;
    }
    let mut bricks = map.bricks.take_vec();
    let mut inside_bits = map.inside_bits.take_vec();
    // Clean bricks: the old states (a clean brick holds the same surface cells).
    for (b, entry) in bricks.iter_mut().enumerate() {
        if slot_of[b] != CLEAN {
            continue;
        }
        let Some(&old_entry) = old.bricks.get(b) else {
            continue;
        };
        if *entry & UNIFORM != 0 {
            *entry = uniform_entry(entry_state(old_entry), 0);
        } else if let (Some(inside), Some(before)) = (
            inside_bits.get_mut(*entry as usize),
            old.inside_bits.get(old_entry as usize),
        ) {
            *inside = *before;
        }
    }
    let classes = classify(map, &bricks, old, surface, dirty, &slot_of);
    let mut overlap: Vec<(u32, BrickBits)> = Vec::new();
    for (s, &b) in dirty.iter().enumerate() {
        let (inside, overlapping) = (classes.inside[s], classes.overlap[s]);
        let entry = bricks[b];
        if entry & UNIFORM != 0 {
            // No surface cell: all its cells form one group.
            let state = if inside == [0; MASK_WORDS] {
                CellState::Outside
            } else {
                CellState::Inside
            };
            bricks[b] = uniform_entry(state, 0);
            if overlapping != [0; MASK_WORDS] {
                let bdims = map.brick_dims;
                overlap.push((
                    b as u32,
                    in_grid_bits(brick_coords(b, bdims), map.grid.dims()),
                ));
            }
        } else {
            if let Some(bits) = inside_bits.get_mut(entry as usize) {
                *bits = inside;
            }
            if overlapping != [0; MASK_WORDS] {
                overlap.push((b as u32, overlapping));
            }
        }
    }
    // The clean bricks' overlap cells, merged in brick order.
    let kept = old
        .overlap_bricks
        .iter()
        .zip(old.overlap_bits.iter())
        .filter(|&(&b, _)| slot_of.get(b as usize) == Some(&CLEAN))
        .map(|(&b, &bits)| (b, bits));
    overlap.extend(kept);
    overlap.sort_unstable_by_key(|&(b, _)| b);
    map.bricks = bricks.into();
    map.inside_bits = inside_bits.into();
    map.overlap_bricks = overlap.iter().map(|&(b, _)| b).collect::<Vec<u32>>().into();
    map.overlap_bits = overlap
        .into_iter()
        .map(|(_, bits)| bits)
        .collect::<Vec<BrickBits>>()
        .into();
}

/// The inside cells of each dirty brick, and those of them whose winding number is not 1.
struct Classes {
    inside: Vec<BrickBits>,
    overlap: Vec<BrickBits>,
}

/// What a group of cells is.
#[derive(Clone, Copy, PartialEq)]
enum Label {
    Outside,
    Inside,
    /// Inside, winding number other than 0 and 1 (see `VoxelMap::overlap_bricks`).
    Overlap,
}

/// Classifies the free cells of the dirty bricks: groups of face-adjacent free cells,
/// grown in brick order as bit masks (as the build's flood grows them), each labelled
/// from a clean free cell next to it or by its winding number.
fn classify(
    map: &VoxelMap,
    bricks: &[u32],
    old: &VoxelMap,
    surface: &Surface,
    dirty: &[usize],
    slot_of: &[u32],
) -> Classes {
    let (dims, bdims) = (map.grid.dims(), map.brick_dims);
    let mut groups = Groups {
        available: dirty
            .iter()
            .map(|&b| free_cells(bricks, &map.surface_bits, b, bdims, dims))
            .collect(),
        neighbours: dirty
            .iter()
            .map(|&b| {
                let bc = brick_coords(b, bdims);
                FACES.map(|(axis, up)| {
                    step(bc, axis, up, bdims).map(|n| brick_of(n.map(|x| x << BRICK_BITS), bdims))
                })
            })
            .collect(),
        reached: vec![[0; MASK_WORDS]; dirty.len()],
        queued: vec![false; dirty.len()],
        work: Vec::new(),
        touched: Vec::new(),
    };
    let mut classes = Classes {
        inside: vec![[0; MASK_WORDS]; dirty.len()],
        overlap: vec![[0; MASK_WORDS]; dirty.len()],
    };
    for (s, &b) in dirty.iter().enumerate() {
        while let Some(seed) = first_cell(&groups.available[s]) {
            groups.grow(s, seed, slot_of);
            let label = groups.clean_label(old, slot_of).unwrap_or_else(|| {
                let c = cell_in_brick(brick_coords(b, bdims), seed);
                let winding = winding_number(surface, map.grid.cell_centre(c)).round();
                if winding == 0.0 {
                    Label::Outside
                } else if winding == 1.0 {
                    Label::Inside
                } else {
                    Label::Overlap
                }
            });
            groups.take(label, &mut classes);
        }
    }
    classes
}

/// The free (non-surface, in-grid) cells of brick `b` of a map with top-level entries
/// `entries` and surface masks `bits`.
fn free_cells(
    entries: &[u32],
    bits: &[BrickBits],
    b: usize,
    bdims: [u32; 3],
    dims: [u32; 3],
) -> BrickBits {
    let in_grid = in_grid_bits(brick_coords(b, bdims), dims);
    let surface = entries
        .get(b)
        .filter(|&&e| e & UNIFORM == 0)
        .and_then(|&e| bits.get(e as usize))
        .copied()
        .unwrap_or_default();
    std::array::from_fn(|z| in_grid[z] & !surface[z])
}

/// The groups of free cells of the dirty bricks (by slot), grown one at a time.
struct Groups {
    /// Free cells not yet in a group.
    available: Vec<BrickBits>,
    /// Each slot's face neighbours (top-level indices), in the order of `FACES`.
    neighbours: Vec<[Option<usize>; 6]>,
    /// The cells of the current group.
    reached: Vec<BrickBits>,
    queued: Vec<bool>,
    work: Vec<usize>,
    /// The slots the current group reached.
    touched: Vec<usize>,
}

impl Groups {
    /// The dirty neighbour of slot `x` across face `face`.
    fn dirty_neighbour(&self, x: usize, face: usize, slot_of: &[u32]) -> Option<usize> {
        let ns = *slot_of.get(self.neighbours[x][face]?)?;
        (ns != CLEAN).then_some(ns as usize)
    }

    /// Grows the group of cell `seed` of slot `s` through face-adjacent available cells
    /// of the dirty bricks.
    fn grow(&mut self, s: usize, seed: usize, slot_of: &[u32]) {
        self.reached[s][seed >> 6] |= 1 << (seed & 63);
        self.touched.push(s);
        self.queued[s] = true;
        self.work.push(s);
        let mut first = true;
        while let Some(x) = self.work.pop() {
            self.queued[x] = false;
            let mut seeds = self.reached[x];
            for face in 0..FACES.len() {
                if let Some(ns) = self.dirty_neighbour(x, face, slot_of) {
                    add_face_seeds(&mut seeds, &self.reached[ns], face);
                }
            }
            let grown = flood_brick(seeds, &self.available[x]);
            if grown == self.reached[x] && !first {
                continue;
            }
            first = false;
            if self.reached[x] == [0; MASK_WORDS] {
                self.touched.push(x);
            }
            self.reached[x] = grown;
            for face in 0..FACES.len() {
                if let Some(ns) = self.dirty_neighbour(x, face, slot_of)
                    && touches_face(&grown, face)
                    && !self.queued[ns]
                {
                    self.queued[ns] = true;
                    self.work.push(ns);
                }
            }
        }
    }

    /// The old label of a clean free cell next to the current group, if any.
    fn clean_label(&self, old: &VoxelMap, slot_of: &[u32]) -> Option<Label> {
        let (dims, bdims) = (old.grid.dims(), old.brick_dims);
        for &x in &self.touched {
            for (face, nb) in self.neighbours[x].iter().enumerate() {
                let Some(nb) = *nb else { continue };
                if slot_of.get(nb) != Some(&CLEAN) {
                    continue;
                }
                let mut next_to = [0; MASK_WORDS];
                add_face_seeds(&mut next_to, &self.reached[x], face ^ 1);
                let free = free_cells(&old.bricks, &old.surface_bits, nb, bdims, dims);
                for z in 0..MASK_WORDS {
                    next_to[z] &= free[z];
                }
                if let Some(l) = first_cell(&next_to)
                    && let Some(label) = old_label(old, cell_in_brick(brick_coords(nb, bdims), l))
                {
                    return Some(label);
                }
            }
        }
        None
    }

    /// Ends the current group: its cells leave the available ones and get `label`.
    fn take(&mut self, label: Label, classes: &mut Classes) {
        for x in self.touched.drain(..) {
            let cells = std::mem::take(&mut self.reached[x]);
            for (z, &w) in cells.iter().enumerate() {
                self.available[x][z] &= !w;
                if label != Label::Outside {
                    classes.inside[x][z] |= w;
                }
                if label == Label::Overlap {
                    classes.overlap[x][z] |= w;
                }
            }
        }
    }
}

/// The label of cell `c` in the old map: `None` for a surface cell.
fn old_label(old: &VoxelMap, c: [u32; 3]) -> Option<Label> {
    match old.state(c) {
        CellState::Surface => None,
        CellState::Outside => Some(Label::Outside),
        CellState::Inside if old.is_overlap(c) => Some(Label::Overlap),
        CellState::Inside => Some(Label::Inside),
    }
}
