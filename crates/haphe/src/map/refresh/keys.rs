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
    let extra = swept.len() + fresh.len();
    let mut surface_bits: Vec<BrickBits> = Vec::with_capacity(old.surface_bits.len() + extra);
    let mut surface_first: Vec<u32> = Vec::with_capacity(old.surface_first.len() + extra);
    let mut triangle_start: Vec<u32> = Vec::with_capacity(old.triangle_start.len() + extra);
    let mut refs: Vec<u32> = Vec::with_capacity(old.triangle_refs.len() + fresh.len());
    let mut touched: Vec<u64> = Vec::new();
    let (mut next_swept, mut next_fresh) = (0, 0);
    // A swept brick's pairs, `local << 32 | triangle`.
    let mut pairs: Vec<u64> = Vec::new();
    for (b, slot) in bricks.iter_mut().enumerate() {
        let entry = old.bricks[b];
        if swept.get(next_swept) == Some(&b) {
            next_swept += 1;
        } else {
            if entry & UNIFORM != 0 {
                continue;
            }
            // A clean detailed brick: copied, its starts shifted.
            let d = entry as usize;
            let (f0, f1) = (
                old.surface_first[d] as usize,
                old.surface_first[d + 1] as usize,
            );
            let (r0, r1) = (
                old.triangle_start[f0] as usize,
                old.triangle_start[f1] as usize,
            );
            *slot = surface_bits.len() as u32;
            surface_first.push(triangle_start.len() as u32);
            surface_bits.push(old.surface_bits[d]);
            let at = refs.len() as u32;
            triangle_start.extend(
                old.triangle_start[f0..f1]
                    .iter()
                    .map(|&s| s.wrapping_sub(r0 as u32).wrapping_add(at)),
            );
            refs.extend_from_slice(&old.triangle_refs[r0..r1]);
            continue;
        }
        // A swept brick: the old lists less the moved triangles, then the fresh pairs.
        pairs.clear();
        let mut changed: BrickBits = [0; MASK_WORDS];
        if entry & UNIFORM == 0
            && let Some(bits) = old.surface_bits.get(entry as usize)
        {
            for (word, &bits) in bits.iter().enumerate() {
                let mut rest = bits;
                while rest != 0 {
                    let local = word * 64 + rest.trailing_zeros() as usize;
                    rest &= rest - 1;
                    for &t in old.listed(entry as usize, local).unwrap_or(&[]) {
                        if is_moved.get(t as usize).copied().unwrap_or(true) {
                            changed[word] |= 1 << (local & 63);
                        } else {
                            pairs.push((local as u64) << 32 | u64::from(t));
                        }
                    }
                }
            }
        }
        while let Some(&key) = fresh.get(next_fresh)
            && (key >> 32) as usize / BRICK_CELLS <= b
        {
            next_fresh += 1;
            let local = (key >> 32) as usize % BRICK_CELLS;
            changed[local >> 6] |= 1 << (local & 63);
            pairs.push((local as u64) << 32 | (key & u64::from(u32::MAX)));
        }
        // By cell, each cell's old list in its order, before its fresh pairs; a changed
        // cell's list by triangle.
        pairs.sort_by_key(|&p| p >> 32);
        let first = triangle_start.len() as u32;
        let mut bits: BrickBits = [0; MASK_WORDS];
        let mut start = 0;
        while start < pairs.len() {
            let local = (pairs[start] >> 32) as usize;
            let end = start + pairs[start..].partition_point(|&p| (p >> 32) as usize == local);
            if has(&changed, local) {
                pairs[start..end].sort_unstable();
            }
            bits[local >> 6] |= 1 << (local & 63);
            triangle_start.push(refs.len() as u32);
            refs.extend(pairs[start..end].iter().map(|&p| p as u32));
            start = end;
        }
        for (word, &w) in changed.iter().enumerate() {
            let mut rest = w;
            while rest != 0 {
                let local = word * 64 + rest.trailing_zeros() as usize;
                rest &= rest - 1;
                touched.push((b * BRICK_CELLS + local) as u64);
            }
        }
        if bits != [0; MASK_WORDS] {
            *slot = surface_bits.len() as u32;
            surface_first.push(first);
            surface_bits.push(bits);
        }
    }
    let count = refs.len() as u64;
    if count >= u64::from(u32::MAX) {
        return Err(MapError::TooManyTriangleRefs { refs: count });
    }
    surface_first.push(triangle_start.len() as u32);
    triangle_start.push(refs.len() as u32);
    let mut map = assembled(
        old.grid,
        old.solid,
        bricks,
        surface_bits,
        surface_first,
        triangle_start,
    );
    map.triangle_refs = refs.into();
    Ok(Spliced { map, touched })
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
