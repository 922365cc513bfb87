//! Saving and loading a surface with its voxel map: one checked, sectioned file.
//!
//! # Layout (format version 12, all numbers little-endian)
//!
//! | bytes | content |
//! |---|---|
//! | 0..8 | [`MAGIC`], `"HAPHEMAP"` |
//! | 8..12 | format version, `u32` ([`FORMAT_VERSION`]) |
//! | 12..16 | number of sections, `u32` |
//! | 16..24 | total file length in bytes, `u64` |
//! | 24..56 | reserved, zero |
//! | 56..64 | checksum, `u64`: XXH3-64 of bytes `0..56` followed by the XXH3-64 (`u64`) of each 4 MiB chunk of bytes `64..end` |
//! | 64.. | section table: per section `kind: u32`, `element size: u32`, `offset: u64`, `length in bytes: u64`, `reserved: u64` |
//! | … | the sections, each starting at a multiple of 64 bytes, zero padding between |
//!
//! The sections, in this order: the mesh report (JSON), vertices (`3 × f64` each),
//! triangles (`3 × u32`), neighbours (`3 × u32`), barycentric frames (`12 × f64`), corner
//! normals (`9 × f32`), fan starts and fan triangles (`u32`), each triangle's index in the
//! mesh the surface was built from (`u32`, [`Surface::source_triangle`]), the map parameters
//! (grid, counts, how the cell size was chosen), the brick entries (`u32`), the surface and
//! inside masks of the detailed bricks (`8 × u64` each), the bricks holding inside cells
//! whose winding number is not 1 (`u32`, increasing) and those cells' masks (`8 × u64`
//! each; both empty for an ordinary solid), the detailed bricks' surface counts per mask
//! word (`8 × u16`) and first surface cells (`u32`), the clearance nibbles of detailed then
//! graded bricks (256 bytes each), the triangle start of each surface cell (`u32`), the
//! triangle references (`u32`; each cell's list ordered along its slab's direction), the
//! slab of each surface cell (`u32`), of each detailed brick (`u32`) and of each region of
//! 4×4×4 bricks (`u64`), and the provenance: the source mesh file's name, size and
//! XXH3-128 hash (JSON, [`Provenance`]; empty when the map records none).
//!
//! Every section starts at a multiple of 64 bytes, so on a little-endian machine a loaded
//! surface and map use their arrays in place, as views of the one buffer the file was read
//! or mapped into ([`decode_in_place`]): loading copies nothing and recomputes nothing. It
//! checks the checksum first (the chunks in parallel), then every invariant a query relies
//! on, so a damaged or crafted file is refused with an error and can never cause a panic
//! or an out-of-bounds index later.

use std::ops::Range;

use crate::par::*;
use bytemuck::Pod;
use glam::DVec3;

use super::file_error::{MapFileError, invalid};
use super::params::{MapParams, map_params_bytes, parse_map_params};
use super::provenance::Provenance;
use super::validate::{check_map, check_surface};
use super::voxel_map::{BrickBits, MASK_WORDS, VoxelMap};
use crate::array::{Array, MapBytes};
use crate::mesh::{
    MeshReport, OwnedSurfaceParts, Surface, SurfaceParts, SurfacePartsRef, TriFrame,
};

/// The first eight bytes of a map file.
pub const MAGIC: [u8; 8] = *b"HAPHEMAP";

/// The format version this build writes and reads. Files of any other version are refused
/// ([`MapFileError::UnsupportedVersion`]): rebuild the map from the mesh.
///
/// Version 11 lists the inside cells where closed parts overlap, which the inside query
/// needs for the non-zero winding rule near the surfaces between them; version 12 records
/// the source mesh file ([`Provenance`]). Maps of earlier versions are refused.
pub const FORMAT_VERSION: u32 = 12;

/// Bytes of the fixed header.
const HEADER_BYTES: usize = 64;
/// Where the checksum is stored in the header.
pub(super) const CHECKSUM_AT: usize = 56;
/// Sections start at multiples of this many bytes.
const SECTION_ALIGN: usize = 64;
/// Bytes of one section-table entry.
const TABLE_ENTRY_BYTES: usize = 32;
/// The checksum hashes the body in chunks of this many bytes (in parallel), then the
/// chunks' hashes.
const CHECKSUM_CHUNK_BYTES: usize = 4 << 20;

