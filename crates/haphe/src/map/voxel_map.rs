//! Sparse storage of the voxel map: a dense array over bricks of 8×8×8 cells, each brick
//! either uniform (one state and a clearance bound for all its cells) or detailed.

use super::free_space::FreeRegions;
use super::grid::Grid;
use super::provenance::Provenance;
use super::{CellSizeRule, CellState};
use crate::array::Array;

/// Cells along each side of a brick: `2^BRICK_BITS`.
pub(crate) const BRICK_BITS: u32 = 3;
/// Cells along each side of a brick.
pub(crate) const BRICK_SIDE: u32 = 1 << BRICK_BITS;
/// Cells in a brick.
pub(crate) const BRICK_CELLS: usize = 1 << (3 * BRICK_BITS);
/// Largest number of bricks in a grid (2²³, so 2³² cells): a brick-major cell key then fits
/// in 32 bits, and the top-level array in 32 MiB.
pub const MAX_BRICKS: u64 = 1 << 23;

/// A top-level entry with this bit set is a uniform brick (one state for all its cells,
/// no surface cell): `UNIFORM | state << 24 | clearance`, or, with [`GRADED`] set too,
/// `UNIFORM | GRADED | state << 24 | index` where `index` names the brick's per-cell
/// clearances in `VoxelMap::clearances`. Without [`UNIFORM`], the entry is the index of a
/// detailed brick.
pub(crate) const UNIFORM: u32 = 1 << 31;
/// See [`UNIFORM`].
pub(crate) const GRADED: u32 = 1 << 30;
/// Where a uniform entry keeps its state (two bits).
pub(crate) const UNIFORM_STATE_SHIFT: u32 = 24;
/// The low bits of a uniform entry: a reach or a clearance-brick index.
pub(crate) const UNIFORM_PAYLOAD: u32 = (1 << UNIFORM_STATE_SHIFT) - 1;
/// The largest reach a uniform entry stores, in cells: the [`VoxelMap::reach`] of all its
/// cells.
pub(crate) const MAX_REACH: u32 = UNIFORM_PAYLOAD;
/// Bytes of per-cell clearances of one brick: a nibble per cell.
pub(crate) const NIBBLE_BYTES: usize = BRICK_CELLS / 2;
/// Words of a brick's bit mask.
pub(crate) const MASK_WORDS: usize = BRICK_CELLS / 64;

/// One bit per cell of a brick: cell `local` is bit `local % 64` of word `local / 64`
/// (word `z`, bit `8·y + x`).
pub(crate) type BrickBits = [u64; MASK_WORDS];

/// Whether cell `local` is set in `bits`.
#[inline]
pub(crate) fn has(bits: &BrickBits, local: usize) -> bool {
    bits[local >> 6] >> (local & 63) & 1 != 0
}

/// A uniform top-level entry with one reach for all cells (see [`MAX_REACH`]).
#[inline]
pub(crate) fn uniform_entry(state: CellState, reach: u32) -> u32 {
    UNIFORM | ((state as u32) << UNIFORM_STATE_SHIFT) | reach.min(MAX_REACH)
}

/// A uniform top-level entry whose per-cell clearances are clearance brick `index`.
#[inline]
pub(crate) fn graded_entry(state: CellState, index: u32) -> u32 {
    UNIFORM | GRADED | ((state as u32) << UNIFORM_STATE_SHIFT) | (index & UNIFORM_PAYLOAD)
}

/// The clearance of cell `local` of clearance brick `brick` in `nibbles` (0 when out of
/// range).
#[inline]
pub(crate) fn nibble(nibbles: &[u8], brick: usize, local: usize) -> u8 {
    nibbles
        .get(brick * NIBBLE_BYTES + (local >> 1))
        .map_or(0, |&b| (b >> ((local & 1) * 4)) & 0xf)
}

/// The state of a uniform entry.
#[inline]
pub(crate) fn entry_state(entry: u32) -> CellState {
    match (entry >> UNIFORM_STATE_SHIFT) & 0x3 {
        0 => CellState::Outside,
        1 => CellState::Inside,
        _ => CellState::Surface,
    }
}

/// Number of bricks along each axis for a grid of `dims` cells.
pub(crate) fn brick_dims(dims: [u32; 3]) -> [u32; 3] {
    dims.map(|d| d.div_ceil(BRICK_SIDE))
}

