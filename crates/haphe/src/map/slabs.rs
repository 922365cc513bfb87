//! Slabs: where in a surface cell its surface lies.
//!
//! A surface cell lists every triangle that overlaps it, but the triangles often fill only
//! a thin layer of the cell: a piece of a smooth surface, or both faces of a thin plate.
//! A segment that passes the cell above or below that layer crosses none of them there.
//! Each surface cell keeps its **slab** in four bytes: a direction `n` (two octahedral
//! bytes, see [`direction`]) and the range `[lo, hi]` of `n · (x − centre)` over its
//! triangles' corners (one byte each, in cells, rounded outward), which holds every point
//! of the triangles in the cell since a triangle is the convex hull of its corners. A
//! segment whose part in the cell lies wholly on one side of the slab ([`interval`]) skips
//! the cell's triangles — their list and their frames, the reads that are cold on large
//! meshes — and one that passes through it has only its part in the slab tested against
//! them.
//!
//! The direction is the sum of the triangles' normals (weighted by area), each turned to
//! the side of the first one's, which follows a smooth patch. Where that sum falls short
//! of the normals' total length (under 0.95 of it), the dominant axis of their second
//! moment, which does not depend on which way each normal points, is tried too and the
//! thinner slab kept: so the two faces of a thin plate give the plate's normal also where
//! a rim triangle, at a right angle to them, comes first. A block whose triangles face
//! every way gets a slab about as thick as the block: it rejects little.
//!
//! Each brick that holds surface cells keeps one too, over the triangles of all its
//! surface cells, in units of the brick's side (a step is then 0.03 of a cell), and so
//! does each region of 4×4×4 bricks, in eight bytes with bounds of 16 bits (a step is
//! 0.0005 of a cell; with a byte it would be 0.13 of one). A long segment's walk reads
//! a region's slab on entering the region, a brick's with the brick's surface mask, and
//! skips the cells of the block before the segment reaches the slab and after it leaves
//! it ([`interval`]): a segment passing near the surface without touching it crosses the
//! region or the brick in one stride, and one that crosses it goes straight to the layer
//! it crosses. On smooth surfaces at the cell sizes a map chooses, a brick's slab is
//! about a cell thick and a region's a few cells.

use crate::par::*;
use glam::{DMat3, DVec3};

use super::VoxelMap;
use super::free_space::{REGION_SIDE, region_dims};
use super::grid::{ceil_to_int, floor_to_int};
use super::voxel_map::{BRICK_SIDE, UNIFORM};
use crate::mesh::{Surface, TriId};

/// Half the range of a slab's bounds, in sides of its block (a cell or a brick) from the
/// block's centre: a little more than half a side, since a direction's L1 norm is 1 and
/// so `|n · (x − centre)|` is at most half a side for a point `x` of the block.
const RANGE: f64 = 0.51;
/// Steps of a slab bound: 255 steps of `2·RANGE/255` (0.004 of the block's side).
const LEVELS: f64 = 255.0;
/// A slab that rejects nothing: both bounds at the ends of the range.
pub(crate) const FULL_SLAB: u32 = 0xff00_0000;
/// Steps of a region's slab bound (16 bits): 65 535 steps of `2·RANGE/65535`, 0.0005 of
/// a cell on a region of 32 cells. With a byte a bound (0.13 of a cell a step, rounded
/// outward and one step more) lay up to a quarter of a cell beyond the region's
/// triangles on each side; a long segment then walked toward a flat surface cell by cell
/// through that margin.
const FINE_LEVELS: f64 = 65_535.0;
/// A region's slab that rejects nothing: both 16-bit bounds at the ends of the range.
pub(crate) const FULL_FINE_SLAB: u64 = 0xffff_0000_0000;

