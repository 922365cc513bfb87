//! The map's scalar parameters (grid, counts, how the cell size was chosen): the "map
//! parameters" section of a map file, written and read back with its checks.

use glam::DVec3;

use super::file::u64_at;
use super::file_error::invalid;
use super::grid::Grid;
use super::voxel_map::{BRICK_SIDE, MAX_BRICKS, brick_dims};
use super::{CellSizeRule, MAX_CLEARANCE, MapFileError, VoxelMap};

/// The map's scalar parameters, as stored in the "map parameters" section.
pub(crate) struct MapParams {
    pub(crate) grid: Grid,
    pub(crate) triangle_count: u32,
    pub(crate) solid: bool,
    pub(crate) cell_size_rule: CellSizeRule,
}

/// Bytes of the "map parameters" section.
const PARAMS_BYTES: usize = 88;

impl MapParams {
    pub(crate) fn of(map: &VoxelMap) -> MapParams {
        MapParams {
            grid: map.grid,
            triangle_count: map.triangle_count,
            solid: map.solid,
            cell_size_rule: map.cell_size_rule,
        }
    }
}

/// The section: origin (3 × f64), cell size (f64), dims (3 × u32), triangle count, solid
/// flag, maximum clearance, brick side, cell-size rule (0 given, 1 automatic) (u32 each),
/// typical triangle size and initial cell size (f64), enlargements and a zero (u32).
pub(crate) fn map_params_bytes(p: &MapParams) -> Vec<u8> {
    let mut out = Vec::with_capacity(PARAMS_BYTES);
    let g = &p.grid;
    for x in g.origin().to_array() {
        out.extend_from_slice(&x.to_le_bytes());
    }
    out.extend_from_slice(&g.cell_size().to_le_bytes());
    for d in g.dims() {
        out.extend_from_slice(&d.to_le_bytes());
    }
    let (rule, typical, initial, enlargements) = match p.cell_size_rule {
        CellSizeRule::Given => (0u32, 0.0, 0.0, 0u32),
        CellSizeRule::Automatic {
            typical_triangle_size_m,
            initial_cell_size_m,
            enlargements,
        } => (
            1,
            typical_triangle_size_m,
            initial_cell_size_m,
            enlargements,
        ),
    };
    for w in [
        p.triangle_count,
        u32::from(p.solid),
        u32::from(MAX_CLEARANCE),
        BRICK_SIDE,
        rule,
    ] {
        out.extend_from_slice(&w.to_le_bytes());
    }
    out.extend_from_slice(&typical.to_le_bytes());
    out.extend_from_slice(&initial.to_le_bytes());
    out.extend_from_slice(&enlargements.to_le_bytes());
    out.extend_from_slice(&0u32.to_le_bytes());
    out
}

pub(crate) fn parse_map_params(bytes: &[u8]) -> Result<MapParams, MapFileError> {
    const NAME: &str = "map parameters";
    if bytes.len() != PARAMS_BYTES {
        return Err(invalid(
            NAME,
            format!("{} bytes, expected {PARAMS_BYTES}", bytes.len()),
        ));
    }
    let f = |at: usize| f64::from_bits(u64_at(bytes, at));
    let u = |at: usize| (u64_at(bytes, at) & 0xffff_ffff) as u32;
    let origin = DVec3::new(f(0), f(8), f(16));
    let cell_size = f(24);
    let dims = [u(32), u(36), u(40)];
    let grid = Grid::new(origin, cell_size, dims).ok_or_else(|| {
        invalid(
            NAME,
            format!("grid at {origin} with {cell_size} m cells and dims {dims:?} is not valid"),
        )
    })?;
    let bricks: u64 = brick_dims(dims).iter().map(|&d| u64::from(d)).product();
    if bricks > MAX_BRICKS || dims.iter().any(|&d| d < 3) {
        return Err(invalid(
            NAME,
            format!("dims {dims:?} are not a padded grid of at most {MAX_BRICKS} bricks"),
        ));
    }
    let (triangle_count, solid, max_clearance, brick_side, rule) =
        (u(44), u(48), u(52), u(56), u(60));
    if solid > 1 || max_clearance != u32::from(MAX_CLEARANCE) || brick_side != BRICK_SIDE {
        return Err(invalid(
            NAME,
            format!(
                "solid flag {solid}, maximum clearance {max_clearance} and brick side \
                 {brick_side} (expected 0 or 1, {MAX_CLEARANCE} and {BRICK_SIDE})"
            ),
        ));
    }
    let (typical, initial, enlargements, zero) = (f(64), f(72), u(80), u(84));
    let cell_size_rule = match rule {
        0 if typical == 0.0 && initial == 0.0 && enlargements == 0 => CellSizeRule::Given,
        1 if typical.is_finite() && initial.is_finite() => CellSizeRule::Automatic {
            typical_triangle_size_m: typical,
            initial_cell_size_m: initial,
            enlargements,
        },
        _ => return Err(invalid(NAME, format!("cell-size rule {rule} is not valid"))),
    };
    if zero != 0 {
        return Err(invalid(NAME, "reserved word is not zero"));
    }
    Ok(MapParams {
        grid,
        triangle_count,
        solid: solid == 1,
        cell_size_rule,
    })
}