/// The index of the brick holding cell `c` in the top-level array (x fastest).
#[inline]
pub(crate) fn brick_of(c: [u32; 3], brick_dims: [u32; 3]) -> usize {
    let [bx, by, _] = brick_dims.map(|d| d as usize);
    let [x, y, z] = c.map(|v| (v >> BRICK_BITS) as usize);
    (z * by + y) * bx + x
}

/// The index of cell `c` within its brick (x fastest, then y, then z).
#[inline]
pub(crate) fn local_of(c: [u32; 3]) -> usize {
    let m = BRICK_SIDE - 1;
    (((c[2] & m) << (2 * BRICK_BITS)) | ((c[1] & m) << BRICK_BITS) | (c[0] & m)) as usize
}

/// The brick coordinates of brick index `b`.
#[inline]
pub(crate) fn brick_coords(b: usize, brick_dims: [u32; 3]) -> [u32; 3] {
    let [bx, by, _] = brick_dims.map(|d| d as usize);
    [
        (b % bx) as u32,
        ((b / bx) % by) as u32,
        (b / (bx * by)) as u32,
    ]
}

/// The grid coordinates of cell `local` of the brick at brick coordinates `bc`.
#[inline]
pub(crate) fn cell_in_brick(bc: [u32; 3], local: usize) -> [u32; 3] {
    let l = local as u32;
    let m = BRICK_SIDE - 1;
    [
        (bc[0] << BRICK_BITS) | (l & m),
        (bc[1] << BRICK_BITS) | ((l >> BRICK_BITS) & m),
        (bc[2] << BRICK_BITS) | (l >> (2 * BRICK_BITS)),
    ]
}