/// The direction of a slab, decoded from its two octahedral bytes: not unit length, its
/// L1 norm is 1 (its length is between `1/√3` and 1). Every code decodes to a non-zero
/// direction.
///
/// A byte `b` of `0..=254` stands for `b / 127 − 1`, so that 127 is an exact 0 and the
/// axes are exact: the plane of a plate or of a CAD part's face along an axis gets a slab
/// as thin as its triangles, where a direction a step off the axis would tilt the slab
/// across its block (over a region of 32 cells, by a quarter of a cell). A byte of 255,
/// which no build writes, reads as 254.
#[inline]
fn direction(slab: u32) -> DVec3 {
    // A product, not a quotient: a division's latency sits on every query's path.
    const STEP: f64 = 1.0 / 127.0;
    let u = f64::from((slab & 0xff).min(254)) * STEP - 1.0;
    let v = f64::from(((slab >> 8) & 0xff).min(254)) * STEP - 1.0;
    let z = 1.0 - u.abs() - v.abs();
    // Selects, not a branch: which half a block's direction falls in is not predictable
    // from one block to the next.
    let upper = z >= 0.0;
    let x = if upper {
        u
    } else {
        (1.0 - v.abs()).copysign(u)
    };
    let y = if upper {
        v
    } else {
        (1.0 - u.abs()).copysign(v)
    };
    DVec3::new(x, y, z)
}

/// The two octahedral bytes of the non-zero direction `n`.
fn encode_direction(n: DVec3) -> u32 {
    let n = n / n.abs().element_sum();
    let (u, v) = if n.z < 0.0 {
        (
            (1.0 - n.y.abs()).copysign(n.x),
            (1.0 - n.x.abs()).copysign(n.y),
        )
    } else {
        (n.x, n.y)
    };
    let byte = |x: f64| round_half_away((x + 1.0) * 127.0).clamp(0.0, 254.0) as u32;
    byte(u) | (byte(v) << 8)
}

/// `x.round()` (half away from zero), inline: `f64::round` is a library call on the
/// baseline x86-64 target. The same value for every `x`, up to the sign of a zero.
#[inline]
fn round_half_away(x: f64) -> f64 {
    // Below 2⁵² in magnitude the integer part is exact as an `i64` and `x − t` is exact.
    if x.is_nan() || x.abs() >= 4_503_599_627_370_496.0 {
        return x.round();
    }
    let t = (x as i64) as f64;
    let d = x - t;
    if d >= 0.5 {
        t + 1.0
    } else if d <= -0.5 {
        t - 1.0
    } else {
        t
    }
}

/// The bounds `(lo, hi)` of a slab, in sides of its block along its direction from the
/// block's centre.
#[inline]
fn bounds(slab: u32) -> (f64, f64) {
    let step = 2.0 * RANGE / LEVELS;
    (
        f64::from((slab >> 16) & 0xff) * step - RANGE,
        f64::from(slab >> 24) * step - RANGE,
    )
}

/// The bounds `(lo, hi)` of a region's slab (16 bits each), as [`bounds`].
#[inline]
fn fine_bounds(slab: u64) -> (f64, f64) {
    let step = 2.0 * RANGE / FINE_LEVELS;
    (
        ((slab >> 16) & 0xffff) as f64 * step - RANGE,
        ((slab >> 32) & 0xffff) as f64 * step - RANGE,
    )
}

/// Three corners of a triangle, metres.
type Corners = [DVec3; 3];

/// What [`VoxelMap::derive_slabs`] finds for a detailed brick: its surface cells' slabs,
/// its own slab, its cells' lists ordered along their slabs, and its triangles (each
/// once, in index order).
type PerBrick = (Vec<u32>, u32, Vec<u32>, Vec<u32>);

/// Reused buffers of the slab of a block: its triangles' corners, and a cell's list keyed
/// along its slab (see [`order_along`]).
#[derive(Default)]
pub(crate) struct SlabScratch {
    corners: Vec<Corners>,
    /// The cell's triangles in the order along its slab, with their keys.
    pub(crate) keyed: Vec<(f64, u32)>,
    /// A bit per triangle of a block, for [`blocks::sort_unique`].
    bits: Vec<u64>,
}

/// The corners of `triangles`, in `out` (emptied first): read once from the surface for
/// the slab's passes and the list's order.
fn gather(surface: &Surface, triangles: &[u32], out: &mut Vec<Corners>) {
    out.clear();
    out.extend(triangles.iter().map(|&t| surface.corners(TriId(t))));
}

