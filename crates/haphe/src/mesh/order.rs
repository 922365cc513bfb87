//! Spatial order: triangles sorted along a Morton (Z-order) curve of their centroids, and
//! vertices numbered in the order those triangles first use them.
//!
//! Every query walks from a triangle to its neighbours and reads the cells, frames,
//! corners and normals around one place. In the order a file lists its faces, neighbours
//! can lie anywhere in memory (a mesh that went through a tool that hashes or sorts its
//! faces by anything but place is, in effect, shuffled); on a mesh of millions of
//! triangles each step then misses the caches and the translation buffer. Sorted along a
//! space-filling curve, triangles near each other on the surface lie near each other in
//! the arrays, whatever order the file had. [`Surface::new`](super::Surface::new) applies
//! it unless [`SurfaceOptions::spatial_order`](super::SurfaceOptions::spatial_order) says
//! not to, and keeps each triangle's index in the mesh it was given
//! ([`Surface::source_triangle`](super::Surface::source_triangle)).

use crate::par::*;
use glam::DVec3;

use super::Mesh;

/// Bits of each coordinate in a Morton key: a curve through 1024³ boxes, of which a surface
/// of a few million triangles meets a few million, so a box holds a handful of triangles
/// at most (ties keep the mesh's order); and a key of 30 bits that fits beside a
/// triangle's index in one `u64` (a sort of plain words).
const KEY_BITS: u32 = 10;

/// `x`'s low [`KEY_BITS`] bits spread to every third bit.
#[inline]
fn spread(x: u64) -> u64 {
    let mut x = x & ((1 << KEY_BITS) - 1);
    x = (x | x << 32) & 0x001f_0000_0000_ffff;
    x = (x | x << 16) & 0x001f_0000_ff00_00ff;
    x = (x | x << 8) & 0x100f_00f0_0f00_f00f;
    x = (x | x << 4) & 0x10c3_0c30_c30c_30c3;
    x = (x | x << 2) & 0x1249_2492_4924_9249;
    x
}

/// The Morton key of point `p` in the cube of side `extent` at `lo` (points outside it are
/// clamped onto it).
#[inline]
fn morton_key(p: DVec3, lo: DVec3, extent: f64) -> u64 {
    let top = f64::from((1u32 << KEY_BITS) - 1);
    let q = ((p - lo) * (top / extent)).clamp(DVec3::ZERO, DVec3::splat(top));
    spread(q.x as u64) | spread(q.y as u64) << 1 | spread(q.z as u64) << 2
}

