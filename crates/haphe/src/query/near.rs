//! The nearest triangle within a radius of a point: exact for any radius
//! ([`nearest_within`]), and bounded for a tick ([`nearest_within_bounded`]: how the proxy
//! notices a surface it has come to rest on without crossing it).

use glam::DVec3;

use super::closest::{ClosestPoint, closest_point_triangle};
use crate::map::{CellBox, VoxelMap};
use crate::mesh::{Surface, TriId};

/// A triangle within the searched radius of a point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NearTriangle {
    /// The triangle.
    pub triangle: TriId,
    /// Its point closest to the query point (object frame), with weights and feature.
    pub closest: ClosestPoint,
    /// Distance from the query point to `closest.point`, metres.
    pub distance: f64,
}

/// Most cells searched along each axis by [`nearest_within_bounded`], the servo's
/// variant: the cell of the point and its two neighbours.
pub const MAX_NEAR_CELLS_PER_AXIS: u32 = 3;

/// Cell lookups [`nearest_within`] may spend per triangle of the surface before it tests
/// every triangle instead: past that, the rings of cells cost more than the brute force.
const NEAR_CELLS_PER_TRIANGLE: u64 = 8;

/// The triangle nearest to `p` (metres, object frame) among those within `radius` metres
/// of it; the lowest triangle index among equally near ones. Exact for any radius: equals
/// [`nearest_within_brute_force`], whatever the map's cell size. `None` when no triangle
/// is within `radius`, or for non-finite input.
///
/// # Work
/// Searches the map's cells in Chebyshev rings around `p`'s cell, starting past the free
/// space its clearance ([`VoxelMap::reach`]) vouches for, and stops once the next ring
/// lies farther than the nearest triangle found or than `radius` (a triangle is listed
/// in every cell it overlaps, so one in ring `k + 1` or beyond is at least `k` cells
/// away). Near a surface this visits a few cells; when the rings would take more than
/// eight cell lookups per triangle, it tests every triangle instead. No allocation, no
/// lock, no panic, but the work grows with the radius: a tick calls the bounded variant,
/// `nearest_within_bounded`, which searches only the cells next to the point's (exact
/// for a radius up to a cell).
pub fn nearest_within(
    surface: &Surface,
    map: &VoxelMap,
    p: DVec3,
    radius: f64,
) -> Option<NearTriangle> {
    if nothing_within(surface, p, radius) {
        return None;
    }
    let grid = map.grid();
    let h = grid.cell_size();
    let r = DVec3::splat(radius);
    // Every cell a triangle within `radius` of `p` may be listed in.
    let search = map.clip_cells(CellBox::around(grid, p - r, p + r))?;
    let centre = CellBox::around(grid, p, p).lo;
    // Rings nearer than the search box, or than the free space around `p`'s cell, hold
    // no listed cell.
    let to_box = (0..3)
        .map(|k| {
            (search.lo[k] - centre[k])
                .max(centre[k] - search.hi[k])
                .max(0)
        })
        .max()
        .unwrap_or(0);
    let free = match centre.map(u32::try_from) {
        [Ok(x), Ok(y), Ok(z)] => i64::from(map.reach([x, y, z])),
        _ => 0,
    };
    let last = (0..3)
        .map(|k| (search.hi[k] - centre[k]).max(centre[k] - search.lo[k]))
        .max()
        .unwrap_or(0);
    let budget = NEAR_CELLS_PER_TRIANGLE.saturating_mul(surface.triangle_count() as u64);
    let mut spent = 0u64;
    let mut best: Option<NearTriangle> = None;
    for ring in to_box.max(free)..=last {
        // Every triangle not yet seen lies in ring `ring` or beyond: at least `ring − 1`
        // cells from `p` (less a rounding margin).
        let farther = (ring - 1) as f64 * h * (1.0 - 1e-9);
        if farther > radius || best.is_some_and(|b| farther > b.distance) {
            break;
        }
        spent += map.visit_ring(centre, ring, search, |_, triangles| {
            for &t in triangles {
                consider(surface, TriId(t), p, radius, &mut best);
            }
        });
        if spent > budget {
            return nearest_within_brute_force(surface, p, radius);
        }
    }
    best
}

/// [`nearest_within`] for a tick: the triangle nearest to `p` (metres, object frame)
/// among those within `radius` metres of it, searched in the map's cells that overlap
/// the cube of half-side `radius` around `p` and lie no farther than one cell from `p`'s
/// ([`MAX_NEAR_CELLS_PER_AXIS`]); the lowest triangle index among equally near ones.
/// Equals [`nearest_within_brute_force`] whenever `radius` is at most a cell (the proxy
/// asks for a fraction of a micrometre); a triangle farther than a cell is not found even
/// within a larger radius.
///
/// # Real-time
/// No allocation, no lock, no panic. Visits the cells the cube overlaps: at most 8 when
/// `radius` is below a cell, never more than 27; each triangle listed there costs one
/// plane height and, when that is within `radius`, one closest-point kernel. Non-finite
/// input gives `None`.
pub fn nearest_within_bounded(
    surface: &Surface,
    map: &VoxelMap,
    p: DVec3,
    radius: f64,
) -> Option<NearTriangle> {
    if nothing_within(surface, p, radius) {
        return None;
    }
    // The cells the cube overlaps, no farther than one cell from `p`'s.
    let grid = map.grid();
    let r = DVec3::splat(radius);
    let cells = CellBox::around(grid, p - r, p + r).intersect(CellBox::around(grid, p, p).grown(1));
    map.clip_cells(cells)?;
    let mut best = None;
    // A triangle within `radius` of `p` reaches into the cube, so it is listed in a cell
    // the cube overlaps (the cell lists are conservative).
    map.visit_cells(cells, |_, triangles| {
        for &t in triangles {
            consider(surface, TriId(t), p, radius, &mut best);
        }
    });
    best
}