/// The slab of a block (a surface cell or a brick) with centre `centre` (metres) and side
/// `h` (metres) over triangles of `corners`: along the sum of their normals, or along the
/// dominant axis of the normals where that gives a thinner slab.
fn slab_of(corners: &[Corners], centre: DVec3, h: f64) -> u32 {
    slab_steps(corners, centre, h, LEVELS, false).map_or(FULL_SLAB, |(code, lo, hi)| {
        code | ((lo as u32) << 16) | ((hi as u32) << 24)
    })
}

/// The slab of a region, as [`slab_of`] with bounds of 16 bits; both directions are tried
/// (a tilt of the sum's direction, which bounds of a byte hide, would thicken it).
fn fine_slab_of(corners: &[Corners], centre: DVec3, h: f64) -> u64 {
    slab_steps(corners, centre, h, FINE_LEVELS, true).map_or(FULL_FINE_SLAB, |(code, lo, hi)| {
        u64::from(code) | (lo << 16) | (hi << 32)
    })
}

/// A slab before packing: the direction's two bytes and the bounds in steps.
type Steps = (u32, u64, u64);

/// The slab of a block over triangles of `corners`, bounds in steps of `levels`: along
/// the sum of their normals when it follows a smooth patch (unless `both`), else the
/// thinner of that and the dominant axis of the normals. `None` without triangles or
/// when products overflow.
fn slab_steps(
    corners: &[Corners],
    centre: DVec3,
    h: f64,
    levels: f64,
    both: bool,
) -> Option<Steps> {
    let first = corners.first()?;
    // Area-weighted normals from the corners (the frames would be one more array to
    // read), each turned to the side of the first.
    let normal = |&[a, b, c]: &Corners| (b - a).cross(c - a);
    let reference = normal(first);
    let (mut sum, mut total) = (DVec3::ZERO, 0.0);
    for t in corners {
        let n = normal(t);
        sum += if n.dot(reference) < 0.0 { -n } else { n };
        total += n.length();
    }
    let along_sum = slab_along(corners, centre, h, sum, levels);
    // The sum gives a smooth patch's normal (then it is nearly as long as the normals
    // together) but cancels out, or turns sideways, where faces meet at an angle (the
    // rim of a thin plate: its top and bottom faces turned to the side of a rim
    // triangle's normal cancel out). There the axis of the normals' second moment
    // `Σ n nᵀ / |n|`, the direction most of the area faces either way, is tried too.
    if !both
        && let Some(steps) = along_sum
        && sum.length() >= 0.95 * total
    {
        return Some(steps);
    }
    let mut moment = DMat3::ZERO;
    for t in corners {
        let n = normal(t);
        let length = n.length();
        if length > 0.0 {
            moment += DMat3::from_cols(n * n.x, n * n.y, n * n.z) / length;
        }
    }
    let axis = dominant_axis(moment);
    let along_moment = slab_along(corners, centre, h, axis, levels);
    [along_sum, along_moment]
        .into_iter()
        .flatten()
        .min_by_key(|&(_, lo, hi)| hi - lo)
}

/// The axis of the largest eigenvalue of the symmetric positive semi-definite `moment`,
/// by power iteration from its largest column (zero when `moment` is).
fn dominant_axis(moment: DMat3) -> DVec3 {
    let columns = [moment.x_axis, moment.y_axis, moment.z_axis];
    let mut axis = columns
        .into_iter()
        .max_by(|a, b| a.length_squared().total_cmp(&b.length_squared()))
        .unwrap_or(DVec3::ZERO);
    for _ in 0..8 {
        let next = moment * axis;
        let length = next.length();
        if !(length > 0.0 && length.is_finite()) {
            break;
        }
        axis = next / length;
    }
    axis
}

/// The slab of direction `n` (non-zero) of a block with centre `centre` and side `h`
/// over `corners`, bounds in steps of `levels`; `None` when `n` is zero or not finite or
/// a product overflows.
fn slab_along(corners: &[Corners], centre: DVec3, h: f64, n: DVec3, levels: f64) -> Option<Steps> {
    if !(n.is_finite() && n.length_squared() > 0.0) {
        return None;
    }
    let code = encode_direction(n);
    let (lo, hi) = steps_along(corners, centre, h, code, levels)?;
    Some((code, lo, hi))
}

