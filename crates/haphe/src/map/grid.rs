//! The uniform grid of a voxel map: cell indices, cell bounds and the half-open convention.

use glam::DVec3;

use super::overlap::TriangleBoxes;

/// Largest number of cells along one axis of a [`Grid`] (2²⁰). Every cell index and its
/// successor then stays exact in `f64` and in `u32` arithmetic, and the build's sort keys
/// fit in 64 bits.
pub const MAX_CELLS_PER_AXIS: u32 = 1 << 20;

/// How far the surface stays from the padding cells of a map's grid, as a fraction of the
/// cell size. Far above [`OVERLAP_TOLERANCE_REL`] and coordinate rounding, so that no
/// triangle is ever listed in a padding cell and every point outside the grid is outside
/// the object.
pub(crate) const PADDING_SLACK_REL: f64 = 1e-3;

/// How much every cell box is enlarged, as a fraction of the cell size on every side,
/// before a triangle is tested against it (so boxes are closed, and slightly more).
///
/// The reason: a query finds the cells a segment passes with floating-point arithmetic
/// (`cell_of`, a 3D-DDA), which can put a point that lies within rounding of a cell face
/// into the neighbouring cell. A triangle through that point must be listed in both cells,
/// so the map lists every triangle that comes within this distance of a cell. The DDA's
/// rounding is about `1e-16 × (coordinate / cell size)` cells, at most about `1e-10` for
/// the largest grids ([`MAX_CELLS_PER_AXIS`]) even for an object a hundred times its own
/// size away from its origin; `1e-7` leaves three orders of magnitude to spare and adds a
/// triangle to a cell it misses only when it passes within a ten-millionth of a cell of it.
pub const OVERLAP_TOLERANCE_REL: f64 = 1e-7;

/// A uniform grid of cubic cells, metres, object frame.
///
/// Cell `[i, j, k]` covers the **half-open** box `[origin + (i, j, k)·h, origin + (i + 1,
/// j + 1, k + 1)·h)` where `h` is the cell size, so every point of the grid box belongs to
/// exactly one cell ([`Grid::cell_of`]). Rounding can move a point lying within about
/// `1e-16` relative of a cell face into the neighbouring cell; the map's triangle lists
/// are conservative for that reason ([`OVERLAP_TOLERANCE_REL`]).
///
/// Invariants (checked by [`Grid::new`]): `origin` and the far corner are finite, the cell
/// size is finite and positive, and each dimension is in `1..=`[`MAX_CELLS_PER_AXIS`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grid {
    origin: DVec3,
    cell_size: f64,
    dims: [u32; 3],
}

impl Grid {
    /// A grid with its lower corner at `origin` (metres, object frame), cubic cells of
    /// `cell_size_m` metres and `dims` cells along x, y and z.
    ///
    /// Returns `None` unless the invariants of [`Grid`] hold.
    pub fn new(origin: DVec3, cell_size_m: f64, dims: [u32; 3]) -> Option<Grid> {
        let grid = Grid {
            origin,
            cell_size: cell_size_m,
            dims,
        };
        let valid = origin.is_finite()
            && cell_size_m.is_finite()
            && cell_size_m > 0.0
            && dims.iter().all(|&d| (1..=MAX_CELLS_PER_AXIS).contains(&d))
            && grid.max_corner().is_finite();
        valid.then_some(grid)
    }

    /// The grid of a voxel map for a surface with bounding box `[min, max]` (metres,
    /// object frame): cells of `cell_size_m` metres over the box, centred on it, with at
    /// least a thousandth of a cell to spare on every side, and one more layer of
    /// *padding* cells all around. The surface then lies strictly inside the cells
    /// `1..dims − 1` along each axis, and every point outside the grid box is outside the
    /// object.
    ///
    /// Returns `None` when the box or the cell size is not finite, the cell size not
    /// positive, or the grid would have more than [`MAX_CELLS_PER_AXIS`] cells along an axis.
    pub fn padded_around(min: DVec3, max: DVec3, cell_size_m: f64) -> Option<Grid> {
        if !(min.is_finite() && max.is_finite() && min.cmple(max).all()) {
            return None;
        }
        if !(cell_size_m.is_finite() && cell_size_m > 0.0) {
            return None;
        }
        let h = cell_size_m;
        let extent = max - min;
        let mut dims = [0u32; 3];
        let mut origin = DVec3::ZERO;
        for axis in 0..3 {
            let cells = (extent[axis] / h).floor() + 1.0;
            let mut interior = cells;
            if interior * h - extent[axis] < 2.0 * PADDING_SLACK_REL * h {
                interior += 1.0;
            }
            let total = interior + 2.0;
            // `extent / h` may overflow to infinity, never to NaN (both are finite, h > 0).
            if total > f64::from(MAX_CELLS_PER_AXIS) {
                return None;
            }
            let slack = 0.5 * (interior * h - extent[axis]);
            dims[axis] = total as u32;
            origin[axis] = min[axis] - h - slack;
        }
        Grid::new(origin, h, dims)
    }