/// Whether `head`, the first bytes of a file of `len` bytes (at least the first 64 when the
/// file has them), is the header of a map file, even a damaged one: at least five of the
/// eight magic bytes (`HAPHEMAP`) in place, or the rest of a map header intact (the section
/// count, the file's length and the reserved zeros). A mesh file never passes by chance:
/// its first bytes are text or an STL header, and no STL has this section count, its own
/// length and 32 zero bytes at these offsets.
pub fn looks_like_map(head: &[u8], len: u64) -> bool {
    let in_place = head.iter().zip(&MAGIC).filter(|(a, b)| a == b).count();
    if in_place >= 5 {
        return true;
    }
    head.len() >= HEADER_BYTES
        && u32_at(head, 12) as usize == SECTIONS.len()
        && u64_at(head, 16) == len
        && head[24..CHECKSUM_AT].iter().all(|&b| b == 0)
}

/// The sections in file order: name and element size in bytes.
const SECTIONS: [(&str, usize); 24] = [
    ("report", 1),
    ("vertices", 24),
    ("triangles", 12),
    ("neighbours", 12),
    ("frames", 96),
    ("corner normals", 36),
    ("fan starts", 4),
    ("fan triangles", 4),
    ("source triangles", 4),
    ("map parameters", 1),
    ("bricks", 4),
    ("surface masks", 64),
    ("inside masks", 64),
    ("overlap bricks", 4),
    ("overlap masks", 64),
    ("surface counts", 16),
    ("surface firsts", 4),
    ("clearances", 1),
    ("triangle starts", 4),
    ("triangle references", 4),
    ("slabs", 4),
    ("brick slabs", 4),
    ("region slabs", 8),
    ("provenance", 1),
];

/// A little-endian word of an array.
trait Word: Pod {
    fn le(self) -> Self;
}

impl Word for u8 {
    #[inline]
    fn le(self) -> Self {
        self
    }
}

impl Word for u16 {
    #[inline]
    fn le(self) -> Self {
        self.to_le()
    }
}

impl Word for u32 {
    #[inline]
    fn le(self) -> Self {
        self.to_le()
    }
}

impl Word for u64 {
    #[inline]
    fn le(self) -> Self {
        self.to_le()
    }
}

/// Appends `data` as little-endian words `W` (a no-op conversion on little-endian hosts).
fn put<T: Pod, W: Word>(out: &mut Vec<u8>, data: &[T]) {
    if cfg!(target_endian = "little") {
        out.extend_from_slice(bytemuck::cast_slice(data));
    } else {
        for &w in bytemuck::cast_slice::<T, W>(data) {
            out.extend_from_slice(bytemuck::bytes_of(&w.le()));
        }
    }
}

/// Copies little-endian words `W` out of `bytes` into a vector of `T` (one copy, any
/// alignment). `bytes.len()` must be a multiple of `size_of::<T>()` (checked by the caller).
fn take<T: Pod, W: Word>(bytes: &[u8]) -> Vec<T> {
    let mut v: Vec<T> = bytemuck::pod_collect_to_vec(bytes);
    if cfg!(target_endian = "big") {
        for w in bytemuck::cast_slice_mut::<T, W>(&mut v) {
            *w = w.le();
        }
    }
    v
}