/// The bounds, in steps of `levels` over the range, of `corners` along the direction of
/// `code`, from `centre`, in units of `h`: outward to the step, then one step more, far
/// beyond the rounding of the products. `None` without corners or when a product
/// overflows.
fn steps_along(
    corners: &[Corners],
    centre: DVec3,
    h: f64,
    code: u32,
    levels: f64,
) -> Option<(u64, u64)> {
    let (lo, hi) = extent_along(corners, centre, direction(code));
    // In units of `h` after the extremes are found: a division by a positive number
    // keeps the order, so this is the extreme of the quotients, one division for two.
    let (lo, hi) = (lo / h, hi / h);
    if !(lo.is_finite() && hi.is_finite()) {
        return None;
    }
    let step = 2.0 * RANGE / levels;
    // `floor_to_int` and `ceil_to_int`, not `f64::floor`, `f64::ceil` (library calls on the
    // baseline target): the same steps once clamped.
    let lo = (floor_to_int((lo + RANGE) / step) as f64 - 1.0).clamp(0.0, levels) as u64;
    let hi = (ceil_to_int((hi + RANGE) / step) as f64 + 1.0).clamp(0.0, levels) as u64;
    Some((lo, hi))
}

/// The smallest and largest `n · (x − centre)` over the corners `x` of `corners`
/// (`(+∞, −∞)` without corners; a NaN product is passed over, as `f64::min` does). Three
/// running bounds, one per corner of a triangle, so that consecutive comparisons do not
/// wait on each other: the extremes of a set do not depend on the order they are taken in.
#[inline]
fn extent_along(corners: &[Corners], centre: DVec3, n: DVec3) -> (f64, f64) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for triangle in corners {
        for i in 0..3 {
            let s = n.dot(triangle[i] - centre);
            lo[i] = if s < lo[i] { s } else { lo[i] };
            hi[i] = if s > hi[i] { s } else { hi[i] };
        }
    }
    let lower = |a: f64, b: f64| if b < a { b } else { a };
    let upper = |a: f64, b: f64| if b > a { b } else { a };
    (
        lower(lower(lo[0], lo[1]), lo[2]),
        upper(upper(hi[0], hi[1]), hi[2]),
    )
}

/// The bounds `(lo, hi)` of a slab (in sides of its block of centre `centre` and side
/// `h`, metres) in metres along its direction from the centre, widened by a margin (a
/// hundred-thousandth of the side, plus `1e-12` of the coordinates) far above the
/// rounding of the products that are compared with them.
#[inline]
fn with_margin((lo, hi): (f64, f64), centre: DVec3, h: f64) -> (f64, f64) {
    let margin = 1e-5 * h + 1e-12 * centre.abs().max_element();
    (lo * h - margin, hi * h + margin)
}

/// The parameters `(from, to)` of the segment `p0 → p1` (metres) between which it lies
/// in `slab`, the slab of a block with centre `centre` and side `h`: outside them the
/// segment crosses none of the block's triangles at a point of the block (`from` may be
/// below 0 and `to` above 1; both infinite for a segment parallel to the slab and in
/// it). `None` when no point of the segment lies in it. The bounds have the margin of
/// [`with_margin`].
/// A segment whose coordinates overflow the products gets `(−∞, +∞)`: it rejects nothing.
#[inline]
pub(crate) fn interval(
    slab: u32,
    centre: DVec3,
    h: f64,
    p0: DVec3,
    p1: DVec3,
) -> Option<(f64, f64)> {
    interval_toward(slab, centre, h, p0, p1).map(|(from, to, _)| (from, to))
}

/// [`interval`], and whether the segment moves along the slab's direction (`false`
/// against it; `true` when it moves neither way or its products overflow): the way to
/// walk a cell's list, ordered along that direction.
#[inline]
pub(crate) fn interval_toward(
    slab: u32,
    centre: DVec3,
    h: f64,
    p0: DVec3,
    p1: DVec3,
) -> Option<(f64, f64, bool)> {
    let bounds = with_margin(bounds(slab), centre, h);
    interval_along(direction(slab), bounds, centre, p0, p1)
}