    /// The lower corner of cell `[0, 0, 0]`, metres, object frame.
    #[inline]
    pub fn origin(&self) -> DVec3 {
        self.origin
    }

    /// The edge length of a cell, metres.
    #[inline]
    pub fn cell_size(&self) -> f64 {
        self.cell_size
    }

    /// Number of cells along x, y and z.
    #[inline]
    pub fn dims(&self) -> [u32; 3] {
        self.dims
    }

    /// Total number of cells.
    #[inline]
    pub fn cell_count(&self) -> u64 {
        self.dims.iter().map(|&d| u64::from(d)).product()
    }

    /// The upper corner of the grid box, `origin + dims·h` (metres, object frame); points
    /// on or beyond it belong to no cell.
    #[inline]
    pub fn max_corner(&self) -> DVec3 {
        self.origin + self.cell_size * DVec3::from_array(self.dims.map(f64::from))
    }

    /// Whether `c` names a cell of the grid.
    #[inline]
    pub fn contains(&self, c: [u32; 3]) -> bool {
        c[0] < self.dims[0] && c[1] < self.dims[1] && c[2] < self.dims[2]
    }

    /// The position of `p_object` in cell units, `(p − origin) / h`: cell `i` along an
    /// axis covers `[i, i + 1)`. This is the coordinate a 3D-DDA steps through.
    #[inline]
    pub fn to_grid(&self, p_object: DVec3) -> DVec3 {
        (p_object - self.origin) / self.cell_size
    }

    /// The cell containing `p_object` (metres, object frame): `floor(to_grid(p))`, or
    /// `None` when `p` is outside the grid box or not finite.
    ///
    /// # Real-time
    /// No allocation, no panic, constant time.
    #[inline]
    pub fn cell_of(&self, p_object: DVec3) -> Option<[u32; 3]> {
        let q = self.to_grid(p_object);
        let mut cell = [0u32; 3];
        for axis in 0..3 {
            // Written so that NaN fails the test.
            if !(q[axis] >= 0.0 && q[axis] < f64::from(self.dims[axis])) {
                return None;
            }
            cell[axis] = q[axis] as u32;
        }
        Some(cell)
    }

    /// The box `(min, max)` of cell `c`, metres, object frame: `min = origin + c·h`,
    /// `max = origin + (c + 1)·h`. The cell itself is half-open, `[min, max)`. Cells
    /// outside the grid get the box their index would have.
    #[inline(always)]
    pub fn cell_bounds(&self, c: [u32; 3]) -> (DVec3, DVec3) {
        let lo = DVec3::from_array(c.map(f64::from));
        (
            self.origin + lo * self.cell_size,
            self.origin + (lo + DVec3::ONE) * self.cell_size,
        )
    }

    /// The centre of cell `c`, metres, object frame.
    #[inline]
    pub fn cell_centre(&self, c: [u32; 3]) -> DVec3 {
        self.origin + (DVec3::from_array(c.map(f64::from)) + DVec3::splat(0.5)) * self.cell_size
    }

    /// The parameter interval `[t0, t1] ⊆ [0, 1]` over which the segment
    /// `p0 + t·(p1 − p0)` (metres, object frame) lies in the closed grid box, or `None`
    /// when it misses the box or a point is not finite. Where a 3D-DDA starts and stops.
    pub fn clip_segment(&self, p0: DVec3, p1: DVec3) -> Option<(f64, f64)> {
        let a = self.to_grid(p0);
        let d = self.to_grid(p1) - a;
        self.clip_along(a, d, d.recip())
    }