/// The voxel map of one object: a uniform [`Grid`] whose cells are outside, inside or on
/// the surface, with the triangles of each surface cell and the clearance of the others.
///
/// Invariants (established by [`VoxelMap::build`] and checked by
/// [`decode`](super::decode)):
/// - every cell outside the grid, and every padding cell (the outer layer), is
///   [`CellState::Outside`]; so is every point outside the grid box;
/// - a cell is [`CellState::Surface`] exactly when at least one triangle overlaps it
///   (enlarged by `OVERLAP_TOLERANCE_REL`), and
///   [`triangles_in`](VoxelMap::triangles_in) lists every such triangle once, ordered along
///   the direction of the cell's slab (by the height of their centroids, then by index;
///   the order a segment crossing the cell that way meets them); other cells list none;
/// - for a solid surface ([`Surface::is_solid`](crate::mesh::Surface::is_solid)),
///   non-surface cells connected to the padding through face-adjacent non-surface cells
///   are outside; every other connected region of non-surface cells is inside, unless
///   the generalised winding number at its first cell says it is outside space (a cavity,
///   or a pocket closed off at the grid's resolution) — checked for as many regions as
///   about 33 million triangle evaluations allow, which covers every ordinary solid; for
///   any other surface no cell is inside;
/// - [`clearance`](VoxelMap::clearance) of a non-surface cell is `k ≥ 1` such that every
///   cell at Chebyshev distance below `k` (in cells) is a non-surface cell. It is exactly
///   the Chebyshev distance to the nearest surface cell, capped at `MAX_CLEARANCE`, in
///   every brick that holds a surface cell or touches one (faces, edges or corners); in
///   bricks farther away, where every cell is at least 9 cells from the surface, it is the
///   smallest clearance of the brick's cells.
///
/// # Layout and memory
/// Bricks of 8×8×8 cells, one `u32` entry each in a dense array (x fastest):
/// - a **detailed** brick (one holding a surface cell) stores a bit mask of its surface
///   cells and one of its inside cells (64 bytes each), a clearance nibble per cell (256
///   bytes), the number of surface cells before each mask word (16 bytes) and its slab
///   (4 bytes, see `map/slabs.rs`); its surface cells, ranked in cell order, index a start
///   offset and a slab each (4 bytes each) and the start offsets index one array of
///   triangle indices (4 bytes each);
/// - a **graded** brick (uniform, touching a detailed brick) stores a clearance nibble per
///   cell: 256 bytes;
/// - any other brick is **uniform**: state and reach live in the entry itself;
/// - each region of 4×4×4 bricks has a slab (4 bytes);
/// - besides, one byte per brick, derived from the entries when the map is built or
///   loaded (not saved): how many bricks around it hold no surface cell, which a long
///   segment's walk reads instead of the entries and clearances to cross free space.
///
/// Space far from the surface costs half a byte per thousand cells.
#[derive(Debug, Clone, PartialEq)]
pub struct VoxelMap {
    pub(crate) grid: Grid,
    pub(crate) brick_dims: [u32; 3],
    /// One entry per brick: [`UNIFORM`]-tagged (possibly [`GRADED`]) or a detailed brick
    /// index.
    pub(crate) bricks: Array<u32>,
    /// Per detailed brick: its surface cells.
    pub(crate) surface_bits: Array<BrickBits>,
    /// Per detailed brick: its inside cells (never surface cells).
    pub(crate) inside_bits: Array<BrickBits>,
    /// The bricks (top-level indices, increasing) holding inside cells whose winding
    /// number is not 1: where closed parts overlap (2 or more), or inside an inside-out
    /// part (−1). Empty for an ordinary solid.
    pub(crate) overlap_bricks: Array<u32>,
    /// Per brick of `overlap_bricks`: those cells (a subset of its inside cells).
    pub(crate) overlap_bits: Array<BrickBits>,
    /// Per detailed brick: surface cells in the mask words before each word.
    pub(crate) surface_before: Array<[u16; MASK_WORDS]>,
    /// Per detailed brick (plus one): the index of its first surface cell.
    pub(crate) surface_first: Array<u32>,
    /// [`NIBBLE_BYTES`] per clearance brick: the detailed bricks (same index), then the
    /// graded ones. A cell's clearance is a nibble (cell `l` in byte `l / 2`, low nibble
    /// first); 0 for a surface cell.
    pub(crate) clearances: Array<u8>,
    /// Per surface cell (plus one): where its triangles start in `triangle_refs`.
    pub(crate) triangle_start: Array<u32>,
    /// Triangle indices of all surface cells, cell after cell.
    pub(crate) triangle_refs: Array<u32>,
    /// Per brick: how far around it, in bricks, no brick holds a surface cell — 0 for a
    /// detailed brick, `d ≥ 1` when no brick within Chebyshev distance `d − 1` of it
    /// (itself included) holds one (see
    /// [`free_bricks_of`](super::free_space::free_bricks_of)). Derived from `bricks` when
    /// a map is built or loaded (not saved), a byte per brick, so that a long segment's
    /// walk crosses free space without reading the entries.
    pub(crate) free_bricks: Vec<u8>,
    /// The same bound by regions of 4×4×4 bricks, derived with `free_bricks`: 64 times
    /// smaller, so that crossing empty space far from the surface reads only the cache.
    pub(crate) free_regions: FreeRegions,
    /// Per surface cell: its slab, the layer of the cell in which its triangles lie
    /// (see `map/slabs.rs`).
    pub(crate) slabs: Array<u32>,
    /// Per detailed brick: its slab, the layer of the brick in which the triangles of
    /// its surface cells lie (see `map/slabs.rs`).
    pub(crate) brick_slabs: Array<u32>,
    /// Per region of 4×4×4 bricks (x fastest): its slab, the layer of the region in
    /// which the triangles of its surface cells lie, with bounds of 16 bits (see
    /// `map/slabs.rs`; a slab that rejects nothing for a region without surface cells).
    pub(crate) region_slabs: Array<u64>,
    /// Triangles of the surface the map was built for.
    pub(crate) triangle_count: u32,
    /// Whether inside cells were classified (the surface is a solid).
    pub(crate) solid: bool,
    /// How the cell size was chosen.
    pub(crate) cell_size_rule: CellSizeRule,
    /// The mesh file the map was built from, when its builder said
    /// ([`VoxelMap::with_provenance`]); saved and loaded with the map.
    pub(crate) provenance: Option<Box<Provenance>>,
}

/// A cell's brick, looked up once.
enum Slot {
    Uniform { entry: u32, local: usize },
    Detailed { brick: usize, local: usize },
}

