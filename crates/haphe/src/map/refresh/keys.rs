//! The (cell, triangle) pairs of a refreshed map: the old map's, less those of the moved
//! triangles, merged with the moved triangles' at their new positions. Bricks no moved
//! triangle reaches are copied whole.

use crate::par::*;

use super::super::bin::bin_triangle;
use super::super::build::assembled;
use super::super::voxel_map::{
    BRICK_CELLS, BrickBits, MASK_WORDS, UNIFORM, VoxelMap, brick_dims, has, uniform_entry,
};
use super::super::{CellState, MapError};
use crate::mesh::Surface;

/// Moved triangles binned per parallel task.
const BIN_CHUNK: usize = 1024;

/// The lists of a refreshed map, spliced from the old map's: the map as
/// [`assemble`](super::super::build::assemble) hands it over, with its lists.
pub(super) struct Spliced {
    /// The map, its lists set: within a cell that no moved triangle overlaps, before or
    /// after, the old map's list (ordered along the cell's slab); within the others, by
    /// triangle, as a build sorts them.
    pub(super) map: VoxelMap,
    /// The cells a moved triangle overlaps, before or after (cell keys `brick · 512 +
    /// local`, increasing), those left without a triangle too.
    pub(super) touched: Vec<u64>,
}

/// The moved triangles (increasing, each below `old`'s triangle count) binned at their
/// positions in `surface`, on `old`'s grid: pairs `cell key << 32 | triangle`, sorted.
pub(super) fn fresh_pairs(old: &VoxelMap, surface: &Surface, moved: &[u32]) -> Vec<u64> {
    bin_moved(old, surface, moved)
}

/// The lists of `surface` on the grid of `old`, the map of the surface before the
/// triangles `moved` moved: the old map's bricks copied whole but for those of `swept`
/// (top-level indices, increasing, holding every cell a moved triangle overlaps, before
/// or after), where the moved triangles leave their old cells and join their `fresh`
/// ones ([`fresh_pairs`]).
///
/// # Errors
/// [`MapError::TooManyTriangleRefs`] as for a build.
pub(super) fn spliced(
    old: &VoxelMap,
    moved: &[u32],
    swept: &[usize],
    fresh: &[u64],
) -> Result<Spliced, MapError> {
    let mut is_moved = vec![false; old.triangle_count as usize];
    for &t in moved {
        if let Some(m) = is_moved.get_mut(t as usize) {
            *m = true;
        }
    }
    let free = if old.solid {
        CellState::Inside
    } else {
        CellState::Outside
    };
    let mut bricks = vec![uniform_entry(free, 0); old.bricks.len()];
    let mut lists = Lists::with_room(old, swept.len() + fresh.len());
    let (mut next_swept, mut next_fresh) = (0, 0);
    for (b, slot) in bricks.iter_mut().enumerate() {
        let entry = old.bricks[b];
        if swept.get(next_swept) != Some(&b) {
            if entry & UNIFORM == 0 {
                *slot = lists.copy_brick(old, entry as usize);
            }
            continue;
        }
        next_swept += 1;
        // The fresh pairs of this brick (every fresh pair lies in a swept brick).
        let from = next_fresh;
        while fresh
            .get(next_fresh)
            .is_some_and(|&key| (key >> 32) as usize / BRICK_CELLS <= b)
        {
            next_fresh += 1;
        }
        if let Some(d) = lists.splice_brick(old, &is_moved, b, &fresh[from..next_fresh]) {
            *slot = d;
        }
    }
    let count = lists.refs.len() as u64;
    if count >= u64::from(u32::MAX) {
        return Err(MapError::TooManyTriangleRefs { refs: count });
    }
    lists.surface_first.push(lists.triangle_start.len() as u32);
    lists.triangle_start.push(lists.refs.len() as u32);
    let mut map = assembled(
        old.grid,
        old.solid,
        bricks,
        lists.surface_bits,
        lists.surface_first,
        lists.triangle_start,
    );
    map.triangle_refs = lists.refs.into();
    Ok(Spliced {
        map,
        touched: lists.touched,
    })
}

/// The lists of a refreshed map as they are spliced, brick after brick.
struct Lists {
    surface_bits: Vec<BrickBits>,
    surface_first: Vec<u32>,
    triangle_start: Vec<u32>,
    refs: Vec<u32>,
    touched: Vec<u64>,
    /// A swept brick's pairs, `local << 32 | triangle`.
    pairs: Vec<u64>,
}

impl Lists {
    /// Empty lists with room for those of `old` and `extra` more cells and pairs.
    fn with_room(old: &VoxelMap, extra: usize) -> Lists {
        Lists {
            surface_bits: Vec::with_capacity(old.surface_bits.len() + extra),
            surface_first: Vec::with_capacity(old.surface_first.len() + extra),
            triangle_start: Vec::with_capacity(old.triangle_start.len() + extra),
            refs: Vec::with_capacity(old.triangle_refs.len() + extra),
            touched: Vec::new(),
            pairs: Vec::new(),
        }
    }