/// Writes `surface` and its `map` (built from it) into one file.
///
/// The map must have been built from this surface; a file pairing a map with another
/// surface is refused by [`decode`].
///
/// # Performance
/// One pass over the arrays plus a checksum, at memory speed. About 190 bytes per
/// triangle for the surface (the barycentric frames, 96, and the shading normals, 36,
/// dominate) plus the map's 40 to 60.
///
/// # Examples
/// ```
/// use haphe::map::{decode, encode, MapOptions, VoxelMap};
/// use haphe::mesh::{shapes, Surface, SurfaceOptions};
/// let surface = Surface::new(shapes::torus(0.07, 0.03, 24, 12), &SurfaceOptions::default()).unwrap();
/// let map = VoxelMap::build(&surface, &MapOptions::default()).unwrap();
/// let bytes = encode(&surface, &map);
/// let (surface2, map2) = decode(&bytes).unwrap();
/// assert_eq!(map2, map);
/// assert_eq!(surface2.vertices(), surface.vertices());
/// ```
pub fn encode(surface: &Surface, map: &VoxelMap) -> Vec<u8> {
    let parts = surface.parts();
    let report = serde_json::to_vec(&parts.report).unwrap_or_default();
    let params = map_params_bytes(&MapParams::of(map));
    let provenance = map
        .provenance()
        .map(|p| serde_json::to_vec(p).unwrap_or_default())
        .unwrap_or_default();
    let lengths = section_lengths(&parts, map, [report.len(), params.len(), provenance.len()]);
    let table_end = HEADER_BYTES + SECTIONS.len() * TABLE_ENTRY_BYTES;
    let mut offsets = [0usize; SECTIONS.len()];
    let mut at = table_end.next_multiple_of(SECTION_ALIGN);
    for (offset, &len) in offsets.iter_mut().zip(&lengths) {
        *offset = at;
        at = (at + len).next_multiple_of(SECTION_ALIGN);
    }
    let total = at;

    let mut out = Vec::with_capacity(total);
    write_header(&mut out, &offsets, &lengths, total);
    let mut section = 0;
    let mut start = |out: &mut Vec<u8>| {
        out.resize(offsets[section], 0);
        section += 1;
    };
    start(&mut out);
    out.extend_from_slice(&report);
    start(&mut out);
    put::<DVec3, u64>(&mut out, parts.vertices);
    start(&mut out);
    put::<[u32; 3], u32>(&mut out, parts.triangles);
    start(&mut out);
    put::<[u32; 3], u32>(&mut out, parts.neighbours);
    start(&mut out);
    put::<TriFrame, u64>(&mut out, parts.frames);
    start(&mut out);
    put::<[[f32; 3]; 3], u32>(&mut out, parts.corner_normals);
    start(&mut out);
    put::<u32, u32>(&mut out, parts.fan_start);
    start(&mut out);
    put::<u32, u32>(&mut out, parts.fan_triangles);
    start(&mut out);
    put::<u32, u32>(&mut out, parts.source);
    start(&mut out);
    out.extend_from_slice(&params);
    start(&mut out);
    put::<u32, u32>(&mut out, &map.bricks);
    start(&mut out);
    put::<BrickBits, u64>(&mut out, &map.surface_bits);
    start(&mut out);
    put::<BrickBits, u64>(&mut out, &map.inside_bits);
    start(&mut out);
    put::<u32, u32>(&mut out, &map.overlap_bricks);
    start(&mut out);
    put::<BrickBits, u64>(&mut out, &map.overlap_bits);
    start(&mut out);
    put::<[u16; MASK_WORDS], u16>(&mut out, &map.surface_before);
    start(&mut out);
    put::<u32, u32>(&mut out, &map.surface_first);
    start(&mut out);
    out.extend_from_slice(&map.clearances);
    start(&mut out);
    put::<u32, u32>(&mut out, &map.triangle_start);
    start(&mut out);
    put::<u32, u32>(&mut out, &map.triangle_refs);
    start(&mut out);
    put::<u32, u32>(&mut out, &map.slabs);
    start(&mut out);
    put::<u32, u32>(&mut out, &map.brick_slabs);
    start(&mut out);
    put::<u64, u64>(&mut out, &map.region_slabs);
    start(&mut out);
    out.extend_from_slice(&provenance);
    out.resize(total, 0);
    let checksum = checksum(&out);
    out[CHECKSUM_AT..HEADER_BYTES].copy_from_slice(&checksum.to_le_bytes());
    out
}

/// The byte length of every section of the file of `parts` and `map`, with the lengths
/// of the report, the map parameters and the provenance, already serialised.
fn section_lengths(
    parts: &SurfacePartsRef<'_>,
    map: &VoxelMap,
    [report, params, provenance]: [usize; 3],
) -> [usize; SECTIONS.len()] {
    [
        report,
        parts.vertices.len() * 24,
        parts.triangles.len() * 12,
        parts.neighbours.len() * 12,
        parts.frames.len() * 96,
        parts.corner_normals.len() * 36,
        parts.fan_start.len() * 4,
        parts.fan_triangles.len() * 4,
        parts.source.len() * 4,
        params,
        map.bricks.len() * 4,
        map.surface_bits.len() * 64,
        map.inside_bits.len() * 64,
        map.overlap_bricks.len() * 4,
        map.overlap_bits.len() * 64,
        map.surface_before.len() * 16,
        map.surface_first.len() * 4,
        map.clearances.len(),
        map.triangle_start.len() * 4,
        map.triangle_refs.len() * 4,
        map.slabs.len() * 4,
        map.brick_slabs.len() * 4,
        map.region_slabs.len() * 8,
        provenance,
    ]
}

