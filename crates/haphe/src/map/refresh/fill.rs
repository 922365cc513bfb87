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
    let free = |bits: Option<&BrickBits>, b: usize| -> BrickBits {
        let in_grid = in_grid_bits(brick_coords(b, bdims), dims);
        let surface = bits.copied().unwrap_or_default();
        std::array::from_fn(|z| in_grid[z] & !surface[z])
    };
    let surface_of = |entries: &[u32], bits: &[BrickBits], b: usize| {
        entries
            .get(b)
            .filter(|&&e| e & UNIFORM == 0)
            .and_then(|&e| bits.get(e as usize))
            .copied()
    };
    let mut available: Vec<BrickBits> = dirty
        .iter()
        .map(|&b| free(surface_of(bricks, &map.surface_bits, b).as_ref(), b))
        .collect();
    // Each slot's face neighbours (top-level indices), in the order of `FACES`.
    let neighbours: Vec<[Option<usize>; 6]> = dirty
        .iter()
        .map(|&b| {
            let bc = brick_coords(b, bdims);
            FACES.map(|(axis, up)| {
                step(bc, axis, up, bdims).map(|n| brick_of(n.map(|x| x << BRICK_BITS), bdims))
            })
        })
        .collect();
    let n = dirty.len();
    let mut classes = Classes {
        inside: vec![[0; MASK_WORDS]; n],
        overlap: vec![[0; MASK_WORDS]; n],
    };
    let mut reached: Vec<BrickBits> = vec![[0; MASK_WORDS]; n];
    let mut queued = vec![false; n];
    let (mut work, mut touched): (Vec<usize>, Vec<usize>) = (Vec::new(), Vec::new());
    for s in 0..n {
        while let Some(seed) = first_cell(&available[s]) {
            reached[s][seed >> 6] |= 1 << (seed & 63);
            touched.push(s);
            queued[s] = true;
            work.push(s);
            let mut first = true;
            while let Some(x) = work.pop() {
                queued[x] = false;
                let mut seeds = reached[x];
                for (face, nb) in neighbours[x].iter().enumerate() {
                    if let Some(&ns) = nb.and_then(|nb| slot_of.get(nb))
                        && ns != CLEAN
                    {
                        add_face_seeds(&mut seeds, &reached[ns as usize], face);
                    }
                }
                let grown = flood_brick(seeds, &available[x]);
                if grown == reached[x] && !first {
                    continue;
                }
                first = false;
                if reached[x] == [0; MASK_WORDS] {
                    touched.push(x);
                }
                reached[x] = grown;
                for (face, nb) in neighbours[x].iter().enumerate() {
                    if let Some(&ns) = nb.and_then(|nb| slot_of.get(nb))
                        && ns != CLEAN
                        && touches_face(&grown, face)
                        && !queued[ns as usize]
                    {
                        queued[ns as usize] = true;
                        work.push(ns as usize);
                    }
                }
            }
            // A clean free cell next to the group gives its label.
            let mut found = None;
            'search: for &x in &touched {
                for (face, nb) in neighbours[x].iter().enumerate() {
                    let Some(nb) = *nb else { continue };
                    if slot_of.get(nb) != Some(&CLEAN) {
                        continue;
                    }
                    let mut next_to = [0; MASK_WORDS];
                    add_face_seeds(&mut next_to, &reached[x], face ^ 1);
                    let clean_free =
                        free(surface_of(&old.bricks, &old.surface_bits, nb).as_ref(), nb);
                    for z in 0..MASK_WORDS {
                        next_to[z] &= clean_free[z];
                    }
                    if let Some(l) = first_cell(&next_to) {
                        found = old_label(old, cell_in_brick(brick_coords(nb, bdims), l));
                        if found.is_some() {
                            break 'search;
                        }
                    }
                }
            }
            let label = found.unwrap_or_else(|| {
                let c = cell_in_brick(brick_coords(dirty[s], bdims), seed);
                let winding = winding_number(surface, map.grid.cell_centre(c)).round();
                if winding == 0.0 {
                    Label::Outside
                } else if winding == 1.0 {
                    Label::Inside
                } else {
                    Label::Overlap
                }
            });
            for x in touched.drain(..) {
                let cells = std::mem::take(&mut reached[x]);
                for z in 0..MASK_WORDS {
                    available[x][z] &= !cells[z];
                    if label != Label::Outside {
                        classes.inside[x][z] |= cells[z];
                    }
                    if label == Label::Overlap {
                        classes.overlap[x][z] |= cells[z];
                    }
                }
            }
        }
    }
    classes
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