    /// Appends detailed brick `d` of `old` as it is, its starts shifted; returns its new
    /// index.
    fn copy_brick(&mut self, old: &VoxelMap, d: usize) -> u32 {
        let (f0, f1) = (
            old.surface_first[d] as usize,
            old.surface_first[d + 1] as usize,
        );
        let (r0, r1) = (
            old.triangle_start[f0] as usize,
            old.triangle_start[f1] as usize,
        );
        self.surface_first.push(self.triangle_start.len() as u32);
        self.surface_bits.push(old.surface_bits[d]);
        let at = self.refs.len() as u32;
        self.triangle_start.extend(
            old.triangle_start[f0..f1]
                .iter()
                .map(|&s| s.wrapping_sub(r0 as u32).wrapping_add(at)),
        );
        self.refs.extend_from_slice(&old.triangle_refs[r0..r1]);
        (self.surface_bits.len() - 1) as u32
    }

    /// Appends swept brick `b`: the old lists less the moved triangles, then its `fresh`
    /// pairs; returns its new index, or `None` when it holds no surface cell now.
    fn splice_brick(
        &mut self,
        old: &VoxelMap,
        is_moved: &[bool],
        b: usize,
        fresh: &[u64],
    ) -> Option<u32> {
        self.pairs.clear();
        let mut changed: BrickBits = [0; MASK_WORDS];
        let entry = old.bricks[b];
        if entry & UNIFORM == 0
            && let Some(bits) = old.surface_bits.get(entry as usize)
        {
            for local in cells(bits) {
                for &t in old.listed(entry as usize, local).unwrap_or(&[]) {
                    if is_moved.get(t as usize).copied().unwrap_or(true) {
                        changed[local >> 6] |= 1 << (local & 63);
                    } else {
                        self.pairs.push((local as u64) << 32 | u64::from(t));
                    }
                }
            }
        }
        for &key in fresh {
            let local = (key >> 32) as usize % BRICK_CELLS;
            changed[local >> 6] |= 1 << (local & 63);
            self.pairs
                .push((local as u64) << 32 | (key & u64::from(u32::MAX)));
        }
        // By cell, each cell's old list in its order, before its fresh pairs; a changed
        // cell's list by triangle.
        self.pairs.sort_by_key(|&p| p >> 32);
        let first = self.triangle_start.len() as u32;
        let mut bits: BrickBits = [0; MASK_WORDS];
        let mut start = 0;
        while start < self.pairs.len() {
            let local = (self.pairs[start] >> 32) as usize;
            let end = start + self.pairs[start..].partition_point(|&p| (p >> 32) as usize == local);
            if has(&changed, local) {
                self.pairs[start..end].sort_unstable();
            }
            bits[local >> 6] |= 1 << (local & 63);
            self.triangle_start.push(self.refs.len() as u32);
            self.refs
                .extend(self.pairs[start..end].iter().map(|&p| p as u32));
            start = end;
        }
        self.touched
            .extend(cells(&changed).map(|local| (b * BRICK_CELLS + local) as u64));
        if bits == [0; MASK_WORDS] {
            return None;
        }
        self.surface_first.push(first);
        self.surface_bits.push(bits);
        Some((self.surface_bits.len() - 1) as u32)
    }
}

/// The cells set in `bits`, in increasing order.
fn cells(bits: &BrickBits) -> impl Iterator<Item = usize> + '_ {
    bits.iter().enumerate().flat_map(|(word, &w)| {
        let mut rest = w;
        std::iter::from_fn(move || {
            (rest != 0).then(|| {
                let local = word * 64 + rest.trailing_zeros() as usize;
                rest &= rest - 1;
                local
            })
        })
    })
}

/// The pairs of the moved triangles at their positions in `surface`, sorted.
fn bin_moved(old: &VoxelMap, surface: &Surface, moved: &[u32]) -> Vec<u64> {
    let grid = &old.grid;
    let (dims, bdims) = (grid.dims(), brick_dims(grid.dims()));
    let (triangles, vertices) = (surface.triangles(), surface.vertices());
    let parts: Vec<Vec<u64>> = moved
        .par_chunks(BIN_CHUNK)
        .map(|chunk| {
            let mut out = Vec::with_capacity(chunk.len() * 8);
            for &t in chunk {
                if let Some(tri) = triangles.get(t as usize) {
                    let corners = tri.map(|v| grid.to_grid(vertices[v as usize]));
                    bin_triangle(corners, t, dims, bdims, &mut out);
                }
            }
            out.sort_unstable();
            out
        })
        .collect();
    let mut fresh: Vec<u64> = parts.concat();
    fresh.par_sort_unstable();
    fresh
}