    /// [`clip_segment`](Self::clip_segment) of the segment from `a` along `d`, in cell
    /// units ([`to_grid`](Self::to_grid)), given `inv = 1 / d` per axis: multiplications,
    /// not divisions (the walk keeps `inv` for its own steps).
    #[inline]
    pub(crate) fn clip_along(&self, a: DVec3, d: DVec3, inv: DVec3) -> Option<(f64, f64)> {
        if !(a.is_finite() && d.is_finite()) {
            return None;
        }
        let hi = DVec3::from_array(self.dims.map(f64::from));
        clip_to_box(a, d, inv, DVec3::ZERO, hi)
    }

    /// Whether triangle `corners_object` (metres, object frame) overlaps cell `c` enlarged
    /// by [`OVERLAP_TOLERANCE_REL`] of a cell on every side: the predicate by which a
    /// [`VoxelMap`](super::VoxelMap) lists triangles, evaluated in cell units exactly as the
    /// build evaluates it. It is the separating-axis test of
    /// [`overlap_triangle_box`](super::overlap_triangle_box) with the triangle's projections
    /// computed once per triangle (the two differ only by rounding, about `1e-16` of the
    /// coordinates in cell units).
    pub fn overlaps_cell(&self, corners_object: [DVec3; 3], c: [u32; 3]) -> bool {
        let corners = corners_object.map(|p| self.to_grid(p));
        overlap_cell_units(corners, c)
    }
}

/// The parameter interval `[t0, t1] ⊆ [0, 1]` over which the segment `a + t·d` lies in the
/// closed box `[lo, hi]`, given `inv = 1 / d` per axis (a slab test; an axis along which
/// the segment does not move tests its coordinate), or `None` when it misses the box.
/// Finite input.
#[inline]
pub(crate) fn clip_to_box(
    a: DVec3,
    d: DVec3,
    inv: DVec3,
    lo: DVec3,
    hi: DVec3,
) -> Option<(f64, f64)> {
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for axis in 0..3 {
        if d[axis] == 0.0 {
            if a[axis] < lo[axis] || a[axis] > hi[axis] {
                return None;
            }
            continue;
        }
        let (s0, s1) = (
            (lo[axis] - a[axis]) * inv[axis],
            (hi[axis] - a[axis]) * inv[axis],
        );
        t0 = t0.max(s0.min(s1));
        t1 = t1.min(s0.max(s1));
    }
    (t0 <= t1).then_some((t0, t1))
}

/// The listing predicate in cell units: triangle `corners` (cell units) against cell `c`
/// enlarged by [`OVERLAP_TOLERANCE_REL`].
#[inline]
pub(crate) fn overlap_cell_units(corners: [DVec3; 3], c: [u32; 3]) -> bool {
    cell_tester(corners).overlaps(cell_centre_units(c))
}

/// The prepared test of one triangle (cell units) against enlarged cells.
#[inline]
pub(crate) fn cell_tester(corners: [DVec3; 3]) -> TriangleBoxes {
    TriangleBoxes::new(corners, DVec3::splat(0.5 + OVERLAP_TOLERANCE_REL))
}

/// The centre of cell `c` in cell units.
#[inline]
pub(crate) fn cell_centre_units(c: [u32; 3]) -> DVec3 {
    DVec3::from_array(c.map(f64::from)) + DVec3::splat(0.5)
}

/// `⌊x⌋` as an integer, inline (`f64::floor` is a library call on the baseline x86-64
/// target), as `x.floor() as i64` for every input: saturating far beyond any grid (where
/// callers' range checks refuse the cell), 0 for NaN.
#[inline(always)]
pub(crate) fn floor_to_int(x: f64) -> i64 {
    let i = x as i64;
    if (i as f64) > x {
        i.saturating_sub(1)
    } else {
        i
    }
}