/// Writes the header and the section table of a file of `total` bytes whose sections lie
/// at `offsets` with `lengths` (the checksum field left zero).
fn write_header(
    out: &mut Vec<u8>,
    offsets: &[usize; SECTIONS.len()],
    lengths: &[usize; SECTIONS.len()],
    total: usize,
) {
    out.extend_from_slice(&MAGIC);
    out.extend_from_slice(&FORMAT_VERSION.to_le_bytes());
    out.extend_from_slice(&(SECTIONS.len() as u32).to_le_bytes());
    out.extend_from_slice(&(total as u64).to_le_bytes());
    out.resize(HEADER_BYTES, 0);
    for (kind, (&(_, elem), (&offset, &len))) in
        SECTIONS.iter().zip(offsets.iter().zip(lengths)).enumerate()
    {
        out.extend_from_slice(&(kind as u32).to_le_bytes());
        out.extend_from_slice(&(elem as u32).to_le_bytes());
        out.extend_from_slice(&(offset as u64).to_le_bytes());
        out.extend_from_slice(&(len as u64).to_le_bytes());
        out.extend_from_slice(&0u64.to_le_bytes());
    }
}

/// The checks of a file's header: magic, version, size (neither truncated nor followed by
/// more bytes) and checksum.
fn check_header(bytes: &[u8]) -> Result<(), MapFileError> {
    let found = bytes.len() as u64;
    let header = bytes.get(..HEADER_BYTES).ok_or(MapFileError::Truncated {
        expected: HEADER_BYTES as u64,
        found,
    })?;
    let mut magic = [0u8; 8];
    magic.copy_from_slice(&header[..8]);
    if magic != MAGIC {
        return Err(MapFileError::WrongMagic { found: magic });
    }
    let version = u32_at(header, 8);
    if version != FORMAT_VERSION {
        return Err(MapFileError::UnsupportedVersion {
            found: version,
            supported: FORMAT_VERSION,
        });
    }
    let expected = u64_at(header, 16);
    if found < expected {
        return Err(MapFileError::Truncated { expected, found });
    }
    if found > expected {
        return Err(MapFileError::TrailingBytes { expected, found });
    }
    let stored = u64_at(header, CHECKSUM_AT);
    let computed = checksum(bytes);
    if stored != computed {
        return Err(MapFileError::ChecksumMismatch { stored, computed });
    }
    Ok(())
}

/// The checksum of a file: XXH3-64 of the header without its checksum field followed by
/// the XXH3-64 of each [`CHECKSUM_CHUNK_BYTES`] chunk of the rest (hashed in parallel).
fn checksum(bytes: &[u8]) -> u64 {
    let chunks: Vec<u64> = bytes
        .get(HEADER_BYTES..)
        .unwrap_or(&[])
        .par_chunks(CHECKSUM_CHUNK_BYTES)
        .map(xxhash_rust::xxh3::xxh3_64)
        .collect();
    let mut hasher = xxhash_rust::xxh3::Xxh3::new();
    hasher.update(bytes.get(..CHECKSUM_AT).unwrap_or(&[]));
    for chunk in chunks {
        hasher.update(&chunk.to_le_bytes());
    }
    hasher.digest()
}

/// Reads a `u32` / `u64` at `at` of `bytes` (little-endian); zero past the end (callers
/// check lengths first).
fn u32_at(bytes: &[u8], at: usize) -> u32 {
    bytes
        .get(at..at + 4)
        .and_then(|b| b.try_into().ok())
        .map_or(0, u32::from_le_bytes)
}

pub(crate) fn u64_at(bytes: &[u8], at: usize) -> u64 {
    bytes
        .get(at..at + 8)
        .and_then(|b| b.try_into().ok())
        .map_or(0, u64::from_le_bytes)
}

/// Loads a surface and its voxel map from the bytes [`encode`] wrote, copying them once
/// into an aligned buffer: [`decode_in_place`] of [`MapBytes::copy_from_slice`].
///
/// # Errors
/// As [`decode_in_place`].
pub fn decode(bytes: &[u8]) -> Result<(Surface, VoxelMap), MapFileError> {
    decode_in_place(&MapBytes::copy_from_slice(bytes))
}

