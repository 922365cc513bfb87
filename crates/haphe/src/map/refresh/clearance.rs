//! Clearances after a deformation, counted again only near the cells whose surface state
//! changed.
//!
//! A cell's clearance is its Chebyshev distance to the nearest surface cell, capped at
//! [`MAX_CLEARANCE`]: it depends only on the surface cells within `MAX_CLEARANCE − 1`
//! cells, so only in bricks within two bricks of one whose surface cells changed (the
//! dirty bricks). Their clearances are counted by the build's dilation over them and the
//! bricks within two bricks of them (all the cells that can be nearest); the others are
//! copied. Which bricks are detailed, graded or near, and the reach of the bricks
//! farther away, come from the bricks' distances, derived again over the whole grid.

use super::super::MAX_CLEARANCE;
use super::super::clearance::{
    NO_SLOT, Target, brick_distances, count_steps, neighbour_slots, uniform_clearance,
};
use super::super::voxel_map::{
    BRICK_BITS, BrickBits, GRADED, MASK_WORDS, NIBBLE_BYTES, UNIFORM, UNIFORM_PAYLOAD, VoxelMap,
    brick_coords, brick_of,
};

/// How far, in bricks, a changed surface cell changes clearances: `⌈(MAX_CLEARANCE −
/// 1) / 8⌉`.
const REACH: i64 = ((MAX_CLEARANCE as i64 - 1) + 7) >> BRICK_BITS;

/// Marks of a brick: its clearances are counted again, or it takes part in the count.
const DIRTY: u8 = 1;
const SLOT: u8 = 2;

/// Sets the clearances of `map` (the map after a deformation, its states classified),
/// copied from `old` (the map before) but in the bricks near `changed` (the top-level
/// bricks whose surface cells changed, increasing).
pub(super) fn reclear(map: &mut VoxelMap, old: &VoxelMap, changed: &[usize]) {
    let bdims = map.brick_dims;
    let distances = brick_distances(&map.bricks, bdims);
    let mark = marks(old, changed, &distances, bdims);
    let slots: Vec<usize> = (0..mark.len()).filter(|&b| mark[b] & SLOT != 0).collect();
    let mut slot_of = vec![NO_SLOT; map.bricks.len()];
    for (s, &b) in slots.iter().enumerate() {
        slot_of[b] = s as u32;
    }
    let neighbours = neighbour_slots(&slots, &slot_of, bdims);
    let initial: Vec<BrickBits> = slots
        .iter()
        .map(|&b| {
            let entry = map.bricks[b];
            if entry & UNIFORM != 0 {
                [0; MASK_WORDS]
            } else {
                map.surface_bits
                    .get(entry as usize)
                    .copied()
                    .unwrap_or_default()
            }
        })
        .collect();
    let counted: Vec<usize> = (0..slots.len())
        .filter(|&s| mark[slots[s]] & DIRTY != 0 && distances[slots[s]] <= 1)
        .collect();
    let steps = count_steps(initial, counted, &neighbours);
    let mut count_of = vec![NO_SLOT; slots.len()];
    for (i, &s) in steps.counted.iter().enumerate() {
        count_of[s] = i as u32;
    }

    let detailed_count = map.detailed_count();
    let graded_count = (0..map.bricks.len())
        .filter(|&b| distances[b] == 1 && map.bricks[b] & UNIFORM != 0)
        .count();
    let mut clearances = vec![0u8; (detailed_count + graded_count) * NIBBLE_BYTES];
    let mut bricks = map.bricks.take_vec();
    let mut graded = 0usize;
    for (b, entry) in bricks.iter_mut().enumerate() {
        let distance = distances[b];
        let slot = slot_of[b] as usize;
        let index = if *entry & UNIFORM == 0 {
            Some(*entry as usize)
        } else if distance == 1 {
            graded += 1;
            Some(detailed_count + graded - 1)
        } else {
            None
        };
        if let Some(index) = index {
            let Some(bytes) = clearances.get_mut(index * NIBBLE_BYTES..(index + 1) * NIBBLE_BYTES)
            else {
                continue;
            };
            if mark[b] & DIRTY != 0 {
                if let Some(counter) = count_of
                    .get(slot)
                    .and_then(|&i| steps.counts.get(i as usize))
                {
                    counter.write_nibbles(bytes);
                }
            } else if let Some(before) = old_nibbles(old, b) {
                bytes.copy_from_slice(before);
            }
        }
        if *entry & UNIFORM == 0 {
            continue;
        }
        let old_reach;
        let (target, empty_steps) = match distance {
            1 => (Some(Target::Graded(graded - 1)), None),
            2 if mark[b] & DIRTY != 0 => (Some(Target::Uniform), steps.empty_steps.get(slot)),
            2 => {
                old_reach = old
                    .bricks
                    .get(b)
                    .map_or(0, |&e| (e & UNIFORM_PAYLOAD) as u8);
                (Some(Target::Uniform), Some(&old_reach))
            }
            _ => (None, None),
        };
        *entry = uniform_clearance(
            *entry,
            distance,
            target.as_ref(),
            empty_steps,
            detailed_count,
        );
    }
    map.bricks = bricks.into();
    map.clearances = clearances.into();
}

