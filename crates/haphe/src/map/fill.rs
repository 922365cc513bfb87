//! Classifying the non-surface cells: the flood fill from the padding (outside versus
//! inside) and the clearance (Chebyshev distance to the nearest surface cell).
//!
//! Both work on the sparse layout: a brick without surface cells is one node of the flood
//! fill, and the clearance is computed only in bricks near the surface, by dilating bit
//! masks of the surface cells one cell at a time.

use rayon::prelude::*;

use super::bricks::{
    BRICK_BITS, BRICK_SIDE, BrickBits, MASK_WORDS, NIBBLE_BYTES, UNIFORM, VoxelMap, brick_coords,
    brick_of, entry_state, graded_entry, in_grid_bits, uniform_entry,
};
use super::{CellState, MAX_CLEARANCE};

/// Marks outside every non-surface cell connected to the padding through face-adjacent
/// non-surface cells, and inside the others. Expects uniform bricks inside on entry (a
/// solid's [`assemble`](super::build) output).
///
/// Works brick by brick: a uniform brick (no surface cell, so all its cells connected) is
/// one node; in a detailed brick the outside cells are a bit mask, grown by dilation
/// inside the brick's free cells from the outside cells of its face neighbours. A brick
/// whose mask grows sends its neighbours back to the work list, until nothing changes.
///
/// Deterministic: the result is the set of reachable cells, whatever the order of work.
/// `O(uniform bricks + detailed bricks × passes)`, sequential.
pub(crate) fn flood_fill(map: &mut VoxelMap) {
    let bdims = map.brick_dims;
    let dims = map.grid.dims();
    let detailed_count = map.detailed_count();
    // Free (non-surface, in-grid) cells of each detailed brick, in brick order.
    let mut free: Vec<BrickBits> = vec![[0; MASK_WORDS]; detailed_count];
    for (b, &entry) in map.bricks.iter().enumerate() {
        if entry & UNIFORM == 0
            && let (Some(f), Some(surface)) = (
                free.get_mut(entry as usize),
                map.surface_bits.get(entry as usize),
            )
        {
            let in_grid = in_grid_bits(brick_coords(b, bdims), dims);
            for z in 0..MASK_WORDS {
                f[z] = in_grid[z] & !surface[z];
            }
        }
    }
    let mut outside: Vec<BrickBits> = vec![[0; MASK_WORDS]; detailed_count];
    let mut queued = vec![false; map.bricks.len()];
    let mut work: Vec<usize> = Vec::new();

    // The padding is one connected shell of non-surface cells: cell [0, 0, 0] seeds it.
    let entry = map.bricks[0];
    if entry & UNIFORM != 0 {
        map.bricks[0] = uniform_entry(CellState::Outside, 0);
    } else if let Some(bits) = outside.get_mut(entry as usize) {
        bits[0] |= 1;
    }
    queued[0] = true;
    work.push(0);

    while let Some(b) = work.pop() {
        queued[b] = false;
        let bc = brick_coords(b, bdims);
        let entry = map.bricks[b];
        let neighbours = FACES.map(|(axis, up)| {
            step(bc, axis, up, bdims).map(|n| brick_of(n.map(|x| x << BRICK_BITS), bdims))
        });
        if entry & UNIFORM != 0 {
            // Reached as a whole: every neighbour can gain from it.
            for nb in neighbours.into_iter().flatten() {
                reach_brick(map, &mut queued, &mut work, nb);
            }
            continue;
        }
        let d = entry as usize;
        let mut seeds = outside[d];
        for (face, nb) in neighbours.iter().enumerate() {
            let Some(nb) = *nb else { continue };
            let n_entry = map.bricks[nb];
            let layer = if n_entry & UNIFORM != 0 {
                if entry_state(n_entry) == CellState::Outside {
                    FULL
                } else {
                    continue;
                }
            } else {
                outside[n_entry as usize]
            };
            add_face_seeds(&mut seeds, &layer, face);
        }
        let grown = flood_brick(seeds, &free[d]);
        if grown == outside[d] {
            continue;
        }
        outside[d] = grown;
        for (face, nb) in neighbours.iter().enumerate() {
            let Some(nb) = *nb else { continue };
            if touches_face(&grown, face) {
                reach_brick(map, &mut queued, &mut work, nb);
            }
        }
    }

    for ((inside, free), outside) in map.inside_bits.iter_mut().zip(&free).zip(&outside) {
        for z in 0..MASK_WORDS {
            inside[z] = free[z] & !outside[z];
        }
    }
}