/// Loads a surface and its voxel map from the bytes [`encode`] wrote, using their arrays
/// in place: the surface and map keep a reference to `bytes` and copy nothing (on a
/// big-endian machine, the arrays are copied and byte-swapped).
///
/// # Errors
/// In the order checked: [`MapFileError::Truncated`] (shorter than a header),
/// [`MapFileError::WrongMagic`], [`MapFileError::UnsupportedVersion`],
/// [`MapFileError::Truncated`] / [`MapFileError::TrailingBytes`] (length differs from the
/// header's), [`MapFileError::ChecksumMismatch`], then [`MapFileError::Invalid`] naming
/// the section and the index where the content breaks an invariant of [`Surface`] or
/// [`VoxelMap`] (indices out of range, offsets not increasing, dimensions inconsistent,
/// non-finite coordinates, a map built for another surface). The barycentric frames, the
/// shading normals, the clearances and the source indices of the triangles are checked
/// for range, not recomputed: a crafted
/// file with a valid checksum can make them wrong (and with them the answers of the
/// queries that trust them: [`first_crossing`](crate::query::first_crossing) skips free
/// space by the clearances), never unsafe to use.
///
/// # Performance
/// A checksum at memory speed (its chunks in parallel) and linear checks, nothing copied
/// or recomputed: for a million triangles (about 270 MB) a few tens of milliseconds, most
/// of it the checksum. Reading the file is the caller's: [`MapBytes::from_mmap`] of a
/// mapped file costs no copy at all, [`MapBytes::read_from`] one copy into fresh memory.
///
/// # Examples
/// ```
/// use haphe::map::{decode_in_place, encode, MapBytes, MapOptions, VoxelMap};
/// use haphe::mesh::{shapes, Surface, SurfaceOptions};
/// let surface = Surface::new(shapes::sphere(0.1, 2), &SurfaceOptions::default()).unwrap();
/// let map = VoxelMap::build(&surface, &MapOptions::default()).unwrap();
/// let bytes = MapBytes::read_from(&encode(&surface, &map)[..]).unwrap();
/// let (surface2, map2) = decode_in_place(&bytes).unwrap();
/// assert_eq!((surface2.triangles(), &map2), (surface.triangles(), &map));
/// ```
pub fn decode_in_place(file: &MapBytes) -> Result<(Surface, VoxelMap), MapFileError> {
    let bytes = file.as_slice();
    check_header(bytes)?;
    let sections = section_ranges(bytes)?;
    let [
        report,
        vertices,
        triangles,
        neighbours,
        frames,
        corner_normals,
        fan_start,
        fan_triangles,
        source,
        params,
        bricks,
        surface_bits,
        inside_bits,
        overlap_bricks,
        overlap_bits,
        surface_before,
        surface_first,
        clearances,
        triangle_start,
        triangle_refs,
        slabs,
        brick_slabs,
        region_slabs,
        provenance,
    ] = sections;

    let report: MeshReport = serde_json::from_slice(&bytes[report])
        .map_err(|e| invalid("report", format!("not a mesh report: {e}")))?;
    let parts: OwnedSurfaceParts = SurfaceParts {
        vertices: array::<DVec3, u64>(file, vertices),
        triangles: array::<[u32; 3], u32>(file, triangles),
        neighbours: array::<[u32; 3], u32>(file, neighbours),
        frames: array::<TriFrame, u64>(file, frames),
        corner_normals: array::<[[f32; 3]; 3], u32>(file, corner_normals),
        fan_start: array::<u32, u32>(file, fan_start),
        fan_triangles: array::<u32, u32>(file, fan_triangles),
        source: array::<u32, u32>(file, source),
        report,
    };
    check_surface(&parts)?;
    let surface = Surface::from_parts(parts);

    let params = parse_map_params(&bytes[params])?;
    let mut map = VoxelMap {
        grid: params.grid,
        brick_dims: super::voxel_map::brick_dims(params.grid.dims()),
        bricks: array::<u32, u32>(file, bricks),
        free_bricks: Vec::new(),
        free_regions: Default::default(),
        surface_bits: array::<BrickBits, u64>(file, surface_bits),
        inside_bits: array::<BrickBits, u64>(file, inside_bits),
        overlap_bricks: array::<u32, u32>(file, overlap_bricks),
        overlap_bits: array::<BrickBits, u64>(file, overlap_bits),
        surface_before: array::<[u16; MASK_WORDS], u16>(file, surface_before),
        surface_first: array::<u32, u32>(file, surface_first),
        clearances: array::<u8, u8>(file, clearances),
        triangle_start: array::<u32, u32>(file, triangle_start),
        triangle_refs: array::<u32, u32>(file, triangle_refs),
        slabs: array::<u32, u32>(file, slabs),
        brick_slabs: array::<u32, u32>(file, brick_slabs),
        region_slabs: array::<u64, u64>(file, region_slabs),
        triangle_count: params.triangle_count,
        solid: params.solid,
        cell_size_rule: params.cell_size_rule,
        provenance: decode_provenance(&bytes[provenance])?,
    };
    check_map(&map, &surface)?;
    map.derive_free_space();
    Ok((surface, map))
}