/// `⌈x⌉` as an integer, inline, as `x.ceil() as i64` for every input (see
/// [`floor_to_int`]).
#[inline(always)]
pub(crate) fn ceil_to_int(x: f64) -> i64 {
    let i = x as i64;
    if (i as f64) < x {
        i.saturating_add(1)
    } else {
        i
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn floor_to_int_is_floor_as_integer() {
        for x in [
            0.0,
            -0.0,
            0.5,
            -0.5,
            1.0,
            -1.0,
            2.999,
            -2.999,
            1e18,
            -1e18,
            1e300,
            -1e300,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            f64::MIN_POSITIVE,
            -f64::MIN_POSITIVE,
        ] {
            assert_eq!(floor_to_int(x), x.floor() as i64, "{x}");
            assert_eq!(ceil_to_int(x), x.ceil() as i64, "{x}");
        }
    }

    fn grid() -> Grid {
        Grid::new(DVec3::new(-1.0, -2.0, 0.5), 0.25, [8, 4, 2]).expect("valid grid")
    }

    #[test]
    fn cells_are_half_open() {
        let g = grid();
        assert_eq!(g.cell_of(g.origin()), Some([0, 0, 0]));
        assert_eq!(g.cell_of(DVec3::new(-0.75, -2.0, 0.5)), Some([1, 0, 0]));
        assert_eq!(g.cell_of(g.max_corner()), None);
        assert_eq!(
            g.cell_of(g.max_corner() - DVec3::splat(1e-12)),
            Some([7, 3, 1])
        );
        assert_eq!(g.cell_of(g.origin() - DVec3::X * 1e-12), None);
        assert_eq!(g.cell_of(DVec3::NAN), None);
        assert_eq!(g.cell_of(DVec3::INFINITY), None);
        let (lo, hi) = g.cell_bounds([1, 2, 1]);
        assert_eq!(lo, DVec3::new(-0.75, -1.5, 0.75));
        assert_eq!(hi, DVec3::new(-0.5, -1.25, 1.0));
        assert_eq!(g.cell_centre([1, 2, 1]), 0.5 * (lo + hi));
        assert_eq!(g.cell_of(g.cell_centre([5, 3, 0])), Some([5, 3, 0]));
        assert!(g.contains([7, 3, 1]) && !g.contains([8, 0, 0]));
        assert_eq!(g.cell_count(), 64);
    }

    #[test]
    fn invalid_grids_are_refused() {
        assert!(Grid::new(DVec3::ZERO, 0.0, [1, 1, 1]).is_none());
        assert!(Grid::new(DVec3::ZERO, f64::NAN, [1, 1, 1]).is_none());
        assert!(Grid::new(DVec3::NAN, 1.0, [1, 1, 1]).is_none());
        assert!(Grid::new(DVec3::ZERO, 1.0, [0, 1, 1]).is_none());
        assert!(Grid::new(DVec3::ZERO, 1.0, [MAX_CELLS_PER_AXIS + 1, 1, 1]).is_none());
        assert!(Grid::new(DVec3::ZERO, 1e308, [1 << 20, 1, 1]).is_none());
        assert!(Grid::padded_around(DVec3::ONE, DVec3::ZERO, 1.0).is_none());
        assert!(Grid::padded_around(DVec3::ZERO, DVec3::ONE, 1e-9).is_none());
    }

    #[test]
    fn padding_keeps_the_box_inside_the_interior_cells() {
        for (extent, h) in [(1.0, 0.25), (1.0, 0.3), (0.0, 0.1), (0.999_999_9, 0.1)] {
            let (min, max) = (
                DVec3::new(-0.5, 0.0, 3.0),
                DVec3::new(-0.5 + extent, 0.0, 3.0),
            );
            let g = Grid::padded_around(min, max, h).expect("valid");
            let lo = g.origin() + DVec3::splat(h);
            let hi = g.max_corner() - DVec3::splat(h);
            let slack = PADDING_SLACK_REL * h;
            assert!((min - lo).min_element() >= slack * 0.99, "{extent} {h}");
            assert!((hi - max).min_element() >= slack * 0.99, "{extent} {h}");
            assert!(g.dims().iter().all(|&d| d >= 3));
        }
    }

    #[test]
    fn clip_segment_finds_the_part_inside() {
        let g = Grid::new(DVec3::ZERO, 1.0, [2, 2, 2]).expect("valid");
        let (t0, t1) = g
            .clip_segment(DVec3::new(-1.0, 1.0, 1.0), DVec3::new(3.0, 1.0, 1.0))
            .expect("crosses");
        assert_eq!((t0, t1), (0.25, 0.75));
        assert!(
            g.clip_segment(DVec3::new(-1.0, 3.0, 1.0), DVec3::new(3.0, 3.0, 1.0))
                .is_none()
        );
        assert!(g.clip_segment(DVec3::NAN, DVec3::ONE).is_none());
        assert_eq!(
            g.clip_segment(DVec3::splat(0.5), DVec3::splat(0.6)),
            Some((0.0, 1.0))
        );
    }
}
