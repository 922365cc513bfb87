//! The clearance of every non-surface cell: its Chebyshev distance in cells to the nearest
//! surface cell, capped at [`MAX_CLEARANCE`], computed only in bricks near the surface by
//! dilating bit masks of the surface cells one cell at a time; and the reach of bricks
//! farther away, from their distance in bricks to the nearest brick with a surface cell.

use crate::par::*;

use super::MAX_CLEARANCE;
use super::fill::{COLUMN_X0, COLUMN_X7, FACES, step};
use super::voxel_map::{
    BRICK_BITS, BRICK_SIDE, BrickBits, MASK_WORDS, NIBBLE_BYTES, UNIFORM, VoxelMap, brick_coords,
    brick_of, entry_state, graded_entry, uniform_entry,
};

/// No neighbour slot.
pub(crate) const NO_SLOT: u32 = u32::MAX;

/// What a brick of the clearance work set stores its clearances in.
#[derive(Clone, Copy)]
pub(crate) enum Target {
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
/// steps get `MAX_CLEARANCE`. Detailed and graded bricks keep every cell's clearance;
/// other uniform bricks of the work set the smallest of their cells' as their reach.
/// Bricks outside it, `D ≥ 3` bricks from the nearest detailed brick, get the reach
/// `8 (D − 1) + 1` (see [`VoxelMap::reach`]).
///
/// Deterministic; parallel over bricks within each step.
pub(crate) fn compute_clearance(map: &mut VoxelMap) {
    let work = WorkSet::of(map);
    let initial = work
        .targets
        .iter()
        .map(|target| match *target {
            Target::Detailed(d) => map.surface_bits.get(d).copied().unwrap_or_default(),
            _ => [0; MASK_WORDS],
        })
        .collect();
    let counted: Vec<usize> = (0..work.slots.len())
        .filter(|&s| !matches!(work.targets[s], Target::Uniform))
        .collect();
    let steps = count_steps(initial, counted, &work.neighbours);
    store(map, &work, &steps);
}

/// Marks of the work set: next to a detailed brick (`TOUCHING`), or within reach of one.
const TOUCHING: u32 = 1;
const NEAR: u32 = 2;

/// The bricks whose cells' clearances are computed: those within
/// `⌈(MAX_CLEARANCE − 1) / 8⌉` bricks of a detailed brick, in brick order.
struct WorkSet {
    /// The slot of every brick in the set (`NO_SLOT` for a brick outside it).
    slot_of: Vec<u32>,
    /// The brick of every slot.
    slots: Vec<usize>,
    /// Where each slot's clearances go.
    targets: Vec<Target>,
    /// How many of the set's uniform bricks become graded.
    graded_count: usize,
    /// The slots of each slot's six face neighbours (`NO_SLOT` outside the set), in the
    /// order of [`FACES`].
    neighbours: Vec<[u32; 6]>,
}

impl WorkSet {
    fn of(map: &VoxelMap) -> WorkSet {
        let bdims = map.brick_dims;
        let mark = near_marks(map);
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
        let neighbours = neighbour_slots(&slots, &slot_of, bdims);
        WorkSet {
            slot_of,
            slots,
            targets,
            graded_count,
            neighbours,
        }
    }
}

/// The slots of each slot's six face neighbours (`NO_SLOT` outside the set), in the
/// order of [`FACES`], for bricks `slots` of a grid of `bdims` bricks whose slots are
/// `slot_of` (one per brick, `NO_SLOT` for a brick outside the set).
pub(crate) fn neighbour_slots(slots: &[usize], slot_of: &[u32], bdims: [u32; 3]) -> Vec<[u32; 6]> {
    slots
        .par_iter()
        .map(|&b| {
            let bc = brick_coords(b, bdims);
            FACES.map(|(axis, up)| {
                step(bc, axis, up, bdims)
                    .and_then(|n| slot_of.get(brick_of(n.map(|x| x << BRICK_BITS), bdims)))
                    .copied()
                    .unwrap_or(NO_SLOT)
            })
        })
        .collect()
}

/// Every brick's mark: `TOUCHING | NEAR` next to a detailed brick, `NEAR` within the work
/// set's reach of one, else 0.
fn near_marks(map: &VoxelMap) -> Vec<u32> {
    let bdims = map.brick_dims;
    let reach = (MAX_CLEARANCE.max(1) - 1).div_ceil(BRICK_SIDE as u8).max(1) as usize;
    let detailed: Vec<bool> = (0..map.bricks.len())
        .into_par_iter()
        .map(|b| map.bricks[b] & UNIFORM == 0)
        .collect();
    let near = box_dilate(&detailed, bdims, reach);
    let touching = box_dilate(&detailed, bdims, 1);
    near.par_iter()
        .zip(touching.par_iter())
        .map(|(&n, &t)| match (n, t) {
            (_, true) => TOUCHING | NEAR,
            (true, false) => NEAR,
            (false, false) => 0,
        })
        .collect()
}

/// The bricks of a grid of `dims` bricks within `radius` bricks along every axis of a
/// marked one (a box around each), one axis after the other: parallel over bricks.
fn box_dilate(marked: &[bool], dims: [u32; 3], radius: usize) -> Vec<bool> {
    let [nx, ny, _] = dims.map(|d| d as usize);
    let strides = [1, nx, nx * ny];
    let mut out = marked.to_vec();
    for (axis, &stride) in strides.iter().enumerate() {
        let len = dims[axis] as usize;
        let src = out;
        out = (0..src.len())
            .into_par_iter()
            .map(|i| {
                let at = (i / stride) % len;
                let first = i - at * stride;
                (at.saturating_sub(radius)..=(at + radius).min(len - 1))
                    .any(|k| src[first + k * stride])
            })
            .collect();
    }
    out
}

/// The dilation steps' counts: for the detailed and graded slots (`counted`), each cell's
/// number of steps outside `D_k` (`counts`); for every slot, the number of steps with the
/// whole brick outside (`empty_steps`).
pub(crate) struct Steps {
    pub(crate) counted: Vec<usize>,
    pub(crate) counts: Vec<Counter>,
    pub(crate) empty_steps: Vec<u8>,
}

/// Dilates the surface cells `MAX_CLEARANCE − 1` times over a set of bricks, counting:
/// `initial` holds each slot's surface cells, `counted` the slots whose cells are counted
/// one by one, `neighbours` each slot's face neighbours ([`neighbour_slots`]).
pub(crate) fn count_steps(
    initial: Vec<BrickBits>,
    counted: Vec<usize>,
    neighbours: &[[u32; 6]],
) -> Steps {
    // D_0: the surface cells. A cell's clearance is the number of steps k in
    // 0..MAX_CLEARANCE with the cell not yet in D_k: counted per cell, in four bit planes,
    // for detailed and graded bricks; for the other bricks only their smallest clearance
    // is kept, the number of steps with the whole brick still outside D_k.
    let current = initial;
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
        dilate(&current, &mut along_x, neighbours, 0);
        dilate(&along_x, &mut along_y, neighbours, 1);
        dilate(&along_y, &mut next, neighbours, 2);
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
    Steps {
        counted,
        counts,
        empty_steps,
    }
}

/// Stores the counted clearances in the map: the nibbles of detailed and graded bricks,
/// the reach of the other uniform bricks.
fn store(map: &mut VoxelMap, work: &WorkSet, steps: &Steps) {
    let (targets, slot_of) = (&work.targets, &work.slot_of);
    let bdims = map.brick_dims;
    let detailed_count = map.detailed_count();
    let mut clearances = vec![0; (detailed_count + work.graded_count) * NIBBLE_BYTES];
    for (&s, counter) in steps.counted.iter().zip(&steps.counts) {
        let brick = match targets[s] {
            Target::Detailed(d) => d,
            Target::Graded(g) => detailed_count + g,
            Target::Uniform => continue,
        };
        if let Some(bytes) = clearances.get_mut(brick * NIBBLE_BYTES..(brick + 1) * NIBBLE_BYTES) {
            counter.write_nibbles(bytes);
        }
    }
    map.clearances = clearances.into();
    let distances = brick_distances(&map.bricks, bdims);
    let mut bricks = map.bricks.take_vec();
    for (b, entry) in bricks.iter_mut().enumerate() {
        if *entry & UNIFORM != 0 {
            let slot = slot_of[b] as usize;
            *entry = uniform_clearance(
                *entry,
                distances[b],
                targets.get(slot),
                steps.empty_steps.get(slot),
                detailed_count,
            );
        }
    }
    map.bricks = bricks.into();
}

/// The entry of a uniform brick `distance` bricks from the nearest detailed one, with its
/// work-set target and steps (`None` outside the set).
pub(crate) fn uniform_clearance(
    entry: u32,
    distance: u16,
    target: Option<&Target>,
    empty_steps: Option<&u8>,
    detailed_count: usize,
) -> u32 {
    let state = entry_state(entry);
    // Cells of bricks `D` bricks apart are at least `8 (D − 1) + 1` cells apart.
    let far = (u32::from(distance).saturating_sub(1) << BRICK_BITS) + 1;
    match (target, empty_steps) {
        (Some(Target::Graded(g)), _) => graded_entry(state, (detailed_count + g) as u32),
        (Some(_), Some(&steps)) => uniform_entry(state, u32::from(steps.min(MAX_CLEARANCE))),
        _ => uniform_entry(state, far.max(u32::from(MAX_CLEARANCE))),
    }
}

/// The Chebyshev distance, in bricks, from every brick to the nearest detailed one (0 for
/// a detailed brick; `u16::MAX` when there is none).
pub(crate) fn brick_distances(bricks: &[u32], bdims: [u32; 3]) -> Vec<u16> {
    chebyshev_distances(bdims, |b| bricks[b] & UNIFORM == 0)
}

/// The Chebyshev distance, in boxes, from every box of a grid of `dims` boxes (index
/// `(z · dims[1] + y) · dims[0] + x`) to the nearest box that `marked` names (0 for a
/// marked box; `u16::MAX` when there is none), by the two raster passes of the chamfer
/// transform with unit weights over the 26 neighbours, which is exact for this distance.
/// Runs over a copy padded by one box, so the passes need no bounds checks.
pub(crate) fn chebyshev_distances(dims: [u32; 3], marked: impl Fn(usize) -> bool) -> Vec<u16> {
    let [bx, by, bz] = dims.map(|d| d as usize);
    let (px, py, pz) = (bx + 2, by + 2, bz + 2);
    let padded = |x: usize, y: usize, z: usize| (z * py + y) * px + x;
    let mut d = vec![u16::MAX; px * py * pz];
    for z in 0..bz {
        for y in 0..by {
            for x in 0..bx {
                if marked((z * by + y) * bx + x) {
                    d[padded(x + 1, y + 1, z + 1)] = 0;
                }
            }
        }
    }
    // The 13 neighbours before a brick in raster order; the other 13 are after it.
    let before: Vec<usize> = (-1isize..=1)
        .flat_map(|dz| (-1isize..=1).flat_map(move |dy| (-1isize..=1).map(move |dx| (dx, dy, dz))))
        .filter(|&(dx, dy, dz)| (dz, dy, dx) < (0, 0, 0))
        .map(|(dx, dy, dz)| ((-dz * py as isize - dy) * px as isize - dx) as usize)
        .collect();
    for z in 1..=bz {
        for y in 1..=by {
            for x in 1..=bx {
                let i = padded(x, y, z);
                d[i] = (before.iter()).fold(d[i], |m, &o| m.min(d[i - o].saturating_add(1)));
            }
        }
    }
    for z in (1..=bz).rev() {
        for y in (1..=by).rev() {
            for x in (1..=bx).rev() {
                let i = padded(x, y, z);
                d[i] = (before.iter()).fold(d[i], |m, &o| m.min(d[i + o].saturating_add(1)));
            }
        }
    }
    let mut out = Vec::with_capacity(bx * by * bz);
    for z in 1..=bz {
        for y in 1..=by {
            out.extend_from_slice(&d[padded(1, y, z)..padded(bx + 1, y, z)]);
        }
    }
    out
}

/// A 4-bit counter per cell of a brick, bit-sliced: bit `p` of every cell's count lives
/// in plane `p`, so adding one to a set of cells costs a few word operations.
#[derive(Clone, Copy, Default)]
pub(crate) struct Counter {
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
    pub(crate) fn write_nibbles(&self, bytes: &mut [u8]) {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::SplitMix64;

    /// The separable box dilation marks the bricks within `radius` (Chebyshev) of a
    /// marked one, as a brute-force search over all pairs does.
    #[test]
    fn box_dilate_equals_brute_force() {
        let mut random = SplitMix64::new(11);
        for case in 0..60 {
            let dims = [1, 1, 1].map(|m: u32| m + random.index(9) as u32);
            let count = dims.iter().map(|&d| d as usize).product();
            let density = [0.0, 0.01, 0.1, 0.5][case % 4];
            let marked: Vec<bool> = (0..count).map(|_| random.next_unit() < density).collect();
            let radius = 1 + case % 3;
            for (b, &near) in box_dilate(&marked, dims, radius).iter().enumerate() {
                let bc = brick_coords(b, dims).map(i64::from);
                let brute = (0..count).filter(|&o| marked[o]).any(|o| {
                    let oc = brick_coords(o, dims).map(i64::from);
                    (0..3).all(|a| (bc[a] - oc[a]).unsigned_abs() as usize <= radius)
                });
                assert_eq!(near, brute, "brick {bc:?} of {dims:?}, radius {radius}");
            }
        }
    }

    /// The chamfer passes give the Chebyshev distance to the nearest detailed brick, as a
    /// brute-force search over all pairs does, on random grids of bricks, with few,
    /// many or no detailed bricks.
    #[test]
    fn brick_distances_equal_brute_force() {
        let mut random = SplitMix64::new(7);
        for case in 0..60 {
            let bdims = [1, 1, 1].map(|m: u32| m + random.index(9) as u32);
            let count = bdims.iter().map(|&d| d as usize).product();
            let density = [0.0, 0.01, 0.1, 0.5][case % 4];
            let bricks: Vec<u32> = (0..count)
                .map(|_| {
                    if random.next_unit() < density {
                        0
                    } else {
                        UNIFORM
                    }
                })
                .collect();
            let fast = brick_distances(&bricks, bdims);
            for (b, &d) in fast.iter().enumerate() {
                let bc = brick_coords(b, bdims).map(i64::from);
                let brute = (0..count)
                    .filter(|&o| bricks[o] & UNIFORM == 0)
                    .map(|o| {
                        let oc = brick_coords(o, bdims).map(i64::from);
                        (0..3).map(|a| (bc[a] - oc[a]).abs()).max().unwrap_or(0) as u16
                    })
                    .min()
                    .unwrap_or(u16::MAX);
                assert_eq!(d, brute, "brick {bc:?} of {bdims:?}");
            }
        }
    }
}