/// [`interval`] for a region's slab (bounds of 16 bits).
#[inline]
pub(crate) fn fine_interval(
    slab: u64,
    centre: DVec3,
    h: f64,
    p0: DVec3,
    p1: DVec3,
) -> Option<(f64, f64)> {
    let bounds = with_margin(fine_bounds(slab), centre, h);
    interval_along(direction(slab as u32), bounds, centre, p0, p1).map(|(from, to, _)| (from, to))
}

/// The parameters between which the segment `p0 → p1` lies in the layer `lo ≤ n · (x −
/// centre) ≤ hi` (metres), and whether it moves along `n`: see [`interval_toward`].
#[inline]
fn interval_along(
    n: DVec3,
    (lo, hi): (f64, f64),
    centre: DVec3,
    p0: DVec3,
    p1: DVec3,
) -> Option<(f64, f64, bool)> {
    let s0 = n.dot(p0 - centre);
    let ds = n.dot(p1 - centre) - s0;
    if !(s0.is_finite() && ds.is_finite()) {
        return Some((f64::NEG_INFINITY, f64::INFINITY, true));
    }
    if ds == 0.0 {
        return (lo <= s0 && s0 <= hi).then_some((f64::NEG_INFINITY, f64::INFINITY, true));
    }
    let inv = 1.0 / ds;
    let (a, b) = ((lo - s0) * inv, (hi - s0) * inv);
    let (from, to) = (a.min(b), a.max(b));
    (from <= 1.0 && to >= 0.0).then_some((from, to, ds > 0.0))
}

/// Puts `listed` (a cell's triangles) into `keyed` in the order a segment moving along
/// `n` meets them: by `n · (a + b + c)`, three times the height of their centroids along
/// the cell's slab direction, then by index. The query walks a list forwards or backwards
/// as its segment moves along `n` or against it, so the first triangle it crosses is
/// mostly the first it tests: the near face of a thin plate before the far one, whose
/// filter then skips it on the part before the crossing (see
/// [`first_crossing`](crate::query::first_crossing)). Any order gives the same answers.
/// `corners` are those of `listed`, in its order.
fn order_along(n: DVec3, listed: &[u32], corners: &[Corners], keyed: &mut Vec<(f64, u32)>) {
    keyed.clear();
    keyed.extend(
        listed
            .iter()
            .zip(corners)
            .map(|(&t, &[a, b, c])| (n.dot(a + b + c), t)),
    );
    keyed.sort_unstable_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
}

impl VoxelMap {
    /// Sets the slab of every surface cell, in the order of the surface cells (detailed
    /// bricks in order, cells of a brick in mask order), and of every detailed brick, and
    /// orders each cell's list along its slab's direction ([`order_along`]). Parallel over
    /// bricks.
    pub(crate) fn derive_slabs(&mut self, surface: &Surface) {
        // Per detailed brick: its cells' slabs, its own slab, its cells' lists, ordered, and
        // its triangles (each once).
        let per_brick: Vec<PerBrick> = (0..self.bricks.len())
            .into_par_iter()
            .filter(|&b| self.bricks[b] & UNIFORM == 0)
            .map(|b| {
                let brick = self.bricks[b] as usize;
                let (mut slabs, mut triangles, mut ordered) = (Vec::new(), Vec::new(), Vec::new());
                let Some(bits) = self.surface_bits.get(brick) else {
                    return (slabs, FULL_SLAB, ordered, triangles);
                };
                let mut scratch = SlabScratch::default();
                for (word, &bits) in bits.iter().enumerate() {
                    let mut rest = bits;
                    while rest != 0 {
                        let local = word * 64 + rest.trailing_zeros() as usize;
                        rest &= rest - 1;
                        let listed = self.listed(brick, local).unwrap_or(&[]);
                        slabs.push(self.cell_slab(surface, b, local, listed, &mut scratch));
                        triangles.extend_from_slice(listed);
                        ordered.extend(scratch.keyed.iter().map(|&(_, t)| t));
                    }
                }
                blocks::sort_unique(&mut triangles, &mut scratch.bits);
                let brick_slab = self.brick_slab_over(surface, b, &triangles, &mut scratch);
                (slabs, brick_slab, ordered, triangles)
            })
            .collect();
        // The lists follow each other in the same order of surface cells, so the ordered
        // ones replace them whole.
        let refs: Vec<u32> = per_brick
            .par_iter()
            .flat_map_iter(|(_, _, o, _)| o.iter().copied())
            .collect();
        debug_assert_eq!(refs.len(), self.triangle_refs.len());
        if refs.len() == self.triangle_refs.len() {
            self.triangle_refs = refs.into();
        }
        self.brick_slabs = per_brick
            .iter()
            .map(|&(_, s, _, _)| s)
            .collect::<Vec<_>>()
            .into();
        self.slabs = per_brick
            .par_iter()
            .flat_map_iter(|(slabs, _, _, _)| slabs.iter().copied())
            .collect::<Vec<_>>()
            .into();
        let [rx, ry, rz] = region_dims(self.brick_dims).map(|d| d as usize);
        // A detailed brick's entry is its index among them, that of `per_brick`.
        let of_brick = |entry: u32, out: &mut Vec<u32>| {
            if let Some((_, _, _, listed)) = per_brick.get(entry as usize) {
                out.extend_from_slice(listed);
            }
        };
        self.region_slabs = (0..rx * ry * rz)
            .into_par_iter()
            .map(|r| self.region_slab(surface, r, &of_brick))
            .collect::<Vec<_>>()
            .into();
    }

