//! Choosing the cell size of a voxel map: the typical triangle size, the fitted rule for a
//! target number of triangles per surface cell, and the memory estimate that enlarges it.

use crate::par::*;
use glam::DVec3;

use super::grid::Grid;
use super::voxel_map::{BRICK_SIDE, MAX_BRICKS, NIBBLE_BYTES, brick_dims};
use super::{CellSizeRule, MapError};
use crate::mesh::{Surface, TriId};

/// Factor by which an automatic cell size grows while the map does not fit.
const CELL_SIZE_GROWTH: f64 = 1.25;

/// Smallest factor between the typical triangle size and an automatic cell size (reached
/// for targets near one triangle per cell).
const MIN_CELL_SIZE_FACTOR: f64 = 0.25;

/// Coefficients of the fit `τ ≈ 1 + a·f + b·f²` of the mean number of triangles per
/// surface cell `τ` against the ratio `f` of cell size to typical triangle size, measured
/// on the procedural sphere, torus and blob (the box comes out about 15% higher, a thin
/// plate with both faces in one cell twice as high).
const FIT_LINEAR: f64 = 2.2;
const FIT_QUADRATIC: f64 = 0.75;

/// The ratio of cell size to typical triangle size that gives about `triangles_per_cell`
/// triangles per surface cell: the positive root of the fit, at least
/// [`MIN_CELL_SIZE_FACTOR`].
fn cell_size_factor(triangles_per_cell: f64) -> f64 {
    let (a, b) = (FIT_LINEAR, FIT_QUADRATIC);
    let root = ((a * a + 4.0 * b * (triangles_per_cell - 1.0)).sqrt() - a) / (2.0 * b);
    root.max(MIN_CELL_SIZE_FACTOR)
}

/// Mean number of cells a unit of surface area crosses, per squared cell size: the mean of
/// `|n_x| + |n_y| + |n_z|` over directions (1 for an axis-aligned plane, √3 at most).
const CELLS_PER_AREA: f64 = 1.5;

/// Bytes of a detailed brick: two masks, clearance nibbles, counts per mask word, the
/// first surface cell.
const DETAILED_BRICK_BYTES: f64 = (64 + 64 + 256 + 16 + 4) as f64;

/// Triangles per parallel task when summing over the surface (fixed, so that the sums are
/// the same for any number of threads).
const MODEL_CHUNK: usize = 4096;

/// What the cell-size rule and the memory estimate need to know about a surface.
pub(super) struct SizeModel {
    min: DVec3,
    max: DVec3,
    triangles: f64,
    area: f64,
    typical_size: f64,
    /// Sums over triangles of the largest and second-largest bounding-box side, and of
    /// their product: the cells a triangle meets are about `(1 + e1/h)(1 + e2/h)`.
    sum_e1: f64,
    sum_e2: f64,
    sum_e1e2: f64,
}