/// The provenance section: empty, or the JSON of a [`Provenance`] this crate could write.
fn decode_provenance(bytes: &[u8]) -> Result<Option<Box<Provenance>>, MapFileError> {
    if bytes.is_empty() {
        return Ok(None);
    }
    let p: Provenance = serde_json::from_slice(bytes)
        .map_err(|e| invalid("provenance", format!("not a provenance record: {e}")))?;
    match p.problem() {
        Some(problem) => Err(invalid("provenance", problem)),
        None => Ok(Some(Box::new(p))),
    }
}

/// The array of little-endian words `W` at `range` of `file`: a view in place on a
/// little-endian machine, else a copy. `range` is inside the file and a whole number of
/// elements (checked by [`section_ranges`]).
fn array<T: Pod, W: Word>(file: &MapBytes, range: Range<usize>) -> Array<T> {
    if cfg!(target_endian = "little")
        && let Some(view) = Array::view(file, range.clone())
    {
        return view;
    }
    take::<T, W>(file.as_slice().get(range).unwrap_or(&[])).into()
}

/// The byte ranges of the sections, after checking the table: the expected kinds in
/// order, element sizes, 64-byte aligned offsets in increasing order without overlap,
/// lengths that are whole elements and inside the file.
fn section_ranges(bytes: &[u8]) -> Result<[Range<usize>; SECTIONS.len()], MapFileError> {
    let count = u32_at(bytes, 12) as usize;
    if count != SECTIONS.len() {
        return Err(invalid(
            "header",
            format!("{count} sections, expected {}", SECTIONS.len()),
        ));
    }
    if bytes
        .get(24..CHECKSUM_AT)
        .is_some_and(|r| r.iter().any(|&b| b != 0))
    {
        return Err(invalid("header", "reserved bytes are not zero"));
    }
    let mut slices: [Range<usize>; SECTIONS.len()] = std::array::from_fn(|_| 0..0);
    let mut end_of_previous = (HEADER_BYTES + count * TABLE_ENTRY_BYTES) as u64;
    for (kind, (&(name, elem), slice)) in SECTIONS.iter().zip(slices.iter_mut()).enumerate() {
        let at = HEADER_BYTES + kind * TABLE_ENTRY_BYTES;
        let (k, e) = (u32_at(bytes, at), u32_at(bytes, at + 4));
        let (offset, len) = (u64_at(bytes, at + 8), u64_at(bytes, at + 16));
        if k as usize != kind || e as usize != elem || u64_at(bytes, at + 24) != 0 {
            return Err(invalid(
                name,
                format!(
                    "table entry {kind} has kind {k} and element size {e}, expected {kind} and {elem}"
                ),
            ));
        }
        if offset % SECTION_ALIGN as u64 != 0 || offset < end_of_previous {
            return Err(invalid(
                name,
                format!("offset {offset} is not 64-byte aligned after byte {end_of_previous}"),
            ));
        }
        if len % elem as u64 != 0 {
            return Err(invalid(
                name,
                format!("length {len} is not a whole number of {elem}-byte elements"),
            ));
        }
        let end = offset
            .checked_add(len)
            .filter(|&end| end <= bytes.len() as u64)
            .ok_or_else(|| invalid(name, format!("bytes {offset}+{len} run past the end")))?;
        *slice = offset as usize..end as usize;
        end_of_previous = end;
    }
    Ok(slices)
}
