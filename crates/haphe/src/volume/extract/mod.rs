//! The iso-surface of a volume, extracted in chunks of [`Chunks::SIZE`]³ cells by marching
//! tetrahedra (see `tetra`), welded into one closed mesh.
//!
//! A cell is the cube of the eight voxels from `(i, j, k)` to `(i + 1, j + 1, k + 1)`.
//! The cells run from −1 to `n − 1` along an axis of `n` voxels: one beyond the grid on
//! each side, where the value is air, so that material touching the grid's border is
//! closed there. Chunk `c` along an axis holds the cells `32c − 1 .. 32c + 31` (fewer in
//! the last).

impl Volume {
    /// The shape of the iso-surface, as a servo loop renders it: every chunk extracted
    /// ([`Chunks::extract`]), welded into one mesh and made a shape as
    /// [`Shape::from_mesh`] makes one (surface, map, clear zones), its map's cells one
    /// voxel wide unless `options` set their size. `name` is in the errors.
    ///
    /// # Errors
    /// Those of [`Shape::from_mesh`]: [`ShapeError::Surface`] when no voxel is material
    /// (no triangle), [`ShapeError::Map`] when the map cannot be built.
    pub fn shape(&self, name: &str, options: &MapOptions) -> Result<Shape, ShapeError> {
        Shape::from_mesh(
            name,
            Chunks::extract(self).mesh(),
            &self.map_options(options),
        )
    }
}

#[cfg(test)]
mod tests;
mod tetra;

use glam::DVec3;
use rustc_hash::FxHashMap;

use super::Volume;
use crate::map::MapOptions;
use crate::mesh::Mesh;
use crate::par::*;
use crate::scene::{Shape, ShapeError};
use tetra::{CASES, TETRAHEDRA, crossing};

/// The iso-surface of a [`Volume`] in chunks of [`Chunks::SIZE`]³ cells: each chunk's
/// triangles with its own vertices, and the grid of chunks, so that a change to some
/// voxels re-extracts only the chunks they touch ([`Chunks::refresh`]).
///
/// Invariants: a vertex lies on an edge of the decomposition whose ends are one material
/// and one air voxel, at least 1/64 of the edge from either end, and its position is a
/// function of that edge's two voxels alone, so that chunks sharing a face have the same
/// vertices there, bit for bit. Triangles are counter-clockwise seen from the air side
/// (their normal `(b − a) × (c − a)` points from material to air, in metres). Taken
/// together ([`Chunks::mesh`]) the chunks make a closed, consistently oriented
/// 2-manifold without degenerate triangles.
#[derive(Debug, Clone)]
pub struct Chunks {
    /// The volume's voxels along each axis.
    dims: [usize; 3],
    /// Chunks along each axis.
    counts: [usize; 3],
    /// The chunks, `x` fastest.
    chunks: Vec<Chunk>,
}

/// One chunk's part of the surface.
#[derive(Debug, Clone, Default)]
struct Chunk {
    /// Each vertex's edge (see [`edge_key`]): the same edge in every chunk.
    keys: Vec<u64>,
    /// Vertex positions, metres (the volume's frame).
    vertices: Vec<DVec3>,
    /// Triangles as indices into `vertices`.
    triangles: Vec<[u32; 3]>,
    /// Each triangle's material value: the highest value at the corners of the
    /// tetrahedron it was made in (a material voxel's, as at least one corner is).
    values: Vec<f32>,
}

/// The edge from voxel `lo` along the offset bits `dir` (1 to 7), as a number unique in
/// the grid: the lower voxel's index in the grid grown by one voxel on every side, times
/// 8, plus `dir`.
#[inline]
fn edge_key(dims: [usize; 3], lo: [i64; 3], dir: u8) -> u64 {
    let [nx, ny, _] = dims.map(|d| d as u64 + 2);
    let [i, j, k] = lo.map(|c| (c + 1) as u64);
    ((i + nx * (j + ny * k)) << 3) | u64::from(dir)
}