/// Each brick's marks: [`DIRTY`] within [`REACH`] bricks of a brick of `changed` (and
/// where the kind of the old brick is not the kind its `distances` give), [`SLOT`] within
/// [`REACH`] of a dirty brick.
fn marks(old: &VoxelMap, changed: &[usize], distances: &[u16], bdims: [u32; 3]) -> Vec<u8> {
    let mut mark = vec![0u8; distances.len()];
    for &b in changed {
        around(b, bdims, |n| {
            if distances[n] <= REACH as u16 {
                mark[n] |= DIRTY;
            }
        });
    }
    // A brick whose kind changed is near a changed one; checked again all the same, so
    // that a clean brick always has its old clearances to copy.
    for (b, m) in mark.iter_mut().enumerate() {
        if *m & DIRTY == 0
            && distances[b] <= REACH as u16
            && !same_kind(old.bricks.get(b).copied(), distances[b])
        {
            *m |= DIRTY;
        }
    }
    let dirty: Vec<usize> = (0..mark.len()).filter(|&b| mark[b] & DIRTY != 0).collect();
    for &b in &dirty {
        around(b, bdims, |n| mark[n] |= SLOT);
    }
    mark
}

/// Calls `visit` with every brick within [`REACH`] bricks of brick `b` (itself
/// included).
fn around(b: usize, bdims: [u32; 3], mut visit: impl FnMut(usize)) {
    let bc = brick_coords(b, bdims).map(i64::from);
    for dz in -REACH..=REACH {
        for dy in -REACH..=REACH {
            for dx in -REACH..=REACH {
                let n = [bc[0] + dx, bc[1] + dy, bc[2] + dz];
                if (0..3).all(|a| n[a] >= 0 && n[a] < i64::from(bdims[a])) {
                    visit(brick_of(n.map(|x| (x as u32) << BRICK_BITS), bdims));
                }
            }
        }
    }
}

/// Whether the old entry of a brick at `distance` bricks from the nearest detailed brick
/// of the new map was of the kind that distance gives: detailed (0), graded (1) or
/// uniform with a clearance of at most [`MAX_CLEARANCE`] (2).
fn same_kind(old_entry: Option<u32>, distance: u16) -> bool {
    let Some(entry) = old_entry else {
        return false;
    };
    match distance {
        0 => entry & UNIFORM == 0,
        1 => entry & UNIFORM != 0 && entry & GRADED != 0,
        _ => {
            entry & UNIFORM != 0
                && entry & GRADED == 0
                && entry & UNIFORM_PAYLOAD <= u32::from(MAX_CLEARANCE)
        }
    }
}

/// The per-cell clearances of brick `b` in the old map (detailed or graded).
fn old_nibbles(old: &VoxelMap, b: usize) -> Option<&[u8]> {
    let entry = *old.bricks.get(b)?;
    let index = if entry & UNIFORM == 0 {
        entry as usize
    } else if entry & GRADED != 0 {
        (entry & UNIFORM_PAYLOAD) as usize
    } else {
        return None;
    };
    old.clearances
        .get(index * NIBBLE_BYTES..(index + 1) * NIBBLE_BYTES)
}