impl VoxelMap {
    /// The map with `provenance` recorded: the mesh file it was built from, saved by
    /// [`encode`](super::encode) and read back by [`decode`](super::decode).
    pub fn with_provenance(mut self, provenance: Provenance) -> VoxelMap {
        self.provenance = Some(Box::new(provenance));
        self
    }

    /// The mesh file the map was built from, if recorded ([`VoxelMap::with_provenance`]).
    pub fn provenance(&self) -> Option<&Provenance> {
        self.provenance.as_deref()
    }

    /// The grid of the map (metres, object frame).
    #[inline]
    pub fn grid(&self) -> &Grid {
        &self.grid
    }

    #[inline]
    fn slot(&self, c: [u32; 3]) -> Option<Slot> {
        if !self.grid.contains(c) {
            return None;
        }
        let entry = *self.bricks.get(brick_of(c, self.brick_dims))?;
        let local = local_of(c);
        Some(if entry & UNIFORM != 0 {
            Slot::Uniform { entry, local }
        } else {
            Slot::Detailed {
                brick: entry as usize,
                local,
            }
        })
    }

    /// Whether cell `local` of detailed brick `brick` is a surface cell.
    #[inline]
    fn is_surface(&self, brick: usize, local: usize) -> bool {
        self.surface_bits.get(brick).is_some_and(|b| has(b, local))
    }

    /// The state of cell `c`; [`CellState::Outside`] for any index outside the grid.
    ///
    /// # Real-time
    /// Constant time (three array reads), no allocation, never panics.
    #[inline]
    pub fn state(&self, c: [u32; 3]) -> CellState {
        match self.slot(c) {
            None => CellState::Outside,
            Some(Slot::Uniform { entry, .. }) => entry_state(entry),
            Some(Slot::Detailed { brick, local }) => {
                if self.is_surface(brick, local) {
                    CellState::Surface
                } else if self.inside_bits.get(brick).is_some_and(|b| has(b, local)) {
                    CellState::Inside
                } else {
                    CellState::Outside
                }
            }
        }
    }

    /// Whether cell `c` is an inside cell whose winding number is not 1 (where closed parts
    /// overlap, or inside an inside-out part): inside under the non-zero rule like every
    /// inside cell, but not a reference of known winding for counting crossings.
    ///
    /// # Real-time
    /// Constant time for an ordinary solid (no such cell); otherwise a binary search over
    /// the bricks that hold such cells. No allocation, never panics.
    #[inline]
    pub fn is_overlap(&self, c: [u32; 3]) -> bool {
        if self.overlap_bricks.is_empty() || !self.grid.contains(c) {
            return false;
        }
        let b = brick_of(c, self.brick_dims) as u32;
        self.overlap_bricks
            .binary_search(&b)
            .ok()
            .and_then(|i| self.overlap_bits.get(i))
            .is_some_and(|bits| has(bits, local_of(c)))
    }

    /// The clearance of cell `c`, in cells: 0 for a surface cell and for any index outside
    /// the grid; otherwise `k` in `1..=MAX_CLEARANCE` such that every cell within
    /// Chebyshev distance `k − 1` of `c` is a non-surface cell. A point in `c` can therefore
    /// move by up to `(k − 1)` cell sizes along every axis (a cube of side `2k − 1` cells
    /// around `c`) without meeting a triangle.
    ///
    /// # Real-time
    /// Constant time (two array reads), no allocation, never panics.
    #[inline]
    pub fn clearance(&self, c: [u32; 3]) -> u8 {
        self.reach(c).min(u32::from(super::MAX_CLEARANCE)) as u8
    }

    /// How far free space reaches around cell `c`, in cells: 0 for a surface cell and for
    /// any index outside the grid; otherwise `k ≥ 1` such that every cell within Chebyshev
    /// distance `k − 1` of `c` is a non-surface cell, as for [`clearance`](Self::clearance),
    /// but without its cap. Where the clearance is below
    /// `MAX_CLEARANCE` the two are equal; farther from the surface,
    /// in bricks at least three bricks from any brick holding a surface cell, the reach is
    /// `8 (D − 1) + 1` for a brick `D` bricks from the nearest such brick (Chebyshev
    /// distance), so a segment crossing empty space skips it in a few strides however
    /// fine the grid.
    ///
    /// # Real-time
    /// Constant time (two array reads), no allocation, never panics.
    #[inline]
    pub fn reach(&self, c: [u32; 3]) -> u32 {
        match self.slot(c) {
            None => 0,
            Some(Slot::Uniform { entry, local }) => {
                Self::uniform_reach(&self.clearances, entry, local)
            }
            Some(Slot::Detailed { brick, local }) => {
                u32::from(nibble(&self.clearances, brick, local))
            }
        }
    }