/// The offset of cube corner `c` (bits `x + 2y + 4z`).
#[inline]
fn corner_offset(c: u8) -> [i64; 3] {
    [
        i64::from(c & 1),
        i64::from((c >> 1) & 1),
        i64::from((c >> 2) & 1),
    ]
}

impl Chunks {
    /// Cells along each axis of a chunk.
    pub const SIZE: usize = 32;

    /// Every chunk of `volume` extracted: the whole iso-surface. In parallel over chunks
    /// with the feature `parallel`, with the same result without it.
    ///
    /// # Performance
    /// Reads every voxel once (and those on chunk faces twice); a cell whose eight voxels
    /// are all material or all air costs a mask of eight comparisons.
    pub fn extract(volume: &Volume) -> Chunks {
        let dims = volume.dims();
        let counts = dims.map(|n| (n + 1).div_ceil(Chunks::SIZE));
        let total = counts.iter().product::<usize>();
        let chunks = (0..total)
            .into_par_iter()
            .map(|c| extract_chunk(volume, chunk_cells(dims, counts, c)))
            .collect();
        Chunks {
            dims,
            counts,
            chunks,
        }
    }

    /// Re-extracts the chunks whose cells touch a voxel in the box `lo..=hi` (voxel
    /// indices, inclusive; a voxel is a corner of the cells from `v − 1` to `v` along each
    /// axis, so a chunk is touched when its cells meet `lo − 1 ..= hi`); returns how many
    /// were re-extracted. Only those chunks' work is done. The box is clipped to the grid
    /// first (no value changes beyond it): a box wholly beyond the grid touches none.
    ///
    /// `volume` is the volume the chunks were extracted from, with some values changed;
    /// for a grid of other dimensions every chunk is extracted anew (and counted).
    pub fn refresh(&mut self, volume: &Volume, lo: [i64; 3], hi: [i64; 3]) -> usize {
        self.refreshed_chunks(volume, lo, hi).len()
    }

    /// [`Chunks::refresh`], returning which chunks it re-extracted (flat indices,
    /// increasing; every chunk for a grid of other dimensions).
    pub(crate) fn refreshed_chunks(
        &mut self,
        volume: &Volume,
        lo: [i64; 3],
        hi: [i64; 3],
    ) -> Vec<usize> {
        if volume.dims() != self.dims {
            *self = Chunks::extract(volume);
            return (0..self.chunk_count()).collect();
        }
        let touched = self.touched(lo, hi);
        let (dims, counts) = (self.dims, self.counts);
        let fresh: Vec<Chunk> = touched
            .par_iter()
            .map(|&c| extract_chunk(volume, chunk_cells(dims, counts, c)))
            .collect();
        for (&c, chunk) in touched.iter().zip(fresh) {
            self.chunks[c] = chunk;
        }
        touched
    }

    /// Where each chunk's triangles begin in [`Chunks::mesh`], and past the last one the
    /// triangle count.
    pub(crate) fn triangle_offsets(&self) -> Vec<usize> {
        std::iter::once(0)
            .chain(self.chunks.iter().scan(0, |at, c| {
                *at += c.triangles.len();
                Some(*at)
            }))
            .collect()
    }

    /// The chunks (flat indices, `x` fastest) whose cells meet `lo − 1 ..= hi`.
    fn touched(&self, lo: [i64; 3], hi: [i64; 3]) -> Vec<usize> {
        let size = Chunks::SIZE as i64;
        let mut range = [(0usize, 0usize); 3];
        for axis in 0..3 {
            // The grid's voxels in the box, `first..=last`, are corners of the cells
            // `first − 1 ..= last`; cell `c` is in chunk `(c + 1) / SIZE`.
            let first = lo[axis].max(0);
            let last = hi[axis].min(self.dims[axis] as i64 - 1);
            if first > last {
                return Vec::new();
            }
            range[axis] = ((first / size) as usize, ((last + 1) / size) as usize);
        }
        let [(x0, x1), (y0, y1), (z0, z1)] = range;
        let [cx, cy, _] = self.counts;
        (z0..=z1)
            .flat_map(|z| {
                (y0..=y1).flat_map(move |y| (x0..=x1).map(move |x| x + cx * (y + cy * z)))
            })
            .collect()
    }

