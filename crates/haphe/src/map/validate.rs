//! The checks a loaded file passes before its surface and map are trusted: every invariant
//! that a query relies on to index arrays, and the canonical layout the build produces.

use super::file_error::invalid;
use super::voxel_map::{
    BRICK_CELLS, BrickBits, GRADED, MASK_WORDS, MAX_REACH, NIBBLE_BYTES, UNIFORM, UNIFORM_PAYLOAD,
    UNIFORM_STATE_SHIFT, VoxelMap, brick_coords, cell_in_brick, entry_state, in_grid_bits,
};
use super::{CellState, MapFileError};
use crate::mesh::{NONE, OwnedSurfaceParts, Surface, Usability};

/// Values checked per vectorised chunk (the position of a fault is looked for only after
/// a chunk fails).
const CHECK_CHUNK: usize = 1024;

/// The index of the first row of `width` values in `values` with a non-finite value.
fn first_non_finite<F: Copy + Into<f64>>(values: &[F], width: usize) -> Option<usize> {
    let finite = values
        .chunks(CHECK_CHUNK)
        .all(|c| c.iter().fold(true, |ok, &x| ok & x.into().is_finite()));
    if finite {
        return None;
    }
    values
        .iter()
        .position(|&x| !x.into().is_finite())
        .map(|i| i / width.max(1))
}

/// The invariants of [`Surface`] that later stages index with.
pub(crate) fn check_surface(p: &OwnedSurfaceParts) -> Result<(), MapFileError> {
    check_triangles(p)?;
    check_frames(p)?;
    check_fans(p)?;
    check_source_and_report(p)
}

