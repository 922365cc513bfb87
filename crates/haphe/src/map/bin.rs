//! Binning: every (cell, triangle) pair of a map, found in parallel and sorted by cell.

use crate::par::*;
use glam::DVec3;

use super::build::PROGRESS_BINNED;
use super::grid::{
    Grid, OVERLAP_TOLERANCE_REL, ceil_to_int, cell_centre_units, cell_tester, floor_to_int,
};
use super::voxel_map::{BRICK_CELLS, brick_dims, brick_of, local_of};
use crate::mesh::Surface;

/// Extra width, in cells, of the slabs used to find candidate cells for a triangle,
/// beyond [`OVERLAP_TOLERANCE_REL`]: covers rounding in the clipping (about `1e-10` cells
/// for the largest grids), so the candidates are a superset of the cells the exact test
/// accepts.
const CANDIDATE_MARGIN_CELLS: f64 = 1e-5;

/// Triangles whose bounding box spans at most this many cells are tested against each of
/// them; larger ones are clipped to find their cells (work proportional to the cells they
/// meet rather than to their bounding box).
const SMALL_TRIANGLE_CELLS: i64 = 48;

/// Triangles binned per parallel task.
const BIN_CHUNK: usize = 2048;

/// The binning is split into this many sequential batches so progress can be reported.
const BIN_BATCHES: usize = 20;

/// Every (cell, triangle) pair as `cell key << 32 | triangle`, where the cell key is
/// `brick · 512 + local` (brick-major), in no particular order, in parts (one per chunk
/// of triangles: [`sort_by_cell`] reads them where they lie rather than from one copy).
pub(super) fn bin_triangles(
    surface: &Surface,
    grid: &Grid,
    progress: &(dyn Fn(f64) + Sync),
) -> Vec<Vec<u64>> {
    let triangles = surface.triangles();
    let vertices = surface.vertices();
    let bdims = brick_dims(grid.dims());
    let batch = triangles.len().div_ceil(BIN_BATCHES).max(1);
    let mut keys: Vec<Vec<u64>> = Vec::new();
    for (b, batch_tris) in triangles.chunks(batch).enumerate() {
        let first = b * batch;
        let parts: Vec<Vec<u64>> = batch_tris
            .par_chunks(BIN_CHUNK)
            .enumerate()
            .map(|(c, chunk)| {
                let mut out = Vec::with_capacity(chunk.len() * 8);
                for (k, tri) in chunk.iter().enumerate() {
                    let t = (first + c * BIN_CHUNK + k) as u32;
                    let corners = tri.map(|v| grid.to_grid(vertices[v as usize]));
                    bin_triangle(corners, t, grid.dims(), bdims, &mut out);
                }
                out
            })
            .collect();
        keys.extend(parts);
        progress(PROGRESS_BINNED * (first + batch_tris.len()) as f64 / triangles.len() as f64);
    }
    keys
}