    /// Every chunk's triangles as one mesh (metres, the volume's frame), the vertices that
    /// chunks share welded (by their edge, so each vertex once). Triangles in chunk order,
    /// each chunk's in the order it made them.
    pub fn mesh(&self) -> Mesh {
        let vertex_total: usize = self.chunks.iter().map(|c| c.vertices.len()).sum();
        let mut index: FxHashMap<u64, u32> =
            FxHashMap::with_capacity_and_hasher(vertex_total, Default::default());
        let mut mesh = Mesh {
            vertices: Vec::with_capacity(vertex_total),
            triangles: Vec::with_capacity(self.triangle_count()),
        };
        for chunk in &self.chunks {
            let global: Vec<u32> = chunk
                .keys
                .iter()
                .zip(&chunk.vertices)
                .map(|(&key, &p)| {
                    *index.entry(key).or_insert_with(|| {
                        mesh.vertices.push(p);
                        (mesh.vertices.len() - 1) as u32
                    })
                })
                .collect();
            mesh.triangles.extend(
                chunk
                    .triangles
                    .iter()
                    .map(|t| t.map(|v| global[v as usize])),
            );
        }
        mesh
    }

    /// Each triangle's material value, in the order of [`Chunks::mesh`]'s triangles: the
    /// highest value at the corners of the tetrahedron of the decomposition the triangle
    /// cuts, so the value of the material beside it (the voxels a cut removed are below
    /// iso).
    pub fn triangle_values(&self) -> Vec<f32> {
        self.chunks
            .iter()
            .flat_map(|c| c.values.iter().copied())
            .collect()
    }

    /// Triangles of every chunk.
    pub fn triangle_count(&self) -> usize {
        self.chunks.iter().map(|c| c.triangles.len()).sum()
    }

    /// Chunks in the grid of chunks (also the empty ones).
    pub fn chunk_count(&self) -> usize {
        self.chunks.len()
    }

    /// Chunks along each axis.
    pub fn chunks_per_axis(&self) -> [usize; 3] {
        self.counts
    }
}

/// The cells of chunk `c` (flat, `x` fastest): the first, and one past the last, along
/// each axis.
fn chunk_cells(dims: [usize; 3], counts: [usize; 3], c: usize) -> [[i64; 3]; 2] {
    let at = [
        c % counts[0],
        (c / counts[0]) % counts[1],
        c / (counts[0] * counts[1]),
    ];
    let size = Chunks::SIZE as i64;
    let lo = at.map(|a| a as i64 * size - 1);
    let hi = [0, 1, 2].map(|k| (lo[k] + size).min(dims[k] as i64));
    [lo, hi]
}

/// The values of the voxels at the corners of the cells `lo..hi`: `lo ..= hi` along each
/// axis, `x` fastest, `-inf` beyond the grid.
struct Block {
    lo: [i64; 3],
    size: [usize; 3],
    values: Vec<f32>,
}

impl Block {
    fn read(volume: &Volume, [lo, hi]: [[i64; 3]; 2]) -> Block {
        let size = [0, 1, 2].map(|k| (hi[k] - lo[k] + 1) as usize);
        let mut values = Vec::with_capacity(size.iter().product());
        for k in 0..size[2] as i64 {
            for j in 0..size[1] as i64 {
                for i in 0..size[0] as i64 {
                    values.push(volume.value(lo[0] + i, lo[1] + j, lo[2] + k));
                }
            }
        }
        Block { lo, size, values }
    }

    /// The flat index of local voxel `(i, j, k)`.
    #[inline]
    fn at(&self, [i, j, k]: [usize; 3]) -> usize {
        i + self.size[0] * (j + self.size[1] * k)
    }
}

/// A chunk being made: its vertices by edge.
struct ChunkBuilder<'v> {
    volume: &'v Volume,
    /// Whether the affine mirrors (a negative determinant): then every triangle is
    /// turned over to stay counter-clockwise seen from the air in metres.
    mirrored: bool,
    by_key: FxHashMap<u64, u32>,
    chunk: Chunk,
}