/// Whether no triangle can be within `radius` of `p`: non-finite input, a negative
/// radius, or `p` beyond the surface's box by more than `radius` (and the rounding of the
/// distances).
#[inline]
fn nothing_within(surface: &Surface, p: DVec3, radius: f64) -> bool {
    !(p.is_finite() && radius >= 0.0 && radius.is_finite())
        || super::bounds::beyond_bounds(surface, p, p, radius + 1e-12 * p.abs().max_element())
}

/// [`nearest_within`] by testing every triangle: the oracle.
///
/// # Performance
/// `O(n)`: for tests and verification, never for a tick.
pub fn nearest_within_brute_force(
    surface: &Surface,
    p: DVec3,
    radius: f64,
) -> Option<NearTriangle> {
    if !(p.is_finite() && radius >= 0.0 && radius.is_finite()) {
        return None;
    }
    let mut best = None;
    for t in 0..surface.triangle_count() {
        consider(surface, TriId(t as u32), p, radius, &mut best);
    }
    best
}

/// Keeps triangle `t` in `best` when it lies within `radius` of `p` and is nearer than
/// the kept one (lower index on ties). The plane height, a lower bound of the distance,
/// skips most triangles before the closest-point kernel.
#[inline(always)]
pub(crate) fn consider(
    surface: &Surface,
    t: TriId,
    p: DVec3,
    radius: f64,
    best: &mut Option<NearTriangle>,
) {
    let frame = surface.frame(t);
    if frame.normal.dot(p - frame.origin).abs() > radius {
        return;
    }
    let closest = closest_point_triangle(p, surface.corners(t));
    let distance = p.distance(closest.point);
    if distance <= radius
        && best.is_none_or(|b: NearTriangle| {
            distance < b.distance || (distance == b.distance && t.0 < b.triangle.0)
        })
    {
        *best = Some(NearTriangle {
            triangle: t,
            closest,
            distance,
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::map::MapOptions;
    use crate::mesh::SurfaceOptions;
    use crate::mesh::shapes;

    #[test]
    fn equals_brute_force_near_and_on_a_sphere() {
        let surface = Surface::new(shapes::sphere(0.1, 3), &SurfaceOptions::default()).unwrap();
        let map = VoxelMap::build(&surface, &MapOptions::default()).unwrap();
        let mut rng = crate::rng::SplitMix64::new(7);
        let mut found = 0;
        for i in 0..4000 {
            let t = TriId((i % surface.triangle_count()) as u32);
            let c = surface.corners(t);
            let w = [rng.next_unit(), rng.next_unit(), rng.next_unit()];
            let s: f64 = w.iter().sum();
            let on = (c[0] * w[0] + c[1] * w[1] + c[2] * w[2]) / s;
            let off = rng.unit_vector();
            let p = on + off * 10f64.powf(rng.range(-8.0, -3.0));
            let radius = 10f64.powf(rng.range(-8.0, -3.0));
            let fast = nearest_within(&surface, &map, p, radius);
            assert_eq!(
                fast,
                nearest_within_brute_force(&surface, p, radius),
                "{p:?} {radius}"
            );
            found += usize::from(fast.is_some());
        }
        assert!(found > 1000, "only {found} points had a triangle in reach");
    }

    #[test]
    fn a_vertex_shared_by_many_triangles_goes_to_the_lowest_index() {
        let mesh = shapes::cuboid(DVec3::splat(0.05), [2, 2, 2]);
        let surface = Surface::new(mesh, &SurfaceOptions::default()).unwrap();
        let map = VoxelMap::build(&surface, &MapOptions::default()).unwrap();
        let corner = surface.vertices()[0];
        let near = nearest_within(&surface, &map, corner, 1e-9).expect("on the surface");
        assert_eq!(near.distance, 0.0);
        let lowest = (0..surface.triangle_count() as u32)
            .find(|&t| surface.triangles()[t as usize].contains(&0))
            .unwrap();
        assert_eq!(near.triangle, TriId(lowest));
        assert_eq!(
            nearest_within(&surface, &map, corner + DVec3::splat(1.0), 1e-3),
            None
        );
        assert_eq!(nearest_within(&surface, &map, DVec3::NAN, 1e-3), None);
        assert_eq!(nearest_within(&surface, &map, corner, f64::NAN), None);
    }
}