/// `mesh` with its triangles sorted by the Morton key of their centroids (ties by their
/// index) and its vertices renumbered in order of first use by those triangles (vertices no
/// triangle uses keep their relative order, after the others), and for each triangle of
/// the result its index in `mesh`. The same mesh gives the same result, bit for bit; the
/// corners of triangle `t` of the result are those of triangle `source[t]` of `mesh`, in
/// the same order.
///
/// # Performance
/// One key per triangle, a parallel sort of one word per triangle and one pass to
/// renumber: linear but for the sort (`haphe bench` times it within the build).
pub(crate) fn spatial_order(mesh: Mesh) -> (Mesh, Vec<u32>) {
    let (lo, extent) = match mesh.bounds() {
        Some((lo, hi)) => (lo, (hi - lo).max_element()),
        None => (DVec3::ZERO, 0.0),
    };
    let Mesh {
        vertices,
        triangles,
    } = mesh;
    let key = |t: usize, tri: &[u32; 3]| {
        let centroid = tri.iter().map(|&v| vertices[v as usize]).sum::<DVec3>() / 3.0;
        let k = if extent > 0.0 && extent.is_finite() {
            morton_key(centroid, lo, extent)
        } else {
            0
        };
        k << 32 | t as u64
    };
    let mut keyed: Vec<u64> = triangles
        .par_iter()
        .enumerate()
        .map(|(t, tri)| key(t, tri))
        .collect();
    // Each word holds a key and a distinct index: any sort gives the one order.
    keyed.par_sort_unstable();
    let source: Vec<u32> = keyed.par_iter().map(|&k| k as u32).collect();
    drop(keyed);

    const UNSEEN: u32 = u32::MAX;
    let mut renumber = vec![UNSEEN; vertices.len()];
    let mut order: Vec<u32> = Vec::with_capacity(vertices.len());
    let sorted: Vec<[u32; 3]> = source
        .iter()
        .map(|&t| {
            triangles[t as usize].map(|v| {
                let new = &mut renumber[v as usize];
                if *new == UNSEEN {
                    *new = order.len() as u32;
                    order.push(v);
                }
                *new
            })
        })
        .collect();
    for (v, new) in renumber.iter_mut().enumerate() {
        if *new == UNSEEN {
            *new = order.len() as u32;
            order.push(v as u32);
        }
    }
    let vertices = order.par_iter().map(|&v| vertices[v as usize]).collect();
    (
        Mesh {
            vertices,
            triangles: sorted,
        },
        source,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::shapes;

    #[test]
    fn spread_interleaves_bits() {
        assert_eq!(spread(0b1), 0b1);
        assert_eq!(spread(0b11), 0b1001);
        assert_eq!(spread(0b101), 0b1_000_001);
        assert_eq!(spread((1 << KEY_BITS) - 1).count_ones(), KEY_BITS);
        // Neighbouring octants: x, y and z take bits 0, 1 and 2.
        let lo = DVec3::ZERO;
        assert!(morton_key(DVec3::new(0.9, 0.1, 0.1), lo, 1.0) < morton_key(DVec3::Y, lo, 1.0));
        assert!(morton_key(DVec3::Y, lo, 1.0) < morton_key(DVec3::Z * 0.9, lo, 1.0));
    }

    #[test]
    fn the_order_is_a_permutation_that_keeps_every_triangle() {
        let mut mesh = shapes::sphere(0.1, 3);
        // Shuffle the faces, and leave one vertex unused.
        mesh.triangles.reverse();
        mesh.triangles.swap(3, 700);
        mesh.vertices.push(DVec3::splat(0.05));
        let (sorted, source) = spatial_order(mesh.clone());
        assert_eq!(sorted.triangles.len(), mesh.triangles.len());
        assert_eq!(sorted.vertices.len(), mesh.vertices.len());
        let mut seen = vec![false; source.len()];
        for (t, &s) in source.iter().enumerate() {
            assert!(!std::mem::replace(&mut seen[s as usize], true), "{s} twice");
            assert_eq!(sorted.corners(t), mesh.corners(s as usize));
        }
        // The unused vertex comes last; the first triangle uses vertices 0, 1, 2.
        assert_eq!(sorted.vertices.last(), Some(&DVec3::splat(0.05)));
        assert_eq!(sorted.triangles[0], [0, 1, 2]);
        // Deterministic, and idempotent up to the numbering it already has.
        assert_eq!(spatial_order(mesh.clone()), (sorted.clone(), source));
        let (again, identity) = spatial_order(sorted.clone());
        assert_eq!(again, sorted);
        assert!(identity.iter().enumerate().all(|(t, &s)| s == t as u32));
    }

    #[test]
    fn sorted_neighbours_lie_closer_in_memory() {
        // A shuffled sphere: the mean index distance across shared edges falls from about
        // a third of the mesh to a small fraction of it.
        let mut mesh = shapes::sphere(0.1, 5);
        let n = mesh.triangles.len();
        shapes::shuffle_faces(&mut mesh, 7);
        let spread_of = |m: &Mesh| {
            let table = crate::mesh::edges::EdgeTable::build(&m.triangles);
            let (sum, count) = table
                .groups()
                .filter_map(|g| match g {
                    [a, b] => Some(a.tri.abs_diff(b.tri) as f64),
                    _ => None,
                })
                .fold((0.0, 0.0), |(s, c), d| (s + d, c + 1.0));
            sum / count / n as f64
        };
        let before = spread_of(&mesh);
        let after = spread_of(&spatial_order(mesh).0);
        assert!(before > 0.25 && after < 0.05, "{before} → {after}");
    }
}