    /// The reach of cell `local` of a uniform brick with top-level `entry`: its graded
    /// clearance nibble, or the entry's own reach.
    #[inline]
    fn uniform_reach(clearances: &[u8], entry: u32, local: usize) -> u32 {
        if entry & GRADED != 0 {
            u32::from(nibble(
                clearances,
                (entry & UNIFORM_PAYLOAD) as usize,
                local,
            ))
        } else {
            entry & UNIFORM_PAYLOAD
        }
    }

    /// The triangles (indices into the surface the map was built from) that overlap cell
    /// `c`, each once (ordered along the direction of the cell's slab, not by index);
    /// empty for a non-surface cell and for any index outside the grid.
    ///
    /// # Real-time
    /// Constant time (five array reads and a population count), no allocation, never
    /// panics.
    #[inline]
    pub fn triangles_in(&self, c: [u32; 3]) -> &[u32] {
        match self.slot(c) {
            Some(Slot::Detailed { brick, local }) => self.listed(brick, local).unwrap_or(&[]),
            _ => &[],
        }
    }

    /// The triangles of cell `local` of detailed brick `brick`: `None` when it is not a
    /// surface cell (or the brick is out of range).
    #[inline]
    pub(super) fn listed(&self, brick: usize, local: usize) -> Option<&[u32]> {
        self.listed_at(brick, local).map(|(t, _)| t)
    }

    /// [`listed`](Self::listed) with the surface cell's index.
    #[inline]
    pub(super) fn listed_at(&self, brick: usize, local: usize) -> Option<(&[u32], usize)> {
        let (word, bit) = (local >> 6, local & 63);
        let mask = self.surface_bits.get(brick)?[word];
        if mask >> bit & 1 == 0 {
            return None;
        }
        let first = *self.surface_first.get(brick)?;
        let before = self.surface_before.get(brick)?[word];
        let rank = usize::from(before) + (mask & ((1u64 << bit) - 1)).count_ones() as usize;
        let s = first as usize + rank;
        let (a, b) = (
            *self.triangle_start.get(s)?,
            *self.triangle_start.get(s + 1)?,
        );
        Some((
            self.triangle_refs
                .get(a as usize..b as usize)
                .unwrap_or(&[]),
            s,
        ))
    }

    /// Number of triangles of the surface the map was built for.
    #[inline]
    pub fn triangle_count(&self) -> usize {
        self.triangle_count as usize
    }

    /// Whether the map classifies inside cells (it was built for a solid surface); when
    /// not, every non-surface cell is outside (free space).
    #[inline]
    pub fn is_solid(&self) -> bool {
        self.solid
    }

    /// How the cell size was chosen.
    #[inline]
    pub fn cell_size_rule(&self) -> CellSizeRule {
        self.cell_size_rule
    }

    /// Bytes of heap memory the map holds.
    pub fn heap_bytes(&self) -> usize {
        self.bricks.heap_bytes()
            + self.free_bricks.capacity()
            + self.free_regions.heap_bytes()
            + self.surface_bits.heap_bytes()
            + self.inside_bits.heap_bytes()
            + self.overlap_bricks.heap_bytes()
            + self.overlap_bits.heap_bytes()
            + self.surface_before.heap_bytes()
            + self.surface_first.heap_bytes()
            + self.clearances.heap_bytes()
            + self.triangle_start.heap_bytes()
            + self.triangle_refs.heap_bytes()
            + self.slabs.heap_bytes()
            + self.brick_slabs.heap_bytes()
            + self.region_slabs.heap_bytes()
    }

    /// Number of detailed bricks.
    pub(crate) fn detailed_count(&self) -> usize {
        self.surface_bits.len()
    }