/// Appends the keys of every cell that triangle `t` (corners in cell units) overlaps.
///
/// Candidates come from clipping the triangle to a slab of cells along its thinnest axis,
/// then to a row within the slab; the span of the clipped piece along the third axis gives
/// the cells of the row. Each candidate is confirmed with the exact test, so the result is
/// the listing predicate exactly; the work is proportional to the cells the triangle meets.
/// Padding cells are never candidates (the surface lies inside the interior cells).
pub(super) fn bin_triangle(
    corners: [DVec3; 3],
    t: u32,
    dims: [u32; 3],
    bdims: [u32; 3],
    out: &mut Vec<u64>,
) {
    let lo = corners[0].min(corners[1]).min(corners[2]);
    let hi = corners[0].max(corners[1]).max(corners[2]);
    let extent = hi - lo;
    let w = if extent.x <= extent.y && extent.x <= extent.z {
        0
    } else if extent.y <= extent.z {
        1
    } else {
        2
    };
    let (v, u) = ((w + 1) % 3, (w + 2) % 3);
    let m = OVERLAP_TOLERANCE_REL + CANDIDATE_MARGIN_CELLS;
    // Interior cells whose slab [i − m, i + 1 + m] meets [a, b].
    let span = |axis: usize, a: f64, b: f64| -> (i64, i64) {
        let first = ceil_to_int(a - 1.0 - m).max(1);
        let last = floor_to_int(b + m).min(i64::from(dims[axis]) - 2);
        (first, last)
    };
    let tester = cell_tester(corners);
    // Appends the key of the cell at (i, j, k) along (u, v, w) when the triangle overlaps it.
    let emit = |k: i64, j: i64, i: i64, out: &mut Vec<u64>| {
        let mut cell = [0u32; 3];
        cell[w] = k as u32;
        cell[v] = j as u32;
        cell[u] = i as u32;
        if tester.overlaps(cell_centre_units(cell)) {
            let key = (brick_of(cell, bdims) * BRICK_CELLS + local_of(cell)) as u64;
            out.push(key << 32 | u64::from(t));
        }
    };
    let (k0, k1) = span(w, lo[w], hi[w]);
    let (j0, j1) = span(v, lo[v], hi[v]);
    let (i0, i1) = span(u, lo[u], hi[u]);
    let count = |a: i64, b: i64| (b - a + 1).max(0);
    if count(k0, k1) * count(j0, j1) * count(i0, i1) <= SMALL_TRIANGLE_CELLS {
        // Small triangles (the common case): every cell of the bounding box.
        for k in k0..=k1 {
            for j in j0..=j1 {
                for i in i0..=i1 {
                    emit(k, j, i, out);
                }
            }
        }
        return;
    }
    let triangle = Polygon::triangle(corners);
    for k in k0..=k1 {
        let slab = triangle.clip(w, k as f64 - m, k as f64 + 1.0 + m);
        let Some((a, b)) = slab.range(v) else {
            continue;
        };
        let (j0, j1) = span(v, a, b);
        for j in j0..=j1 {
            let row = slab.clip(v, j as f64 - m, j as f64 + 1.0 + m);
            let Some((a, b)) = row.range(u) else {
                continue;
            };
            let (i0, i1) = span(u, a, b);
            for i in i0..=i1 {
                emit(k, j, i, out);
            }
        }
    }
}

/// The sort first distributes the keys into `2^BUCKET_BITS` buckets by the top bits of
/// their cell.
const BUCKET_BITS: u32 = 12;

/// Sorts the keys of `parts` (cell in the upper 32 bits, of which the lower `cell_bits`
/// are used, triangle below) into one array: one sequential pass distributes them into
/// buckets by the top bits of the cell, then the buckets are sorted in parallel. The
/// result is the keys in increasing order — by cell, then by triangle — whatever their
/// order on entry, so it does not depend on the number of threads.
pub(super) fn sort_by_cell(parts: Vec<Vec<u64>>, cell_bits: u32) -> Vec<u64> {
    let shift = 32 + cell_bits.saturating_sub(BUCKET_BITS);
    let bucket = |k: u64| bucket_of(k, shift);
    let mut starts = vec![0usize; (1 << BUCKET_BITS) + 1];
    for &k in parts.iter().flatten() {
        starts[bucket(k) + 1] += 1;
    }
    for i in 1..starts.len() {
        starts[i] += starts[i - 1];
    }
    let mut sorted = vec![0u64; starts[starts.len() - 1]];
    distribute(parts, &starts, shift, &mut sorted);
    let mut buckets: Vec<&mut [u64]> = Vec::with_capacity(1 << BUCKET_BITS);
    let mut rest: &mut [u64] = &mut sorted;
    for w in starts.windows(2) {
        let (head, tail) = rest.split_at_mut(w[1] - w[0]);
        buckets.push(head);
        rest = tail;
    }
    buckets.par_iter_mut().for_each(|b| b.sort_unstable());
    sorted
}

/// The bucket of `key` in [`sort_by_cell`]: the bits of its cell from `shift` on.
#[inline]
fn bucket_of(key: u64, shift: u32) -> usize {
    ((key >> shift) as usize) & ((1 << BUCKET_BITS) - 1)
}

