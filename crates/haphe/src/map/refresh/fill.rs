//! Inside and outside after a deformation, decided again only where a moved triangle may
//! have swept.
//!
//! A point's winding number changes only when the surface passes through it: a moved
//! triangle, on its way from its old corners to its new ones, stays in the box of both.
//! A cell of no such box keeps its winding number, so its state (inside, outside, in an
//! overlap) is the old map's. The cells of the bricks that meet a box (the dirty bricks)
//! are classified again as the build does: face-adjacent non-surface cells share their
//! winding number, so each connected group of them takes the state of a clean
//! non-surface cell next to it, or, with none, the winding number at its first cell.

use super::super::CellState;
use super::super::fill::{FACES, step};
use super::super::voxel_map::{
    BRICK_CELLS, BrickBits, MASK_WORDS, UNIFORM, VoxelMap, brick_coords, brick_of, cell_in_brick,
    entry_state, has, in_grid_bits, local_of, uniform_entry,
};
use crate::mesh::{Surface, winding_number};

/// A free cell not yet classified.
const UNKNOWN: u8 = 0;
/// A surface cell, or one beyond the grid.
const BLOCKED: u8 = 1;
/// A free cell on the work list of its group.
const QUEUED: u8 = 2;
/// Outside (winding number 0).
const OUTSIDE: u8 = 3;
/// Inside, winding number 1.
const INSIDE: u8 = 4;
/// Inside, winding number other than 0 and 1 (see `VoxelMap::overlap_bricks`).
const OVERLAP: u8 = 5;

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
    let labels = classify(map, &bricks, old, surface, dirty, &slot_of);
    let mut overlap: Vec<(u32, BrickBits)> = Vec::new();
    for (s, &b) in dirty.iter().enumerate() {
        let label = &labels[s];
        let pick = |wanted: &[u8]| -> BrickBits {
            let mut bits = [0; MASK_WORDS];
            for (l, v) in label.iter().enumerate() {
                if wanted.contains(v) {
                    bits[l >> 6] |= 1 << (l & 63);
                }
            }
            bits
        };
        let entry = bricks[b];
        if entry & UNIFORM != 0 {
            // No surface cell: all its cells form one group.
            let first = label.iter().copied().find(|&v| v != BLOCKED);
            let state = if first == Some(OUTSIDE) {
                CellState::Outside
            } else {
                CellState::Inside
            };
            bricks[b] = uniform_entry(state, 0);
            if first == Some(OVERLAP) {
                let bdims = map.brick_dims;
                overlap.push((
                    b as u32,
                    in_grid_bits(brick_coords(b, bdims), map.grid.dims()),
                ));
            }
        } else {
            if let Some(inside) = inside_bits.get_mut(entry as usize) {
                *inside = pick(&[INSIDE, OVERLAP]);
            }
            let bits = pick(&[OVERLAP]);
            if bits != [0; MASK_WORDS] {
                overlap.push((b as u32, bits));
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

/// The label of every cell of the dirty bricks: groups of face-adjacent free cells,
/// found in brick order, each labelled from a clean neighbour or its winding number.
fn classify(
    map: &VoxelMap,
    bricks: &[u32],
    old: &VoxelMap,
    surface: &Surface,
    dirty: &[usize],
    slot_of: &[u32],
) -> Vec<[u8; BRICK_CELLS]> {
    let (dims, bdims) = (map.grid.dims(), map.brick_dims);
    let mut labels: Vec<[u8; BRICK_CELLS]> = dirty
        .iter()
        .map(|&b| {
            let in_grid = in_grid_bits(brick_coords(b, bdims), dims);
            let entry = bricks[b];
            let surface_bits = if entry & UNIFORM != 0 {
                [0; MASK_WORDS]
            } else {
                map.surface_bits
                    .get(entry as usize)
                    .copied()
                    .unwrap_or_default()
            };
            std::array::from_fn(|l| {
                if has(&in_grid, l) && !has(&surface_bits, l) {
                    UNKNOWN
                } else {
                    BLOCKED
                }
            })
        })
        .collect();
    let mut work: Vec<(usize, usize)> = Vec::new();
    let mut group: Vec<(usize, usize)> = Vec::new();
    for s in 0..dirty.len() {
        for local in 0..BRICK_CELLS {
            if labels[s][local] != UNKNOWN {
                continue;
            }
            labels[s][local] = QUEUED;
            work.push((s, local));
            group.clear();
            let mut found: Option<u8> = None;
            while let Some((s, l)) = work.pop() {
                group.push((s, l));
                let c = cell_in_brick(brick_coords(dirty[s], bdims), l);
                for (axis, up) in FACES {
                    let Some(n) = step(c, axis, up, dims) else {
                        continue;
                    };
                    let (nb, nl) = (brick_of(n, bdims), local_of(n));
                    match slot_of.get(nb).copied() {
                        Some(CLEAN) => {
                            if found.is_none() {
                                found = old_label(old, n);
                            }
                        }
                        Some(ns) => {
                            let v = &mut labels[ns as usize][nl];
                            if *v == UNKNOWN {
                                *v = QUEUED;
                                work.push((ns as usize, nl));
                            }
                        }
                        None => {}
                    }
                }
            }
            let label = found.unwrap_or_else(|| {
                let c = cell_in_brick(brick_coords(dirty[s], bdims), local);
                let winding = winding_number(surface, map.grid.cell_centre(c)).round();
                if winding == 0.0 {
                    OUTSIDE
                } else if winding == 1.0 {
                    INSIDE
                } else {
                    OVERLAP
                }
            });
            for &(s, l) in &group {
                labels[s][l] = label;
            }
        }
    }
    labels
}

/// The label of cell `c` in the old map: `None` for a surface cell.
fn old_label(old: &VoxelMap, c: [u32; 3]) -> Option<u8> {
    match old.state(c) {
        CellState::Surface => None,
        CellState::Outside => Some(OUTSIDE),
        CellState::Inside if old.is_overlap(c) => Some(OVERLAP),
        CellState::Inside => Some(INSIDE),
    }
}