    /// Size and occupancy figures of the map.
    ///
    /// # Performance
    /// Linear in the number of bricks; not for a servo tick.
    pub fn stats(&self) -> MapStats {
        let grid = &self.grid;
        let (mut inside, mut outside) = (0u64, 0u64);
        for (b, &entry) in self.bricks.iter().enumerate() {
            let in_grid = in_grid_bits(brick_coords(b, self.brick_dims), grid.dims());
            let cells: u64 = in_grid.iter().map(|w| u64::from(w.count_ones())).sum();
            if entry & UNIFORM != 0 {
                match entry_state(entry) {
                    CellState::Inside => inside += cells,
                    _ => outside += cells,
                }
            } else {
                let d = entry as usize;
                let count = |bits: Option<&BrickBits>| -> u64 {
                    bits.map_or(0, |bits| {
                        bits.iter().map(|w| u64::from(w.count_ones())).sum()
                    })
                };
                let (surface, inner) = (
                    count(self.surface_bits.get(d)),
                    count(self.inside_bits.get(d)),
                );
                inside += inner;
                outside += cells.saturating_sub(surface + inner);
            }
        }
        let surface_cells = self.triangle_start.len().saturating_sub(1) as u64;
        let max_per_cell = self
            .triangle_start
            .windows(2)
            .map(|w| w[1] - w[0])
            .max()
            .unwrap_or(0);
        let refs = self.triangle_refs.len() as u64;
        let detailed = self.detailed_count() as u64;
        MapStats {
            dims: grid.dims(),
            cell_size_m: grid.cell_size(),
            cell_size_rule: self.cell_size_rule,
            cells: grid.cell_count(),
            surface_cells,
            inside_cells: inside,
            outside_cells: outside,
            triangle_refs: refs,
            mean_triangles_per_surface_cell: if surface_cells > 0 {
                refs as f64 / surface_cells as f64
            } else {
                0.0
            },
            max_triangles_per_surface_cell: max_per_cell,
            bricks: self.bricks.len() as u64,
            detailed_bricks: detailed,
            graded_bricks: (self.clearances.len() / NIBBLE_BYTES) as u64 - detailed,
            bytes: self.heap_bytes(),
        }
    }
}

/// The cells of the brick at brick coordinates `bc` that lie inside a grid of `dims` cells
/// (all of them except in the last brick along an axis whose size is not a multiple of 8).
pub(crate) fn in_grid_bits(bc: [u32; 3], dims: [u32; 3]) -> BrickBits {
    let count = |a: usize| dims[a].saturating_sub(bc[a] << BRICK_BITS).min(BRICK_SIDE);
    let (nx, ny, nz) = (count(0), count(1), count(2));
    let row: u64 = (1u64 << nx) - 1;
    let mut slice = 0u64;
    for y in 0..ny {
        slice |= row << (8 * y);
    }
    let mut bits = [0u64; MASK_WORDS];
    for (z, word) in bits.iter_mut().enumerate() {
        if (z as u32) < nz {
            *word = slice;
        }
    }
    bits
}

/// Size and occupancy figures of a [`VoxelMap`] ([`VoxelMap::stats`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MapStats {
    /// Cells along x, y and z (padding included).
    pub dims: [u32; 3],
    /// Cell edge length, metres.
    pub cell_size_m: f64,
    /// How the cell size was chosen.
    pub cell_size_rule: CellSizeRule,
    /// Total cells of the grid.
    pub cells: u64,
    /// Cells that list at least one triangle.
    pub surface_cells: u64,
    /// Non-surface cells inside the solid (0 for a surface that is not a solid).
    pub inside_cells: u64,
    /// Non-surface cells outside (free space).
    pub outside_cells: u64,
    /// (cell, triangle) pairs listed.
    pub triangle_refs: u64,
    /// Mean number of triangles listed per surface cell.
    pub mean_triangles_per_surface_cell: f64,
    /// Largest number of triangles listed in one cell: the worst-case number of triangle
    /// tests per cell a query visits.
    pub max_triangles_per_surface_cell: u32,
    /// Bricks of 8×8×8 cells in the top-level array.
    pub bricks: u64,
    /// Bricks stored cell by cell (those holding surface cells).
    pub detailed_bricks: u64,
    /// Uniform bricks that store a clearance per cell (those touching a detailed brick).
    pub graded_bricks: u64,
    /// Heap bytes of the map ([`VoxelMap::heap_bytes`]).
    pub bytes: usize,
}
