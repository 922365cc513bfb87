//! Slabs after a deformation, derived again only where a moved triangle lies or lay.
//!
//! A surface cell's slab and the order of its list depend only on its triangles' corners:
//! a cell that no moved triangle overlaps, before or after, keeps both. A brick keeps its
//! slab when none of its cells is touched, a region of bricks when none of its bricks is.

use crate::par::*;

use super::super::free_space::region_dims;
use super::super::slabs::SlabScratch;
use super::super::voxel_map::{
    BRICK_CELLS, BrickBits, MASK_WORDS, UNIFORM, VoxelMap, brick_coords, has,
};
use crate::mesh::Surface;

/// Bricks of a region along each side: `2^REGION_BRICK_BITS`.
const REGION_BRICK_BITS: u32 = 2;

/// What a detailed brick's slabs become.
enum Derived {
    /// As in the old map's detailed brick of this index.
    Kept(usize),
    /// Derived again: the slabs of its surface cells, its own, and the new order of the
    /// lists of its touched cells (the index of the cell, its ordered list).
    Fresh(Vec<u32>, u32, Vec<(usize, Vec<u32>)>),
}

/// Sets the slabs of `map` (the map of `surface` after a deformation, its lists those of
/// `old` in untouched cells and sorted by triangle in the cells of `touched`, cell keys
/// increasing), and orders the touched cells' lists along their slabs.
pub(super) fn reslab(map: &mut VoxelMap, old: &VoxelMap, surface: &Surface, touched: &[u64]) {
    // The touched cells of each brick, in brick order.
    let mut by_brick: Vec<(usize, BrickBits)> = Vec::new();
    for &cell in touched {
        let (b, local) = ((cell as usize) / BRICK_CELLS, (cell as usize) % BRICK_CELLS);
        if by_brick.last().map(|&(last, _)| last) != Some(b) {
            by_brick.push((b, [0; MASK_WORDS]));
        }
        if let Some((_, bits)) = by_brick.last_mut() {
            bits[local >> 6] |= 1 << (local & 63);
        }
    }
    let tops: Vec<usize> = (0..map.bricks.len())
        .filter(|&b| map.bricks[b] & UNIFORM == 0)
        .collect();
    let this: &VoxelMap = map;
    let derived: Vec<Derived> = tops
        .par_iter()
        .map(|&b| {
            let touched = by_brick
                .binary_search_by_key(&b, |&(t, _)| t)
                .ok()
                .map(|i| by_brick[i].1);
            derive_brick(this, old, surface, b, touched)
        })
        .collect();
    let mut slabs: Vec<u32> = Vec::with_capacity(map.triangle_start.len().saturating_sub(1));
    let mut brick_slabs: Vec<u32> = Vec::with_capacity(derived.len());
    let mut refs = map.triangle_refs.take_vec();
    for derived in &derived {
        match derived {
            Derived::Kept(d) => {
                let (from, to) = (old.surface_first[*d], old.surface_first[*d + 1]);
                slabs.extend_from_slice(&old.slabs[from as usize..to as usize]);
                brick_slabs.push(old.brick_slabs[*d]);
            }
            Derived::Fresh(cell_slabs, brick_slab, ordered) => {
                slabs.extend_from_slice(cell_slabs);
                brick_slabs.push(*brick_slab);
                for (s, list) in ordered {
                    let start = map.triangle_start[*s] as usize;
                    if let Some(part) = refs.get_mut(start..start + list.len()) {
                        part.copy_from_slice(list);
                    }
                }
            }
        }
    }
    map.triangle_refs = refs.into();
    map.slabs = slabs.into();
    map.brick_slabs = brick_slabs.into();

    // Regions holding a touched brick: derived again; the others kept.
    let dims = region_dims(map.brick_dims);
    let [rx, ry, _] = dims.map(|d| d as usize);
    let region_of = |b: usize| {
        let bc = brick_coords(b, map.brick_dims).map(|v| (v >> REGION_BRICK_BITS) as usize);
        (bc[2] * ry + bc[1]) * rx + bc[0]
    };
    let mut regions: Vec<usize> = by_brick.iter().map(|&(b, _)| region_of(b)).collect();
    regions.sort_unstable();
    regions.dedup();
    let this: &VoxelMap = map;
    let of_brick = |entry: u32, out: &mut Vec<u32>| {
        let d = entry as usize;
        if let (Some(&from), Some(&to)) = (this.surface_first.get(d), this.surface_first.get(d + 1))
            && let (Some(&start), Some(&end)) = (
                this.triangle_start.get(from as usize),
                this.triangle_start.get(to as usize),
            )
        {
            out.extend_from_slice(&this.triangle_refs[start as usize..end as usize]);
        }
    };
    let fresh: Vec<u64> = regions
        .par_iter()
        .map(|&r| this.region_slab(surface, r, &of_brick))
        .collect();
    let mut region_slabs = old.region_slabs.to_vec();
    for (&r, slab) in regions.iter().zip(fresh) {
        if let Some(s) = region_slabs.get_mut(r) {
            *s = slab;
        }
    }
    map.region_slabs = region_slabs.into();
}

/// The slabs of the detailed brick at top-level index `b`, whose cells `touched` are
/// touched by a moved triangle.
fn derive_brick(
    map: &VoxelMap,
    old: &VoxelMap,
    surface: &Surface,
    b: usize,
    touched: Option<BrickBits>,
) -> Derived {
    let d = map.bricks[b] as usize;
    let old_entry = old.bricks.get(b).copied().unwrap_or(UNIFORM);
    let bits = map.surface_bits.get(d).copied().unwrap_or_default();
    let old_bits = (old_entry & UNIFORM == 0)
        .then(|| old.surface_bits.get(old_entry as usize).copied())
        .flatten();
    if touched.is_none() && old_bits == Some(bits) {
        return Derived::Kept(old_entry as usize);
    }
    let touched = touched.unwrap_or([0; MASK_WORDS]);
    let first = map.surface_first.get(d).copied().unwrap_or(0) as usize;
    let mut scratch = SlabScratch::default();
    let (mut cell_slabs, mut ordered, mut triangles) = (Vec::new(), Vec::new(), Vec::new());
    let mut s = first;
    for (word, &w) in bits.iter().enumerate() {
        let mut rest = w;
        while rest != 0 {
            let local = word * 64 + rest.trailing_zeros() as usize;
            rest &= rest - 1;
            let listed = map.listed(d, local).unwrap_or(&[]);
            triangles.extend_from_slice(listed);
            let kept = if has(&touched, local) {
                None
            } else {
                old.listed_at(old_entry as usize, local)
                    .map(|(_, s_old)| old.slab(s_old))
            };
            let slab = match kept {
                Some(slab) => slab,
                None => {
                    // Sorted by triangle, as the build's list: the slab depends on which
                    // triangle comes first.
                    let mut sorted = listed.to_vec();
                    sorted.sort_unstable();
                    let slab = map.cell_slab(surface, b, local, &sorted, &mut scratch);
                    ordered.push((s, scratch.keyed.iter().map(|&(_, t)| t).collect()));
                    slab
                }
            };
            cell_slabs.push(slab);
            s += 1;
        }
    }
    triangles.sort_unstable();
    triangles.dedup();
    let brick_slab = map.brick_slab_over(surface, b, &triangles, &mut scratch);
    Derived::Fresh(cell_slabs, brick_slab, ordered)
}