/// Puts the keys of `parts` into `sorted`, each bucket's ([`bucket_of`]) from
/// `starts[bucket]` in the order of the parts: one pass with one thread; with more, one
/// pass per range of buckets, in parallel, each writing its own part of `sorted`.
fn distribute(parts: Vec<Vec<u64>>, starts: &[usize], shift: u32, sorted: &mut [u64]) {
    let bucket = |k: u64| bucket_of(k, shift);
    let groups = threads().clamp(1, 16);
    if groups == 1 {
        let mut fill = starts.to_vec();
        // Each part freed once distributed: the peak holds about one copy of the keys.
        for part in parts {
            for k in part {
                let at = &mut fill[bucket(k)];
                sorted[*at] = k;
                *at += 1;
            }
        }
        return;
    }
    let buckets = starts.len() - 1;
    let mut ranges: Vec<(usize, usize, &mut [u64])> = Vec::with_capacity(groups);
    let mut rest = sorted;
    for g in 0..groups {
        let (b0, b1) = (g * buckets / groups, (g + 1) * buckets / groups);
        let (head, tail) = rest.split_at_mut(starts[b1] - starts[b0]);
        ranges.push((b0, b1, head));
        rest = tail;
    }
    ranges.par_iter_mut().for_each(|(b0, b1, out)| {
        let base = starts[*b0];
        let mut fill: Vec<usize> = starts[*b0..*b1].iter().map(|s| s - base).collect();
        for &k in parts.iter().flatten() {
            let b = bucket(k);
            if (*b0..*b1).contains(&b) {
                out[fill[b - *b0]] = k;
                fill[b - *b0] += 1;
            }
        }
    });
}

/// Capacity of a clipped polygon. A convex polygon gains at most one corner per clipping
/// plane (three corners plus four planes); rounding can in principle add more, in which
/// case the clip returns its input, which is a superset and so still safe.
const POLYGON_CAPACITY: usize = 12;

/// A small convex polygon (cell units), for clipping.
#[derive(Clone, Copy)]
struct Polygon {
    corners: [DVec3; POLYGON_CAPACITY],
    len: usize,
}

impl Polygon {
    fn triangle(t: [DVec3; 3]) -> Polygon {
        let mut corners = [DVec3::ZERO; POLYGON_CAPACITY];
        corners[..3].copy_from_slice(&t);
        Polygon { corners, len: 3 }
    }

    /// The part of the polygon with `lo ≤ p[axis] ≤ hi`.
    fn clip(&self, axis: usize, lo: f64, hi: f64) -> Polygon {
        self.clip_half(axis, lo, 1.0).clip_half(axis, hi, -1.0)
    }

    /// The part with `sign · (p[axis] − bound) ≥ 0` (Sutherland–Hodgman).
    fn clip_half(&self, axis: usize, bound: f64, sign: f64) -> Polygon {
        let mut out = Polygon {
            corners: [DVec3::ZERO; POLYGON_CAPACITY],
            len: 0,
        };
        let n = self.len;
        for i in 0..n {
            let (a, b) = (self.corners[i], self.corners[(i + 1) % n]);
            let (da, db) = (sign * (a[axis] - bound), sign * (b[axis] - bound));
            if da >= 0.0 && !out.push(a) {
                return *self;
            }
            if (da >= 0.0) != (db >= 0.0) {
                let mut q = a + (b - a) * (da / (da - db));
                q[axis] = bound;
                if !out.push(q) {
                    return *self;
                }
            }
        }
        out
    }

    fn push(&mut self, p: DVec3) -> bool {
        match self.corners.get_mut(self.len) {
            Some(slot) => {
                *slot = p;
                self.len += 1;
                true
            }
            None => false,
        }
    }

    /// The span `(min, max)` of the corners along `axis`, or `None` when empty.
    fn range(&self, axis: usize) -> Option<(f64, f64)> {
        let mut it = self.corners[..self.len].iter().map(|p| p[axis]);
        let first = it.next()?;
        Some(it.fold((first, first), |(a, b), x| (a.min(x), b.max(x))))
    }
}
