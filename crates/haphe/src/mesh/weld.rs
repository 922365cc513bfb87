//! Welding: merging vertices that are the same point, so that triangles share them.
//!
//! Files such as STL store every triangle with its own three corners; the topology (which
//! triangle lies across which edge) exists only once equal corners are one vertex.

use crate::par::*;
use glam::DVec3;
use rustc_hash::FxHashMap;

use super::Mesh;

/// How duplicate vertices are merged.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Weld {
    /// Merge vertices with bit-identical coordinates (`-0.0` equals `0.0`). The default:
    /// it never moves a vertex.
    #[default]
    Exact,
    /// Merge vertices closer than this distance, metres, transitively (a chain of close
    /// vertices becomes one). Each merged vertex takes the position of its first member.
    Tolerance(f64),
    /// Keep the vertices as the file indexes them (unreferenced ones are still dropped).
    Off,
}

/// What a weld did.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct WeldStats {
    /// Vertices before welding.
    pub vertices_before: usize,
    /// Vertices merged into an earlier one.
    pub merged: usize,
    /// Vertices no triangle used, dropped.
    pub unreferenced: usize,
}

/// Welds the vertices of `mesh` as `mode` says and drops vertices no triangle uses.
///
/// Vertices keep the order of their first use, so the result is deterministic, and welding
/// a welded mesh again changes nothing (idempotent, for every mode).
pub fn weld(mesh: &Mesh, mode: Weld) -> (Mesh, WeldStats) {
    let n = mesh.vertices.len();
    // representative[v]: the vertex v merges into (itself when it is kept).
    let representative: Vec<u32> = match mode {
        Weld::Exact => exact_representatives(&mesh.vertices),
        Weld::Tolerance(tol) if tol.is_finite() && tol > 0.0 => {
            tolerance_representatives(&mesh.vertices, tol)
        }
        Weld::Tolerance(_) => exact_representatives(&mesh.vertices),
        Weld::Off => (0..n as u32).collect(),
    };
    let merged = representative
        .iter()
        .enumerate()
        .filter(|&(v, &r)| r as usize != v)
        .count();

    // Renumber the kept vertices in order of first use by a triangle.
    let mut new_index = vec![u32::MAX; n];
    let mut vertices = Vec::with_capacity(n - merged);
    let triangles = mesh
        .triangles
        .iter()
        .map(|tri| {
            tri.map(|v| {
                let r = representative[v as usize] as usize;
                if new_index[r] == u32::MAX {
                    new_index[r] = vertices.len() as u32;
                    vertices.push(mesh.vertices[r]);
                }
                new_index[r]
            })
        })
        .collect();
    let stats = WeldStats {
        vertices_before: n,
        merged,
        unreferenced: n - merged - vertices.len(),
    };
    (
        Mesh {
            vertices,
            triangles,
        },
        stats,
    )
}

/// The exact identity of a position: the bit patterns of its coordinates (with `-0.0`
/// folded into `0.0`), each passed through a bijective mixer. Equal keys mean equal
/// positions; the mixing spreads the bits, since coordinates read from `f32` files have 29
/// zero low bits, which a fast hash would map into few buckets.
#[inline]
fn key(p: DVec3) -> [u64; 3] {
    (p + DVec3::ZERO).to_array().map(|x| mix64(x.to_bits()))
}

/// MurmurHash3's 64-bit finaliser: a bijection on `u64` with full avalanche.
#[inline]
fn mix64(mut x: u64) -> u64 {
    x ^= x >> 33;
    x = x.wrapping_mul(0xff51_afd7_ed55_8ccd);
    x ^= x >> 33;
    x = x.wrapping_mul(0xc4ce_b9fe_1a85_ec53);
    x ^ (x >> 33)
}

/// Number of hash shards of the exact weld, as a power of two: each shard's table stays
/// small enough for the cache, so a million-vertex weld does not wait on memory.
const WELD_SHARD_BITS: u32 = 8;