/// A brick whose face neighbour has outside cells next to it: a uniform inside brick
/// becomes outside; either kind goes on the work list (once).
fn reach_brick(map: &mut VoxelMap, queued: &mut [bool], work: &mut Vec<usize>, b: usize) {
    let entry = map.bricks[b];
    if entry & UNIFORM != 0 {
        if entry_state(entry) != CellState::Inside {
            return;
        }
        map.bricks[b] = uniform_entry(CellState::Outside, 0);
    }
    if !queued[b] {
        queued[b] = true;
        work.push(b);
    }
}

/// Every bit set.
const FULL: BrickBits = [u64::MAX; MASK_WORDS];

/// Rows `y = 0` and `y = 7` of a word.
const ROW_Y0: u64 = 0xff;
const ROW_Y7: u64 = 0xff << 56;

/// Adds to `seeds` the cells next to the outside cells `layer` of the neighbour across
/// face `face` (index into [`FACES`]: −x, +x, −y, +y, −z, +z).
fn add_face_seeds(seeds: &mut BrickBits, layer: &BrickBits, face: usize) {
    let last = BRICK_SIDE as usize - 1;
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
fn touches_face(bits: &BrickBits, face: usize) -> bool {
    let last = BRICK_SIDE as usize - 1;
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
fn flood_brick(seeds: BrickBits, free: &BrickBits) -> BrickBits {
    let last = BRICK_SIDE as usize - 1;
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
const FACES: [(usize, bool); 6] = [
    (0, false),
    (0, true),
    (1, false),
    (1, true),
    (2, false),
    (2, true),
];

/// The neighbour of `c` one step along `axis`, if inside the grid of `dims`.
#[inline]
fn step(c: [u32; 3], axis: usize, up: bool, dims: [u32; 3]) -> Option<[u32; 3]> {
    let mut n = c;
    if up {
        n[axis] = c[axis].checked_add(1).filter(|&x| x < dims[axis])?;
    } else {
        n[axis] = c[axis].checked_sub(1)?;
    }
    Some(n)
}

/// Bits at `x = 0` and at `x = 7` of every row.
const COLUMN_X0: u64 = 0x0101_0101_0101_0101;
const COLUMN_X7: u64 = 0x8080_8080_8080_8080;

/// No neighbour slot.
const NO_SLOT: u32 = u32::MAX;

/// What a brick of the clearance work set stores its clearances in.
#[derive(Clone, Copy)]
enum Target {
    /// Detailed brick `d`: its nibbles.
    Detailed(usize),
    /// Graded brick `g` (uniform, touching a detailed brick): nibbles after the detailed
    /// bricks'.
    Graded(usize),
    /// Other uniform brick: only the smallest clearance.
    Uniform,
}

/// Sets the clearance of every non-surface cell, and makes graded the uniform bricks
/// that touch a detailed brick.
///
/// Bricks within `⌈(MAX_CLEARANCE − 1) / 8⌉` bricks of a detailed brick form the work set.
/// Starting from the surface cells, the set of cells within Chebyshev distance `k` is the
/// previous one dilated by one cell along x, then y, then z (separable); a cell first
/// reached at step `k` has clearance `k`. Cells not reached after `MAX_CLEARANCE − 1`
/// steps get `MAX_CLEARANCE`, as do bricks outside the work set (farther than
/// `MAX_CLEARANCE` cells from any surface cell). Detailed and graded bricks keep every
/// cell's clearance; other uniform bricks the smallest of their cells'.
///
/// Deterministic; parallel over bricks within each step.
pub(crate) fn compute_clearance(map: &mut VoxelMap) {
    let bdims = map.brick_dims;
    let reach = i64::from((MAX_CLEARANCE.max(1) - 1).div_ceil(BRICK_SIDE as u8)).max(1);
    // The work set, in brick order; `TOUCHING` marks bricks next to a detailed brick.
    const TOUCHING: u32 = 1;
    const NEAR: u32 = 2;
    let mut mark = vec![0u32; map.bricks.len()];
    for (b, &entry) in map.bricks.iter().enumerate() {
        if entry & UNIFORM != 0 {
            continue;
        }
        let bc = brick_coords(b, bdims).map(i64::from);
        for dz in -reach..=reach {
            for dy in -reach..=reach {
                for dx in -reach..=reach {
                    let n = [bc[0] + dx, bc[1] + dy, bc[2] + dz];
                    if (0..3).all(|a| n[a] >= 0 && n[a] < i64::from(bdims[a])) {
                        let nb = brick_of(n.map(|x| (x as u32) << BRICK_BITS), bdims);
                        let touching = dx.abs().max(dy.abs()).max(dz.abs()) <= 1;
                        mark[nb] |= if touching { TOUCHING | NEAR } else { NEAR };
                    }
                }
            }
        }
    }
    let mut slot_of = vec![NO_SLOT; map.bricks.len()];
    let mut slots: Vec<usize> = Vec::new();
    let mut targets: Vec<Target> = Vec::new();
    let mut graded_count = 0usize;
    for (b, &m) in mark.iter().enumerate() {
        if m == 0 {
            continue;
        }
        slot_of[b] = slots.len() as u32;
        slots.push(b);
        let entry = map.bricks[b];
        targets.push(if entry & UNIFORM == 0 {
            Target::Detailed(entry as usize)
        } else if m & TOUCHING != 0 {
            graded_count += 1;
            Target::Graded(graded_count - 1)
        } else {
            Target::Uniform
        });
    }
    drop(mark);
    let neighbours: Vec<[u32; 6]> = slots
        .par_iter()
        .map(|&b| {
            let bc = brick_coords(b, bdims);
            FACES.map(|(axis, up)| {
                step(bc, axis, up, bdims)
                    .map(|n| slot_of[brick_of(n.map(|x| x << BRICK_BITS), bdims)])
                    .unwrap_or(NO_SLOT)
            })
        })
        .collect();

    // D_0: the surface cells. A cell's clearance is the number of steps k in
    // 0..MAX_CLEARANCE with the cell not yet in D_k: counted per cell, in four bit planes,
    // for detailed and graded bricks; for the other bricks only their smallest clearance
    // is kept, the number of steps with the whole brick still outside D_k.
    let mut current: Vec<BrickBits> = vec![[0; MASK_WORDS]; slots.len()];
    for (s, target) in targets.iter().enumerate() {
        if let Target::Detailed(d) = *target
            && let Some(surface) = map.surface_bits.get(d)
        {
            current[s] = *surface;
        }
    }
    let counted: Vec<usize> = (0..slots.len())
        .filter(|&s| !matches!(targets[s], Target::Uniform))
        .collect();
    let mut counts: Vec<Counter> = counted
        .par_iter()
        .map(|&s| {
            let mut counter = Counter::default();
            counter.add_missing(&current[s]);
            counter
        })
        .collect();
    let mut current = Layer::new(current);
    let mut empty_steps: Vec<u8> = current
        .occupancy
        .iter()
        .map(|&o| u8::from(o == Occupancy::Empty))
        .collect();
    let mut along_x = current.clone();
    let mut along_y = current.clone();
    let mut next = current.clone();
    for _ in 1..MAX_CLEARANCE {
        dilate(&current, &mut along_x, &neighbours, 0);
        dilate(&along_x, &mut along_y, &neighbours, 1);
        dilate(&along_y, &mut next, &neighbours, 2);
        counts
            .par_iter_mut()
            .zip(counted.par_iter())
            .for_each(|(counter, &s)| {
                if next.occupancy[s] != Occupancy::Full {
                    counter.add_missing(&next.bits[s]);
                }
            });
        empty_steps
            .par_iter_mut()
            .zip(next.occupancy.par_iter())
            .for_each(|(steps, &o)| *steps += u8::from(o == Occupancy::Empty));
        std::mem::swap(&mut current, &mut next);
    }
    drop((current, next, along_x, along_y));

    let detailed_count = map.detailed_count();
    map.clearances = vec![0; (detailed_count + graded_count) * NIBBLE_BYTES];
    for (&s, counter) in counted.iter().zip(&counts) {
        let brick = match targets[s] {
            Target::Detailed(d) => d,
            Target::Graded(g) => detailed_count + g,
            Target::Uniform => continue,
        };
        if let Some(bytes) = map
            .clearances
            .get_mut(brick * NIBBLE_BYTES..(brick + 1) * NIBBLE_BYTES)
        {
            counter.write_nibbles(bytes);
        }
    }
    for (b, entry) in map.bricks.iter_mut().enumerate() {
        if *entry & UNIFORM == 0 {
            continue;
        }
        let state = entry_state(*entry);
        let slot = slot_of[b] as usize;
        *entry = match (targets.get(slot), empty_steps.get(slot)) {
            (Some(Target::Graded(g)), _) => graded_entry(state, (detailed_count + g) as u32),
            (Some(_), Some(&steps)) => uniform_entry(state, steps.min(MAX_CLEARANCE)),
            _ => uniform_entry(state, MAX_CLEARANCE),
        };
    }
}

/// A 4-bit counter per cell of a brick, bit-sliced: bit `p` of every cell's count lives
/// in plane `p`, so adding one to a set of cells costs a few word operations.
#[derive(Clone, Copy, Default)]
struct Counter {
    planes: [BrickBits; 4],
}

impl Counter {
    /// Adds one to every cell not in `bits` (counts stay below 16: at most
    /// [`MAX_CLEARANCE`] additions).
    #[inline]
    fn add_missing(&mut self, bits: &BrickBits) {
        for z in 0..MASK_WORDS {
            let mut carry = !bits[z];
            for plane in &mut self.planes {
                let sum = plane[z] ^ carry;
                carry &= plane[z];
                plane[z] = sum;
            }
        }
    }

    /// The counts as nibbles (cell `l` in byte `l / 2`, low nibble first).
    fn write_nibbles(&self, bytes: &mut [u8]) {
        for (group, out) in bytes.chunks_exact_mut(4).enumerate() {
            // Eight cells: `group * 8 ..`, the byte `group % 8` of word `group / 8`.
            let (z, shift) = (group / 8, 8 * (group % 8));
            let mut nibbles = 0u32;
            for (p, plane) in self.planes.iter().enumerate() {
                nibbles |= SPREAD_NIBBLES[((plane[z] >> shift) & 0xff) as usize] << p;
            }
            out.copy_from_slice(&nibbles.to_le_bytes());
        }
    }
}

/// `SPREAD_NIBBLES[x]` has bit `i` of `x` at bit `4·i`.
const SPREAD_NIBBLES: [u32; 256] = {
    let mut table = [0u32; 256];
    let mut x = 0;
    while x < 256 {
        let mut i = 0;
        while i < 8 {
            if x >> i & 1 != 0 {
                table[x] |= 1 << (4 * i);
            }
            i += 1;
        }
        x += 1;
    }
    table
};

/// How much of a brick's bit mask is set, so that dilation can skip bricks whose result
/// is known.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Occupancy {
    Empty,
    Full,
    Mixed,
}

impl Occupancy {
    fn of(bits: &BrickBits) -> Occupancy {
        if bits.iter().all(|&w| w == 0) {
            Occupancy::Empty
        } else if bits.iter().all(|&w| w == u64::MAX) {
            Occupancy::Full
        } else {
            Occupancy::Mixed
        }
    }
}

/// The bit masks of the work set, with each brick's occupancy.
#[derive(Clone)]
struct Layer {
    bits: Vec<BrickBits>,
    occupancy: Vec<Occupancy>,
}

impl Layer {
    fn new(bits: Vec<BrickBits>) -> Layer {
        let occupancy = bits.par_iter().map(Occupancy::of).collect();
        Layer { bits, occupancy }
    }
}

/// One dilation step along `axis` of every brick of the work set: a bit is set when it or
/// a face neighbour along `axis` (possibly in the next brick) is set in `input`. A full
/// brick stays full, and an empty one with empty neighbours along `axis` stays empty,
/// without computing.
fn dilate(input: &Layer, output: &mut Layer, neighbours: &[[u32; 6]], axis: usize) {
    let get = |slot: u32| input.bits.get(slot as usize);
    let occupancy = |slot: u32| {
        input
            .occupancy
            .get(slot as usize)
            .copied()
            .unwrap_or(Occupancy::Empty)
    };
    output
        .bits
        .par_iter_mut()
        .zip(output.occupancy.par_iter_mut())
        .zip(input.bits.par_iter().zip(input.occupancy.par_iter()))
        .zip(neighbours.par_iter())
        .for_each(|(((out, out_occupancy), (bits, &own)), nb)| {
            let (below, above) = (nb[2 * axis], nb[2 * axis + 1]);
            if own == Occupancy::Full {
                *out = [u64::MAX; MASK_WORDS];
                *out_occupancy = Occupancy::Full;
                return;
            }
            if own == Occupancy::Empty
                && occupancy(below) == Occupancy::Empty
                && occupancy(above) == Occupancy::Empty
            {
                *out = [0; MASK_WORDS];
                *out_occupancy = Occupancy::Empty;
                return;
            }
            let (below, above) = (get(below), get(above));
            match axis {
                0 => {
                    for z in 0..MASK_WORDS {
                        let w = bits[z];
                        let mut o = w | ((w << 1) & !COLUMN_X0) | ((w >> 1) & !COLUMN_X7);
                        if let Some(n) = below {
                            o |= (n[z] & COLUMN_X7) >> 7;
                        }
                        if let Some(n) = above {
                            o |= (n[z] & COLUMN_X0) << 7;
                        }
                        out[z] = o;
                    }
                }
                1 => {
                    for z in 0..MASK_WORDS {
                        let w = bits[z];
                        let mut o = w | (w << 8) | (w >> 8);
                        if let Some(n) = below {
                            o |= n[z] >> 56;
                        }
                        if let Some(n) = above {
                            o |= (n[z] & 0xff) << 56;
                        }
                        out[z] = o;
                    }
                }
                _ => {
                    let last = MASK_WORDS - 1;
                    for z in 0..=last {
                        let mut o = bits[z];
                        o |= if z > 0 {
                            bits[z - 1]
                        } else {
                            below.map_or(0, |n| n[last])
                        };
                        o |= if z < last {
                            bits[z + 1]
                        } else {
                            above.map_or(0, |n| n[0])
                        };
                        out[z] = o;
                    }
                }
            }
            *out_occupancy = Occupancy::of(out);
        });
}