/// The vertices, the triangles' vertex indices and the neighbours (linked both ways).
fn check_triangles(p: &OwnedSurfaceParts) -> Result<(), MapFileError> {
    // The arrays as plain slices once (a loaded array is a view; see `crate::array`).
    let (triangles, neighbours): (&[[u32; 3]], &[[u32; 3]]) = (&p.triangles, &p.neighbours);
    let (v, t) = (p.vertices.len(), triangles.len());
    if t == 0 || t >= NONE as usize || v >= NONE as usize {
        return Err(invalid(
            "triangles",
            format!("{t} triangles and {v} vertices"),
        ));
    }
    if let Some(i) = first_non_finite::<f64>(bytemuck::cast_slice(&p.vertices), 3) {
        return Err(invalid("vertices", format!("vertex {i} is not finite")));
    }
    if let Some(i) = triangles
        .iter()
        .position(|tri| tri.iter().any(|&x| x as usize >= v))
    {
        return Err(invalid(
            "triangles",
            format!("triangle {i} has a vertex index out of range (of {v})"),
        ));
    }
    if neighbours.len() != t {
        return Err(invalid(
            "neighbours",
            format!("{} rows for {t} triangles", neighbours.len()),
        ));
    }
    for (i, row) in neighbours.iter().enumerate() {
        for &n in row {
            let linked_back = neighbours
                .get(n as usize)
                .is_some_and(|back| n as usize != i && back.contains(&(i as u32)));
            if n != NONE && !linked_back {
                return Err(invalid(
                    "neighbours",
                    format!(
                        "triangle {i} names neighbour {n}, which is out of range or does not name it back"
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// One finite frame and one row of finite corner normals per triangle.
fn check_frames(p: &OwnedSurfaceParts) -> Result<(), MapFileError> {
    let t = p.triangles.len();
    if p.frames.len() != t {
        return Err(invalid(
            "frames",
            format!("{} frames for {t} triangles", p.frames.len()),
        ));
    }
    if let Some(i) = first_non_finite::<f64>(bytemuck::cast_slice(&p.frames), 12) {
        return Err(invalid(
            "frames",
            format!("triangle {i} has a non-finite frame"),
        ));
    }
    if p.corner_normals.len() != t {
        return Err(invalid(
            "corner normals",
            format!("{} rows for {t} triangles", p.corner_normals.len()),
        ));
    }
    if let Some(i) = first_non_finite::<f32>(bytemuck::cast_slice(&p.corner_normals), 9) {
        return Err(invalid(
            "corner normals",
            format!("triangle {i} has a non-finite normal"),
        ));
    }
    Ok(())
}

/// The vertex fans: one start per vertex and one past the last, non-decreasing, each fan
/// listing only triangles with a corner at its vertex.
fn check_fans(p: &OwnedSurfaceParts) -> Result<(), MapFileError> {
    let triangles: &[[u32; 3]] = &p.triangles;
    let (starts, fan_triangles): (&[u32], &[u32]) = (&p.fan_start, &p.fan_triangles);
    let v = p.vertices.len();
    if starts.len() != v + 1
        || starts.first() != Some(&0)
        || starts.last().map(|&x| x as usize) != Some(fan_triangles.len())
        || starts.windows(2).any(|w| w[0] > w[1])
    {
        return Err(invalid(
            "fan starts",
            format!(
                "{} starts for {v} vertices and {} fan entries: not 0, non-decreasing, up to the entries",
                starts.len(),
                fan_triangles.len()
            ),
        ));
    }
    for (vertex, w) in starts.windows(2).enumerate() {
        let fan = fan_triangles
            .get(w[0] as usize..w[1] as usize)
            .unwrap_or(&[]);
        for &tri in fan {
            let has_corner = triangles
                .get(tri as usize)
                .is_some_and(|corners| corners.contains(&(vertex as u32)));
            if !has_corner {
                return Err(invalid(
                    "fan triangles",
                    format!(
                        "the fan of vertex {vertex} lists triangle {tri}, which has no corner there"
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// The source triangles (in range) and the report (describing this surface, usable).
fn check_source_and_report(p: &OwnedSurfaceParts) -> Result<(), MapFileError> {
    let (v, t) = (p.vertices.len(), p.triangles.len());
    // Only for what the surface reports (a face's index in the file), never to index an
    // array: range-checked, as the frames are, not proven a permutation.
    let source: &[u32] = &p.source;
    if source.len() != t {
        return Err(invalid(
            "source triangles",
            format!("{} entries for {t} triangles", source.len()),
        ));
    }
    if let Some(i) = source.iter().position(|&s| s as usize >= t) {
        return Err(invalid(
            "source triangles",
            format!("triangle {i} names source triangle {}, of {t}", source[i]),
        ));
    }
    let r = &p.report;
    if r.triangles != t || r.vertices != v || r.usable_as == Usability::Unusable {
        return Err(invalid(
            "report",
            format!(
                "the report describes {} triangles and {} vertices ({:?}); the surface has {t} and {v}",
                r.triangles, r.vertices, r.usable_as
            ),
        ));
    }
    Ok(())
}

/// The invariants of [`VoxelMap`], against the surface it must belong to.
pub(crate) fn check_map(map: &VoxelMap, surface: &Surface) -> Result<(), MapFileError> {
    let t = surface.triangle_count();
    if map.triangle_count as usize != t || map.solid != surface.is_solid() {
        let solid = |s: bool| if s { "solid" } else { "not solid" };
        return Err(invalid(
            "map parameters",
            format!(
                "the map was built for {} triangles ({}), the surface has {t} ({})",
                map.triangle_count,
                solid(map.solid),
                solid(surface.is_solid()),
            ),
        ));
    }
    check_bricks(map)?;
    check_detailed(map)?;
    check_overlap(map)?;
    check_triangle_lists(map, t)
}

/// Overlap cells: one mask per listed brick, bricks in increasing order, each mask
/// non-empty and within the brick's inside cells (a uniform inside brick's in-grid cells,
/// or a detailed brick's inside mask); none unless the surface is a solid.
fn check_overlap(map: &VoxelMap) -> Result<(), MapFileError> {
    let section = "overlap bricks";
    if map.overlap_bricks.len() != map.overlap_bits.len() {
        return Err(invalid(
            section,
            format!(
                "{} bricks for {} masks",
                map.overlap_bricks.len(),
                map.overlap_bits.len()
            ),
        ));
    }
    if !map.solid && !map.overlap_bricks.is_empty() {
        return Err(invalid(section, "overlap cells in a map that is not solid"));
    }
    let mut previous: Option<u32> = None;
    for (&b, bits) in map.overlap_bricks.iter().zip(map.overlap_bits.iter()) {
        if previous.is_some_and(|p| p >= b) {
            return Err(invalid(
                section,
                format!("brick {b} after brick {previous:?}: not increasing"),
            ));
        }
        previous = Some(b);
        let Some(&entry) = map.bricks.get(b as usize) else {
            return Err(invalid(
                section,
                format!("brick {b} beyond the {} bricks", map.bricks.len()),
            ));
        };
        let allowed = if entry & UNIFORM == 0 {
            map.inside_bits
                .get(entry as usize)
                .copied()
                .unwrap_or([0; MASK_WORDS])
        } else if entry_state(entry) == CellState::Inside {
            in_grid_bits(brick_coords(b as usize, map.brick_dims), map.grid.dims())
        } else {
            [0; MASK_WORDS]
        };
        let empty = bits.iter().all(|&w| w == 0);
        if empty || bits.iter().zip(&allowed).any(|(w, a)| w & !a != 0) {
            return Err(invalid(
                "overlap masks",
                format!("brick {b}: the mask is empty or not within the brick's inside cells"),
            ));
        }
    }
    Ok(())
}

/// Brick entries: uniform ones with a valid state and reach (inside only for a solid,
/// never at the border), graded and detailed ones numbered consecutively in brick order.
fn check_bricks(map: &VoxelMap) -> Result<(), MapFileError> {
    let bdims = map.brick_dims;
    let brick_count: usize = bdims.iter().map(|&d| d as usize).product();
    if map.bricks.len() != brick_count {
        return Err(invalid(
            "bricks",
            format!("{} entries for {brick_count} bricks", map.bricks.len()),
        ));
    }
    let detailed = map.detailed_count();
    let mut next_detailed = 0u32;
    let mut next_graded = detailed as u32;
    for (b, &entry) in map.bricks.iter().enumerate() {
        if entry & UNIFORM == 0 {
            if entry != next_detailed {
                return Err(invalid(
                    "bricks",
                    format!("brick {b} names detailed brick {entry}, expected {next_detailed}"),
                ));
            }
            next_detailed += 1;
            continue;
        }
        let bc = brick_coords(b, bdims);
        let state = (entry >> UNIFORM_STATE_SHIFT) & 0x3f;
        let payload = entry & UNIFORM_PAYLOAD;
        let on_border = (0..3).any(|a| bc[a] == 0 || bc[a] + 1 >= bdims[a]);
        let state_ok = state == 0 || (state == 1 && map.solid && !on_border);
        let payload_ok = if entry & GRADED != 0 {
            next_graded += 1;
            payload == next_graded - 1
        } else {
            (1..=MAX_REACH).contains(&payload)
        };
        if !state_ok || !payload_ok {
            return Err(invalid(
                "bricks",
                format!(
                    "uniform brick {b} has entry {entry:#010x}: bad state, reach or \
                     graded index"
                ),
            ));
        }
    }
    if next_detailed as usize != detailed {
        return Err(invalid(
            "bricks",
            format!("{next_detailed} detailed bricks named, {detailed} stored"),
        ));
    }
    if map.clearances.len() != next_graded as usize * NIBBLE_BYTES {
        return Err(invalid(
            "clearances",
            format!(
                "{} bytes for {next_graded} detailed and graded bricks",
                map.clearances.len()
            ),
        ));
    }
    Ok(())
}

/// Detailed bricks: masks of the same length, surface and inside disjoint and within the
/// interior cells (inside only for a solid), at least one surface cell, counts per word
/// and first surface cells consistent; clearance nibbles 0 exactly on surface cells and
/// `1..=MAX_CLEARANCE` elsewhere (graded bricks: everywhere).
fn check_detailed(map: &VoxelMap) -> Result<(), MapFileError> {
    let detailed = map.detailed_count();
    if map.inside_bits.len() != detailed
        || map.surface_before.len() != detailed
        || map.surface_first.len() != detailed + 1
        || map.surface_first.first() != Some(&0)
    {
        return Err(invalid(
            "surface firsts",
            format!(
                "{} surface masks, {} inside masks, {} counts and {} firsts do not match",
                detailed,
                map.inside_bits.len(),
                map.surface_before.len(),
                map.surface_first.len()
            ),
        ));
    }
    let dims = map.grid.dims();
    let bdims = map.brick_dims;
    // The interior cells of a brick: all of them, except in bricks at the border of the
    // grid, which hold the padding (and cells beyond the grid).
    let interior = |bc: [u32; 3]| {
        let mut bits = in_grid_bits(bc, dims);
        if (0..3).all(|a| bc[a] > 0 && bc[a] + 1 < bdims[a]) {
            return bits;
        }
        for local in 0..BRICK_CELLS {
            let c = cell_in_brick(bc, local);
            if (0..3).any(|a| c[a] == 0 || c[a] + 1 >= dims[a]) {
                bits[local >> 6] &= !(1 << (local & 63));
            }
        }
        bits
    };
    for (b, &entry) in map.bricks.iter().enumerate() {
        if entry & UNIFORM != 0 {
            continue;
        }
        let d = entry as usize;
        let (surface, inside) = (map.surface_bits[d], map.inside_bits[d]);
        let allowed = interior(brick_coords(b, bdims));
        let mut count = 0u32;
        let mut ok = true;
        for z in 0..MASK_WORDS {
            ok &= surface[z] & inside[z] == 0
                && surface[z] & !allowed[z] == 0
                && inside[z] & !allowed[z] == 0
                && (map.solid || inside[z] == 0)
                && u32::from(map.surface_before[d][z]) == count;
            count += surface[z].count_ones();
        }
        let (first, next) = (map.surface_first[d], map.surface_first[d + 1]);
        if !ok || count == 0 || next.checked_sub(first) != Some(count) {
            return Err(invalid(
                "surface masks",
                format!(
                    "detailed brick {d} (brick {b}): masks overlap, leave the interior, or \
                     disagree with its counts ({count} surface cells, firsts {first}..{next})"
                ),
            ));
        }
        // Zero nibbles exactly on the surface cells (the cap is 15, so any non-zero
        // nibble is a valid clearance).
        let bytes = map
            .clearances
            .get(d * NIBBLE_BYTES..(d + 1) * NIBBLE_BYTES)
            .unwrap_or(&[]);
        if zero_nibbles(bytes) != surface {
            return Err(invalid(
                "clearances",
                format!(
                    "detailed brick {d} has clearance 0 on a non-surface cell or not on a surface cell"
                ),
            ));
        }
    }
    let graded = map.clearances.get(detailed * NIBBLE_BYTES..).unwrap_or(&[]);
    let has_zero_nibble = |b: &u8| b & 0x0f == 0 || b & 0xf0 == 0;
    let clean = graded
        .chunks(CHECK_CHUNK)
        .all(|c| !c.iter().fold(false, |any, b| any | has_zero_nibble(b)));
    if let Some(i) = (!clean)
        .then(|| graded.iter().position(has_zero_nibble))
        .flatten()
    {
        return Err(invalid(
            "clearances",
            format!(
                "graded brick {} has clearance 0 near cell {}",
                detailed + i / NIBBLE_BYTES,
                2 * (i % NIBBLE_BYTES)
            ),
        ));
    }
    Ok(())
}

/// The cells of a brick whose clearance nibble is zero (`bytes` holds the brick's
/// [`NIBBLE_BYTES`]; missing bytes count as zero).
fn zero_nibbles(bytes: &[u8]) -> BrickBits {
    const LOW: u64 = 0x0f0f_0f0f_0f0f_0f0f;
    let mut bits = [0u64; MASK_WORDS];
    for (word, out) in bits.iter_mut().enumerate() {
        // 64 cells = 32 bytes = four u64 lanes of 16 nibbles each.
        for lane in 0..4 {
            let at = word * 32 + lane * 8;
            let x = bytes
                .get(at..at + 8)
                .and_then(|b| b.try_into().ok())
                .map_or(0, u64::from_le_bytes);
            // Per byte: bit 0 set when the low nibble is zero, bit 1 when the high one is.
            let (lo, hi) = (x & LOW, (x >> 4) & LOW);
            let lo_zero = !((lo + LOW) >> 4) & 0x0101_0101_0101_0101;
            let hi_zero = !((hi + LOW) >> 4) & 0x0101_0101_0101_0101;
            let mut pairs = lo_zero | (hi_zero << 1);
            // Gather the eight 2-bit groups into 16 bits (cell 2k is bit 2k).
            let mut gathered = 0u64;
            for k in 0..8 {
                gathered |= (pairs & 3) << (2 * k);
                pairs >>= 8;
            }
            *out |= gathered << (16 * lane);
        }
    }
    bits
}

/// Triangle lists: one start per surface cell plus one, from 0, increasing (no empty
/// list), up to the references; each list within the triangles, none twice.
fn check_triangle_lists(map: &VoxelMap, t: usize) -> Result<(), MapFileError> {
    let surface_cells = map.surface_first.last().map_or(0, |&x| x as usize);
    let starts = &map.triangle_start;
    if starts.len() != surface_cells + 1
        || starts.first() != Some(&0)
        || starts.last().map(|&x| x as usize) != Some(map.triangle_refs.len())
        || starts.windows(2).any(|w| w[0] >= w[1])
    {
        return Err(invalid(
            "triangle starts",
            format!(
                "{} starts for {surface_cells} surface cells and {} references: not 0, \
                 increasing, up to the references",
                starts.len(),
                map.triangle_refs.len()
            ),
        ));
    }
    // One slab per surface cell, per detailed brick and per region of bricks.
    let regions: usize = super::free_space::region_dims(map.brick_dims)
        .iter()
        .map(|&d| d as usize)
        .product();
    for (section, count, wanted, per) in [
        ("slabs", map.slabs.len(), surface_cells, "surface cell"),
        (
            "brick slabs",
            map.brick_slabs.len(),
            map.surface_bits.len(),
            "brick with surface cells",
        ),
        (
            "region slabs",
            map.region_slabs.len(),
            regions,
            "region of bricks",
        ),
    ] {
        if count != wanted {
            return Err(invalid(
                section,
                format!("{count} {section} where there are {wanted}: one per {per}"),
            ));
        }
    }
    // Every reference within the triangles, and no triangle twice in one list (a list is
    // ordered along its cell's slab, not by index): each triangle marked with the last
    // list it was seen in.
    let refs = &map.triangle_refs;
    let mut seen_in = vec![u32::MAX; t];
    for (s, w) in starts.windows(2).enumerate() {
        for &x in refs.get(w[0] as usize..w[1] as usize).unwrap_or(&[]) {
            let Some(seen) = seen_in.get_mut(x as usize) else {
                return Err(invalid(
                    "triangle references",
                    format!("surface cell {s} lists triangle {x}, out of range (of {t})"),
                ));
            };
            if *seen == s as u32 {
                return Err(invalid(
                    "triangle references",
                    format!("surface cell {s} lists triangle {x} twice"),
                ));
            }
            *seen = s as u32;
        }
    }
    Ok(())
}