/// For each vertex, the first vertex with the same key. Vertices are split into shards by
/// the top bits of their key (a counting sort that keeps index order within a
/// shard), then each shard is welded with its own small table, in parallel.
fn exact_representatives(vertices: &[DVec3]) -> Vec<u32> {
    // The shard comes from the mixed y bits, not from the table's hash: a shard whose
    // members all shared the hash's top bits would defeat the table's tag filtering. Keys
    // are computed twice rather than stored: fresh memory costs more than the mixing.
    let shard_of = |k: &[u64; 3]| (k[1] >> (64 - WELD_SHARD_BITS)) as usize;
    let shards = 1usize << WELD_SHARD_BITS;
    let mut start = vec![0usize; shards + 1];
    for &p in vertices {
        start[shard_of(&key(p)) + 1] += 1;
    }
    for s in 0..shards {
        start[s + 1] += start[s];
    }
    // Scatter (key, vertex) into shard order: 2^WELD_SHARD_BITS sequential write streams,
    // so each shard is then read from contiguous memory.
    let mut fill = start.clone();
    let mut sorted = vec![([0u64; 3], 0u32); vertices.len()];
    for (v, &p) in vertices.iter().enumerate() {
        let k = key(p);
        let s = shard_of(&k);
        sorted[fill[s]] = (k, v as u32);
        fill[s] += 1;
    }
    // Representatives in `sorted`'s order, computed shard by shard.
    let mut in_order = vec![0u32; vertices.len()];
    let mut segments = Vec::with_capacity(shards);
    let mut rest = in_order.as_mut_slice();
    for s in 0..shards {
        let (head, tail) = rest.split_at_mut(start[s + 1] - start[s]);
        segments.push((s, head));
        rest = tail;
    }
    segments.into_par_iter().for_each(|(s, out)| {
        let members = &sorted[start[s]..start[s + 1]];
        let mut first: FxHashMap<[u64; 3], u32> =
            FxHashMap::with_capacity_and_hasher(members.len(), Default::default());
        for (slot, &(k, v)) in out.iter_mut().zip(members) {
            *slot = *first.entry(k).or_insert(v);
        }
    });
    let mut representative = vec![0u32; vertices.len()];
    for (&(_, v), &r) in sorted.iter().zip(&in_order) {
        representative[v as usize] = r;
    }
    representative
}

/// Union of every pair of vertices closer than `tol`, found through a hash grid of cell
/// size `tol` (each vertex looks at its own and the 26 adjacent cells).
fn tolerance_representatives(vertices: &[DVec3], tol: f64) -> Vec<u32> {
    let cell_of = |p: DVec3| (p / tol).floor().as_i64vec3().to_array();
    let mut grid: FxHashMap<[i64; 3], Vec<u32>> = FxHashMap::default();
    for (v, &p) in vertices.iter().enumerate() {
        grid.entry(cell_of(p)).or_default().push(v as u32);
    }
    let mut parent: Vec<u32> = (0..vertices.len() as u32).collect();
    let tol2 = tol * tol;
    for (v, &p) in vertices.iter().enumerate() {
        let [x, y, z] = cell_of(p);
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    let Some(members) = grid.get(&[x + dx, y + dy, z + dz]) else {
                        continue;
                    };
                    for &w in members {
                        if (w as usize) < v && vertices[w as usize].distance_squared(p) < tol2 {
                            union(&mut parent, v as u32, w);
                        }
                    }
                }
            }
        }
    }
    (0..vertices.len() as u32)
        .map(|v| find(&mut parent, v))
        .collect()
}

/// Root of `v`, halving the path on the way. Roots are the smallest index of their set.
pub(crate) fn find(parent: &mut [u32], mut v: u32) -> u32 {
    while parent[v as usize] != v {
        let grand = parent[parent[v as usize] as usize];
        parent[v as usize] = grand;
        v = grand;
    }
    v
}

/// Joins the sets of `a` and `b`; the smaller root becomes the root (deterministic).
pub(crate) fn union(parent: &mut [u32], a: u32, b: u32) {
    let (ra, rb) = (find(parent, a), find(parent, b));
    if ra != rb {
        let (lo, hi) = if ra < rb { (ra, rb) } else { (rb, ra) };
        parent[hi as usize] = lo;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn soup() -> Mesh {
        // Two triangles sharing an edge, stored as a soup (six corners), plus one unused.
        let v = |x, y| DVec3::new(x, y, 0.0);
        Mesh {
            vertices: vec![
                v(0.0, 0.0),
                v(1.0, 0.0),
                v(0.0, 1.0),
                v(1.0, 0.0),
                v(1.0, 1.0),
                v(-0.0, 1.0),
                v(5.0, 5.0),
            ],
            triangles: vec![[0, 1, 2], [3, 4, 5]],
        }
    }

    #[test]
    fn exact_weld_merges_equal_corners_and_folds_negative_zero() {
        let (welded, stats) = weld(&soup(), Weld::Exact);
        assert_eq!(welded.vertices.len(), 4);
        assert_eq!(welded.triangles, vec![[0, 1, 2], [1, 3, 2]]);
        assert_eq!(
            stats,
            WeldStats {
                vertices_before: 7,
                merged: 2,
                unreferenced: 1
            }
        );
    }

    #[test]
    fn tolerance_weld_merges_chains_and_keeps_the_first_position() {
        let mut mesh = soup();
        mesh.vertices[3].x += 4e-7;
        mesh.vertices[5].y -= 4e-7;
        assert_eq!(weld(&mesh, Weld::Exact).0.vertices.len(), 6);
        let (welded, _) = weld(&mesh, Weld::Tolerance(1e-6));
        assert_eq!(welded.vertices.len(), 4);
        assert_eq!(welded.vertices[1], DVec3::new(1.0, 0.0, 0.0));
    }

    #[test]
    fn weld_off_only_drops_unreferenced_vertices() {
        let (welded, stats) = weld(&soup(), Weld::Off);
        assert_eq!(welded.vertices.len(), 6);
        assert_eq!(stats.unreferenced, 1);
    }
}
