//! The (cell, triangle) pairs of a refreshed map: the old map's, less those of the moved
//! triangles, merged with the moved triangles' at their new positions.

use crate::par::*;

use super::super::bin::bin_triangle;
use super::super::voxel_map::{BRICK_CELLS, UNIFORM, VoxelMap, brick_dims};
use crate::mesh::Surface;

/// Moved triangles binned per parallel task.
const BIN_CHUNK: usize = 1024;

/// The pairs of a refreshed map, as `cell key << 32 | triangle` (see
/// [`bin_triangles`](super::super::bin::bin_triangles)), in increasing order of cell.
pub(super) struct Keys {
    /// Every pair. Within a cell that no moved triangle overlaps, before or after, the
    /// old map's order (along the cell's slab); within the others, by triangle, as a
    /// build sorts them.
    pub(super) keys: Vec<u64>,
    /// The cells a moved triangle overlaps, before or after (cell keys, increasing).
    pub(super) touched: Vec<u64>,
}

/// The pairs of `surface` on the grid of `old`, the map of the surface before the
/// triangles `moved` (increasing, each below `old`'s triangle count) moved.
///
/// Reads the old map's lists once (a linear pass) and bins only the moved triangles.
pub(super) fn merged_keys(old: &VoxelMap, surface: &Surface, moved: &[u32]) -> Keys {
    let mut is_moved = vec![false; old.triangle_count as usize];
    for &t in moved {
        if let Some(m) = is_moved.get_mut(t as usize) {
            *m = true;
        }
    }
    let fresh = bin_moved(old, surface, moved);
    let mut keys: Vec<u64> = Vec::with_capacity(old.triangle_refs.len() + fresh.len());
    let mut touched: Vec<u64> = Vec::new();
    let mut next = 0;
    // Appends the fresh pairs of cells before `cell` (each such cell is touched).
    let flush_before =
        |cell: u64, next: &mut usize, keys: &mut Vec<u64>, touched: &mut Vec<u64>| {
            while let Some(&key) = fresh.get(*next)
                && key >> 32 < cell
            {
                if touched.last() != Some(&(key >> 32)) {
                    touched.push(key >> 32);
                }
                keys.push(key);
                *next += 1;
            }
        };
    for (b, &entry) in old.bricks.iter().enumerate() {
        if entry & UNIFORM != 0 {
            continue;
        }
        let d = entry as usize;
        let Some(bits) = old.surface_bits.get(d) else {
            continue;
        };
        for (word, &bits) in bits.iter().enumerate() {
            let mut rest = bits;
            while rest != 0 {
                let local = word * 64 + rest.trailing_zeros() as usize;
                rest &= rest - 1;
                let cell = (b * BRICK_CELLS + local) as u64;
                flush_before(cell, &mut next, &mut keys, &mut touched);
                let start = keys.len();
                let mut changed = false;
                for &t in old.listed(d, local).unwrap_or(&[]) {
                    if is_moved.get(t as usize).copied().unwrap_or(true) {
                        changed = true;
                    } else {
                        keys.push(cell << 32 | u64::from(t));
                    }
                }
                while let Some(&key) = fresh.get(next)
                    && key >> 32 == cell
                {
                    keys.push(key);
                    next += 1;
                    changed = true;
                }
                if changed {
                    keys[start..].sort_unstable();
                    touched.push(cell);
                }
            }
        }
    }
    flush_before(u64::MAX, &mut next, &mut keys, &mut touched);
    Keys { keys, touched }
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