impl ChunkBuilder<'_> {
    /// The vertex on the edge from cell corner `a` to corner `b` of the cell at voxel
    /// `cell`, whose values are `va` and `vb`; made the first time it is asked for.
    #[inline]
    fn vertex(&mut self, cell: [i64; 3], (a, va): (u8, f32), (b, vb): (u8, f32)) -> u32 {
        // The lower corner's bits are a subset of the upper's (see `tetra`).
        let ((lo, v_lo), (hi, v_hi)) = if a < b {
            ((a, va), (b, vb))
        } else {
            ((b, vb), (a, va))
        };
        let off = corner_offset(lo);
        let p = [cell[0] + off[0], cell[1] + off[1], cell[2] + off[2]];
        let dir = lo ^ hi;
        let key = edge_key(self.volume.dims(), p, dir);
        let chunk = &mut self.chunk;
        let volume = self.volume;
        *self.by_key.entry(key).or_insert_with(|| {
            let s = crossing(v_lo, v_hi, volume.iso());
            let d = corner_offset(dir).map(|c| c as f64 * s);
            chunk.keys.push(key);
            chunk.vertices.push(volume.point(
                p[0] as f64 + d[0],
                p[1] as f64 + d[1],
                p[2] as f64 + d[2],
            ));
            (chunk.vertices.len() - 1) as u32
        })
    }

    /// The triangles of the cell at voxel `cell` whose corner values are `corners`
    /// (numbered by offset bits) and material mask `mask`.
    fn cell(&mut self, cell: [i64; 3], corners: [f32; 8], mask: u8) {
        for tet in TETRAHEDRA {
            let case_mask =
                (0..4).fold(0usize, |m, v| m | (usize::from((mask >> tet[v]) & 1) << v));
            let case = CASES[case_mask];
            let value = tet
                .iter()
                .map(|&c| corners[usize::from(c)])
                .fold(f32::NEG_INFINITY, f32::max);
            for tri in &case.triangles[..usize::from(case.count)] {
                let mut ids = tri.map(|[a, b]| {
                    let (a, b) = (tet[usize::from(a)], tet[usize::from(b)]);
                    self.vertex(
                        cell,
                        (a, corners[usize::from(a)]),
                        (b, corners[usize::from(b)]),
                    )
                });
                if self.mirrored {
                    ids.swap(1, 2);
                }
                self.chunk.triangles.push(ids);
                self.chunk.values.push(value);
            }
        }
    }
}

/// The part of the surface in the cells `lo..hi` of `volume`.
fn extract_chunk(volume: &Volume, cells: [[i64; 3]; 2]) -> Chunk {
    let block = Block::read(volume, cells);
    let iso = volume.iso();
    let material = block.values.iter().filter(|&&v| v >= iso).count();
    if material == 0 || material == block.values.len() {
        return Chunk::default();
    }
    let mut builder = ChunkBuilder {
        volume,
        mirrored: volume.to_world().matrix3.determinant() < 0.0,
        by_key: FxHashMap::default(),
        chunk: Chunk::default(),
    };
    let [sx, sy, sz] = block.size;
    for k in 0..sz - 1 {
        for j in 0..sy - 1 {
            for i in 0..sx - 1 {
                let mut corners = [0.0f32; 8];
                let mut mask = 0u8;
                for (c, value) in corners.iter_mut().enumerate() {
                    let [dx, dy, dz] = corner_offset(c as u8).map(|o| o as usize);
                    *value = block.values[block.at([i + dx, j + dy, k + dz])];
                    mask |= u8::from(*value >= iso) << c;
                }
                if mask != 0 && mask != 0xff {
                    let at = [i as i64, j as i64, k as i64];
                    let cell = [0, 1, 2].map(|a| block.lo[a] + at[a]);
                    builder.cell(cell, corners, mask);
                }
            }
        }
    }
    builder.chunk
}