impl SizeModel {
    /// Deterministic: sums are taken per fixed chunk, then chunk by chunk in order.
    pub(super) fn of(surface: &Surface) -> SizeModel {
        let vertices = surface.vertices();
        let (min, max) = vertices
            .par_chunks(MODEL_CHUNK)
            .map(|chunk| {
                chunk
                    .iter()
                    .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), &p| {
                        (lo.min(p), hi.max(p))
                    })
            })
            .collect::<Vec<_>>()
            .into_iter()
            .fold(
                (DVec3::INFINITY, DVec3::NEG_INFINITY),
                |(lo, hi), (a, b)| (lo.min(a), hi.max(b)),
            );
        let per_triangle = |tri: &[u32; 3]| {
            let [a, b, c] = tri.map(|v| vertices[v as usize]);
            let mut e = ((a.max(b).max(c)) - (a.min(b).min(c))).to_array();
            e.sort_by(|x, y| y.total_cmp(x));
            let area = 0.5 * (b - a).cross(c - a).length();
            (e[0], e[1], area)
        };
        let sums = surface
            .triangles()
            .par_chunks(MODEL_CHUNK)
            .map(|chunk| {
                chunk.iter().fold([0.0; 4], |s, tri| {
                    let (e1, e2, area) = per_triangle(tri);
                    [s[0] + e1, s[1] + e2, s[2] + e1 * e2, s[3] + area]
                })
            })
            .collect::<Vec<_>>()
            .into_iter()
            .fold([0.0; 4], |s, c| {
                [s[0] + c[0], s[1] + c[1], s[2] + c[2], s[3] + c[3]]
            });
        let mut sizes: Vec<f64> = surface
            .triangles()
            .par_iter()
            .enumerate()
            .filter(|&(t, _)| !surface.frame(TriId(t as u32)).is_degenerate())
            .map(|(_, tri)| per_triangle(tri).2.sqrt())
            .collect();
        let typical_size = if sizes.is_empty() {
            (max - min).max_element()
        } else {
            let mid = sizes.len() / 2;
            *sizes.select_nth_unstable_by(mid, f64::total_cmp).1
        };
        SizeModel {
            min,
            max,
            triangles: surface.triangle_count() as f64,
            area: sums[3],
            typical_size,
            sum_e1: sums[0],
            sum_e2: sums[1],
            sum_e1e2: sums[2],
        }
    }

    /// The grid for a given cell size, or why not.
    pub(super) fn given_grid(&self, h: f64, budget: usize) -> Result<Grid, MapError> {
        if !(h.is_finite() && h > 0.0) {
            return Err(MapError::InvalidCellSize { cell_size_m: h });
        }
        let grid = self.grid(h).ok_or(MapError::TooManyCells {
            cell_size_m: h,
            extent_m: (self.max - self.min).to_array(),
        })?;
        let needed = self.estimate_bytes(&grid);
        if needed > budget as f64 {
            return Err(MapError::OverBudget {
                cell_size_m: h,
                needed_bytes: needed as u64,
                budget_bytes: budget,
            });
        }
        Ok(grid)
    }

    /// The automatic cell size after at least `enlargements` growth steps: the first that
    /// makes a valid grid whose estimated map fits the budget.
    pub(super) fn automatic_grid(
        &self,
        triangles_per_cell: f64,
        enlargements: u32,
        budget: usize,
    ) -> Result<(Grid, CellSizeRule), MapError> {
        let initial = self.typical_size * cell_size_factor(triangles_per_cell);
        let mut steps = enlargements;
        loop {
            let h = initial * CELL_SIZE_GROWTH.powi(steps as i32);
            if !(h.is_finite() && h > 0.0) {
                return Err(MapError::InvalidCellSize { cell_size_m: h });
            }
            if let Some(grid) = self.grid(h) {
                let needed = self.estimate_bytes(&grid);
                if needed <= budget as f64 {
                    let rule = CellSizeRule::Automatic {
                        typical_triangle_size_m: self.typical_size,
                        initial_cell_size_m: initial,
                        enlargements: steps,
                    };
                    return Ok((grid, rule));
                }
                if grid.dims().iter().all(|&d| d <= 3) {
                    return Err(MapError::OverBudget {
                        cell_size_m: h,
                        needed_bytes: needed as u64,
                        budget_bytes: budget,
                    });
                }
            }
            steps += 1;
        }
    }

    /// The padded grid for cell size `h`, if within the limits.
    fn grid(&self, h: f64) -> Option<Grid> {
        let grid = Grid::padded_around(self.min, self.max, h)?;
        let bricks: u64 = brick_dims(grid.dims())
            .iter()
            .map(|&d| u64::from(d))
            .product();
        (bricks <= MAX_BRICKS).then_some(grid)
    }

    /// Estimated heap bytes of the map on `grid`.
    fn estimate_bytes(&self, grid: &Grid) -> f64 {
        let h = grid.cell_size();
        let bricks: f64 = brick_dims(grid.dims())
            .iter()
            .map(|&d| f64::from(d))
            .product();
        let refs = self.triangles + (self.sum_e1 + self.sum_e2) / h + self.sum_e1e2 / (h * h);
        let surface_cells = refs.min(1.2 * CELLS_PER_AREA * self.area / (h * h));
        let side = f64::from(BRICK_SIDE) * h;
        let detailed = (1.2 * CELLS_PER_AREA * self.area / (side * side) + 8.0)
            .min(surface_cells)
            .min(bricks);
        // Graded bricks: the uniform bricks touching a detailed one, about two per detailed
        // brick for a smooth surface.
        let graded = (2.0 * detailed).min(bricks - detailed);
        4.0 * (bricks + refs + surface_cells)
            + DETAILED_BRICK_BYTES * detailed
            + NIBBLE_BYTES as f64 * graded
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::build::build_on_grid;
    use crate::mesh::SurfaceOptions;
    use crate::mesh::shapes::Catalog;

    #[test]
    fn cell_size_factor_inverts_the_fit() {
        for tau in [2.0, 3.0, 4.0, 8.0] {
            let f = cell_size_factor(tau);
            let back = 1.0 + FIT_LINEAR * f + FIT_QUADRATIC * f * f;
            assert!((back - tau).abs() < 1e-12, "{tau}: {f} gives {back}");
        }
        assert_eq!(cell_size_factor(1.0), MIN_CELL_SIZE_FACTOR);
    }

    #[test]
    fn memory_estimate_is_close_to_the_built_map() {
        for shape in Catalog::ALL {
            for n in [300, 5_000, 40_000] {
                let surface = Surface::new(shape.with_triangles(n), &SurfaceOptions::default())
                    .expect("a procedural shape is a surface");
                let model = SizeModel::of(&surface);
                for tau in [2.0, 3.0, 6.0] {
                    let (grid, rule) = model
                        .automatic_grid(tau, 0, usize::MAX)
                        .expect("no budget limit");
                    let map = build_on_grid(&surface, grid, rule, &|_| {}).expect("builds");
                    let ratio = model.estimate_bytes(&grid) / map.heap_bytes() as f64;
                    println!("{shape} {n} τ={tau}: estimate / actual = {ratio:.2}");
                    assert!((0.8..2.5).contains(&ratio), "{shape} {n} τ={tau}: {ratio}");
                }
            }
        }
    }
}