    /// The slab of detailed brick `brick` ([`FULL_SLAB`] when out of range): where in the
    /// brick the triangles of its surface cells lie.
    #[inline]
    pub(crate) fn brick_slab(&self, brick: u32) -> u32 {
        self.brick_slabs
            .get(brick as usize)
            .copied()
            .unwrap_or(FULL_SLAB)
    }

    /// The parameters `(from, to)` between which the segment `p0 → p1` (metres) lies in
    /// the slab of detailed brick `brick`, the brick of cell `c` (see [`interval`]):
    /// outside them it crosses no triangle at a point of the brick. `None` when it never
    /// lies in the slab.
    #[inline]
    pub(crate) fn brick_window(
        &self,
        brick: u32,
        c: [u32; 3],
        p0: DVec3,
        p1: DVec3,
    ) -> Option<(f64, f64)> {
        self.window(self.brick_slab(brick), BRICK_SIDE, c, p0, p1)
    }

    /// As [`brick_window`](Self::brick_window) for region `region` (an index of
    /// [`look_region`](VoxelMap::look_region)), the region of cell `c`.
    #[inline]
    pub(crate) fn region_window(
        &self,
        region: u32,
        c: [u32; 3],
        p0: DVec3,
        p1: DVec3,
    ) -> Option<(f64, f64)> {
        let slab = self
            .region_slabs
            .get(region as usize)
            .copied()
            .unwrap_or(FULL_FINE_SLAB);
        let (centre, side) = self.block_of(c, REGION_SIDE);
        fine_interval(slab, centre, side, p0, p1)
    }

    /// The window of the segment in `slab`, the slab of the block of `side` cells (a
    /// power of two) that holds cell `c`.
    #[inline]
    fn window(
        &self,
        slab: u32,
        side: u32,
        c: [u32; 3],
        p0: DVec3,
        p1: DVec3,
    ) -> Option<(f64, f64)> {
        let (centre, side) = self.block_of(c, side);
        interval(slab, centre, side, p0, p1)
    }

    /// The centre and the side (metres) of the block of `side` cells (a power of two)
    /// that holds cell `c`.
    #[inline]
    fn block_of(&self, c: [u32; 3], side: u32) -> (DVec3, f64) {
        let corner = c.map(|v| v & !(side - 1));
        let side = f64::from(side) * self.grid.cell_size();
        let (lo, _) = self.grid.cell_bounds(corner);
        (lo + DVec3::splat(0.5 * side), side)
    }

    /// The slab of surface cell `s` ([`FULL_SLAB`] when out of range).
    #[inline]
    pub(crate) fn slab(&self, s: usize) -> u32 {
        self.slabs.get(s).copied().unwrap_or(FULL_SLAB)
    }
}

mod blocks;
#[cfg(test)]
mod tests;
