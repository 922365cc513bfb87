//! Segment crossing: the first place where a segment meets the surface (object frame).

use glam::DVec3;

use super::frame_error::FRAME_DIRECTION_ERROR;
use super::{Segment, SegmentHit, intersect_segment_framed};
use crate::map::{CellPart, Found, VoxelMap};
use crate::mesh::{Surface, TriId};

/// Where a segment first meets the surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Crossing {
    /// Parameter along the segment, `p0 + t (p1 − p0)`, in `[0, 1]`.
    pub t: f64,
    /// The triangle crossed (the surface's index; see
    /// [`Surface::source_triangle`](crate::mesh::Surface::source_triangle)).
    pub triangle: TriId,
    /// Barycentric weights of the crossing point for the triangle's corners.
    pub weights: [f64; 3],
    /// The crossing point, metres, object frame.
    pub point: DVec3,
    /// Unit face normal of the triangle (pointing out of a solid).
    pub face_normal: DVec3,
    /// The segment passes from the front of the triangle to its back (into a solid).
    pub entering: bool,
}

/// The shortest segment, in cells, for which [`first_crossing`] skips free space in
/// strides and tests slabs: a shorter one crosses too few cells for that to save their
/// look-ups (the short moves of a haptic tick walk cell by cell, after testing their
/// start cell alone).
const SKIP_MIN_LENGTH: f64 = 4.0;

/// Triangles remembered in a plain list before the table of [`TESTED_SLOTS`] is used: most
/// queries meet fewer, and a list needs no clearing.
const TESTED_LIST: usize = 32;

/// Slots of the per-query table of triangles already tested (a power of two), used once
/// the list is full. A segment that meets more distinct triangles than fit simply tests
/// some twice (the answer is the same); see [`first_crossing`].
const TESTED_SLOTS: usize = 256;

/// A fixed-size, allocation-free set of triangle indices: a short list, then (only for
/// the rare query that meets more triangles) a hash table with open addressing. Nothing
/// is cleared per query beyond the list's length.
pub(crate) struct Tested {
    list: [u32; TESTED_LIST],
    len: usize,
    table: Option<[u32; TESTED_SLOTS]>,
    table_len: usize,
}

impl Tested {
    pub fn new() -> Tested {
        Tested {
            list: [0; TESTED_LIST],
            len: 0,
            table: None,
            table_len: 0,
        }
    }

    /// Inserts `t`; `false` when it was already there. When the table is three quarters
    /// full, it answers `true` without remembering (`overflowed` says so).
    #[inline]
    pub fn insert(&mut self, t: u32) -> bool {
        if self.table.is_none() {
            if self.list[..self.len].contains(&t) {
                return false;
            }
            if self.len < TESTED_LIST {
                self.list[self.len] = t;
                self.len += 1;
                return true;
            }
        }
        self.insert_in_table(t)
    }

    #[cold]
    fn insert_in_table(&mut self, t: u32) -> bool {
        if self.table.is_none() {
            self.table = Some([u32::MAX; TESTED_SLOTS]);
            for k in 0..self.len {
                self.table_insert(self.list[k]);
            }
        }
        self.table_insert(t)
    }

    fn table_insert(&mut self, t: u32) -> bool {
        if self.overflowed() {
            return true;
        }
        let Some(slots) = self.table.as_mut() else {
            return true;
        };
        let mut i = (t.wrapping_mul(0x9E37_79B1) >> 24) as usize % TESTED_SLOTS;
        loop {
            match slots[i] {
                u32::MAX => {
                    slots[i] = t;
                    self.table_len += 1;
                    return true;
                }
                s if s == t => return false,
                _ => i = (i + 1) % TESTED_SLOTS,
            }
        }
    }

    /// Whether the table stopped remembering.
    pub fn overflowed(&self) -> bool {
        4 * self.table_len >= 3 * TESTED_SLOTS
    }
}

/// The first crossing of the segment from `p0` to `p1` (metres, object frame) with the
/// surface, walking the map's cells in order (3D-DDA) and testing each triangle of each
/// surface cell (once, as far as the per-query table holds) with the watertight test.
/// Among hits at the same `t`, the lowest triangle index wins, as in
/// [`first_crossing_brute_force`], which this always equals.
///
/// Free space costs little on a segment longer than a few cells: the walk crosses a
/// cube of the map known to hold no surface cell in one stride — far from the surface a
/// cube of regions of 32³ cells, nearer a cube of bricks of 8³ cells (both derived from
/// where the surface cells are, the bricks' through [`VoxelMap::reach`]), and in a brick
/// that holds surface cells a free block of 4³ cells of its surface mask — so crossing
/// empty space takes a few strides however fine the grid, reading mostly memory that
/// stays in the cache. In a region and in a brick that hold surface cells, the cells
/// before the segment reaches the layer in which the block's triangles lie (its slab,
/// four bytes) and after it leaves it are skipped in one stride each. In a surface cell,
/// a part of the segment that passes beside the layer the cell's triangles lie in (the
/// cell's slab) skips them without reading their indices or frames, and one that passes
/// through it is filtered against them on its part in the layer only; once a crossing is
/// found, the cell's remaining triangles are filtered on the part before it (so a thin
/// wall's far face, listed in the same cells as its near face, costs no exact test when
/// the near face comes first: a cell's list is ordered along its slab's direction and
/// taken from the side the segment comes from). A triangle whose plane the segment's
/// line meets beyond an edge is filtered out from its frame, and one it crosses well
/// inside is answered from its plane's orientations and its frame (the watertight test's
/// answer, without its shear of the corners; see `intersect_segment_framed`). On a
/// surface of 2048 triangles or more, the frames and corners of a cell's triangles are
/// fetched together before they are tested. It never reads the clearances of free cells,
/// which are cold when the segment comes from far away.
///
/// A segment longer than a million times the diagonal of the surface's bounding box
/// (`LONG_SEGMENT_FACTOR`: 200 km for a 20 cm object) that reaches the box is
/// answered by testing every triangle, as the brute force does: along such a segment the
/// walk's parameters cannot place the cells' boundaries exactly.
///
/// # Real-time
/// No allocation (a list of 32 and, only when more triangles are met, a 1 KiB table on
/// the stack), no lock, no panic; visits at most
/// the grid's `dims[0] + dims[1] + dims[2]` cells (or, for a segment longer than
/// a million times the object, tests every triangle once). Non-finite input
/// gives `None`.
pub fn first_crossing(surface: &Surface, map: &VoxelMap, p0: DVec3, p1: DVec3) -> Option<Crossing> {
    first_crossing_where(surface, map, p0, p1, |_| true)
}

/// A segment longer than this many times the object's bounding-box diagonal is answered
/// by testing every triangle (see [`first_crossing`]).
pub const LONG_SEGMENT_FACTOR: f64 = 1e6;

/// Whether `p0 → p1` is longer than [`LONG_SEGMENT_FACTOR`] times the diagonal of the
/// surface's bounding box.
fn is_far_longer_than(surface: &Surface, p0: DVec3, p1: DVec3) -> bool {
    let (lo, hi) = surface.bounds();
    p0.distance(p1) > LONG_SEGMENT_FACTOR * (hi - lo).length()
}

/// [`first_crossing`] counting only the crossings that `accept` keeps (for example only
/// entering ones, `|hit| hit.entering`): the first accepted crossing, lowest triangle index
/// on ties. Same real-time bounds.
pub fn first_crossing_where(
    surface: &Surface,
    map: &VoxelMap,
    p0: DVec3,
    p1: DVec3,
    accept: impl Fn(&SegmentHit) -> bool,
) -> Option<Crossing> {
    if super::bounds::beyond_bounds(surface, p0, p1, 0.0) {
        return None;
    }
    // A segment far longer than the object: the walk's parameters along it lose the
    // precision that places cell boundaries, so the exact test of every triangle answers
    // instead (bounded work, the same answer as the oracle).
    if is_far_longer_than(surface, p0, p1) {
        return first_crossing_brute_force_where(surface, p0, p1, accept);
    }
    // Prepared on first use: most queries of a haptic tick skip every triangle before the
    // exact test.
    let mut prepared: Option<Segment> = None;
    let mut segment = || *prepared.get_or_insert_with(|| Segment::new(p0, p1));
    let h = map.grid().cell_size();
    // A long segment strides over free space and reads slabs; a short one (a haptic
    // tick's move) walks cell by cell, and first tests its start cell alone.
    let skips = p0.distance_squared(p1) >= (SKIP_MIN_LENGTH * h) * (SKIP_MIN_LENGTH * h);
    if !skips && let Some(cell) = map.grid().cell_of(p0) {
        let mut best: Option<(SegmentHit, u32)> = None;
        let mut until = p1;
        let margin = plane_margin(map);
        for &t in map.triangles_in(cell) {
            if cannot_cross(surface, t, p0, until, margin) {
                continue;
            }
            if let Some(hit) = better_hit(surface, t, (p0, p1), &mut segment, &accept, best) {
                best = Some((hit, t));
                until = point_at(p0, p1, filter_end(hit.t));
            }
        }
        // The common haptic cases. Cells are convex and list every triangle that overlaps
        // them, so a crossing at a point inside the start cell is tested here: when the
        // whole segment lies in that cell (a short move), the best hit is the answer, and
        // so it is when the hit comes before the segment leaves the cell (a press whose
        // surface is near the proxy), with a margin for the rounding of the cell's
        // boundaries. No walk, no table of tested triangles.
        if map.grid().cell_of(p1) == Some(cell)
            || best.is_some_and(|(hit, _)| {
                hit.t < exit_parameter(map, cell, p0, p1) - map.boundary_margin(p0, p1)
            })
        {
            return best.map(|(hit, t)| crossing_from_hit(surface, hit, t));
        }
    }
    let mut tested = Tested::new();
    let mut best: Option<(SegmentHit, u32)> = None;
    let plane_margin = plane_margin(map);
    let fetch = surface.triangle_count() >= FETCH_AHEAD_MIN_TRIANGLES;
    // Each cell's triangles are filtered on the part of the segment in the cell (and in
    // its slab), up to where a crossing can still improve on the best: a triangle crossed
    // at a point in this cell is crossed on that part, so the filter never skips it here;
    // one it skips may be crossed in a later cell, which lists it too, so it is not yet
    // tested. Long segments that graze a surface (along a thin plate, say) thus test
    // exactly only the triangles near where they pass.
    map.cast_segment(p0, p1, skips, |part| {
        let CellPart {
            triangles,
            forward,
            from,
            mut to,
        } = part;
        let (q0, mut q1) = (point_at(p0, p1, from), point_at(p0, p1, to));
        if fetch {
            fetch_ahead(surface, triangles);
        }
        let mut found = None;
        let n = triangles.len();
        for i in 0..n {
            let t = triangles[if forward { i } else { n - 1 - i }];
            if cannot_cross(surface, t, q0, q1, plane_margin) || !tested.insert(t) {
                continue;
            }
            if let Some(hit) = better_hit(surface, t, (p0, p1), &mut segment, &accept, best) {
                best = Some((hit, t));
                let until = filter_end(hit.t);
                found = Some(Found { t: hit.t, until });
                // The cell's remaining triangles too are filtered on the part before it
                // (a thin wall's far face, listed in the same cell as its near one).
                if until < to {
                    (to, q1) = (until, point_at(p0, p1, until));
                }
            }
        }
        found
    });
    best.map(|(hit, t)| crossing_from_hit(surface, hit, t))
}

/// The hit of triangle `t` by the segment `p0 → p1` (`segment` prepares it when the
/// whole watertight test needs it) when `accept` keeps it and it comes before `best`, or
/// at the same parameter on a triangle of lower index: the crossing's order.
#[inline(always)]
fn better_hit(
    surface: &Surface,
    t: u32,
    (p0, p1): (DVec3, DVec3),
    segment: &mut impl FnMut() -> Segment,
    accept: &impl Fn(&SegmentHit) -> bool,
    best: Option<(SegmentHit, u32)>,
) -> Option<SegmentHit> {
    triangle_hit(surface, TriId(t), (p0, p1), segment)
        .filter(|hit| accept(hit))
        .filter(|hit| best.is_none_or(|(b, bt)| hit.t < b.t || (hit.t == b.t && t < bt)))
}

/// The watertight hit of the segment `p0 → p1` (metres, object frame) on triangle `t` of
/// `surface`, answered from the triangle's frame where that is certain
/// (`intersect_segment_framed`); `segment` prepares the segment when the whole test runs.
/// The one segment–triangle test of the queries, the oracles and the clear zones.
#[inline(always)]
pub(crate) fn triangle_hit(
    surface: &Surface,
    t: TriId,
    (p0, p1): (DVec3, DVec3),
    segment: impl FnOnce() -> Segment,
) -> Option<SegmentHit> {
    intersect_segment_framed(p0, p1, surface.corners(t), surface.frame(t), segment)
}

/// The fewest triangles for which [`first_crossing`] fetches a cell's frames and corners
/// ahead ([`fetch_ahead`]): a smaller surface (about 190 bytes a triangle, under 400 KiB)
/// stays in the core's own cache between queries, where the reads ahead are only work.
/// Measured on the 1k thin plate: about 3 % off the random segments' p99.
const FETCH_AHEAD_MIN_TRIANGLES: usize = 2048;

/// Reads, for each of `triangles`, a word of its frame's two cache lines, its corner
/// indices and a word of each corner, discarding what it read: a prefetch written as
/// reads. On a large mesh these lines are cold and the test loop that follows reaches
/// them one after another behind its branches; read here, in loops without branches,
/// they are fetched from memory together (the frames and indices at once, the corners
/// once their indices arrive), so the cell costs about two memory latencies instead of
/// two per triangle. Measured: see docs/performance.md.
#[inline]
fn fetch_ahead(surface: &Surface, triangles: &[u32]) {
    let mut sink = 0u64;
    for &t in triangles {
        let frame = surface.frame(TriId(t));
        sink ^= frame.origin.x.to_bits() ^ frame.normal.z.to_bits();
        sink ^= u64::from(surface.triangle(TriId(t))[0]);
    }
    for &t in triangles {
        let [a, b, c] = surface.corners(TriId(t));
        sink ^= a.x.to_bits() ^ b.x.to_bits() ^ c.x.to_bits();
    }
    std::hint::black_box(sink);
}

/// How far past the best crossing so far (in units of `t`) the cheap filter keeps looking:
/// far above the rounding of a crossing's parameter (a relative `2⁻⁴⁰`), so that a
/// triangle crossed at the same parameter or before is never skipped.
const FILTER_PAST_BEST: f64 = 1e-6;

/// The parameter where the part of the segment on which a crossing can still improve on
/// one at parameter `t` (ties included) ends: what [`cannot_cross`] is given once a
/// crossing is known. A triangle crossed at `t` or before has its crossing on that part,
/// and the filter's margins cover the rounding of the point computed from it.
#[inline]
fn filter_end(t: f64) -> f64 {
    (t + FILTER_PAST_BEST).min(1.0)
}

/// The point at parameter `t` of the segment `p0 → p1` (`p1` itself at 1).
#[inline]
fn point_at(p0: DVec3, p1: DVec3, t: f64) -> DVec3 {
    if t >= 1.0 { p1 } else { p0 + t * (p1 - p0) }
}

/// The parameter `t` at which the segment `p0 + t (p1 − p0)`, starting in `cell`, leaves
/// that cell's box (up to rounding; `+∞` for a zero-length segment).
#[inline]
fn exit_parameter(map: &VoxelMap, cell: [u32; 3], p0: DVec3, p1: DVec3) -> f64 {
    let (lo, hi) = map.grid().cell_bounds(cell);
    let d = p1 - p0;
    let mut exit = f64::INFINITY;
    for k in 0..3 {
        if d[k] > 0.0 {
            exit = exit.min((hi[k] - p0[k]) / d[k]);
        } else if d[k] < 0.0 {
            exit = exit.min((lo[k] - p0[k]) / d[k]);
        }
    }
    exit
}

/// Whether the segment `p0 → p1` certainly misses triangle `t`, by tests on the
/// triangle's frame that are cheaper than the watertight test: both ends lie on the same
/// side of the triangle's plane; or, for a segment not nearly parallel to the plane, its
/// line meets the plane beyond an edge (so the line misses the triangle, wherever on it
/// `p0` and `p1` lie); or, for one nearly parallel, both ends lie beyond the same edge
/// (outside the same side plane of the triangle's prism, where one barycentric weight of
/// their projections is negative). Each test keeps a margin above the rounding of the
/// frame and of the products (see [`FRAME_DIRECTION_ERROR`]), so it only skips triangles
/// the watertight test would miss too: it never changes an answer.
#[inline(always)]
pub(crate) fn cannot_cross(surface: &Surface, t: u32, p0: DVec3, p1: DVec3, margin: f64) -> bool {
    let frame = surface.frame(TriId(t));
    let d0 = p0 - frame.origin;
    let d1 = p1 - frame.origin;
    let extent = d0.abs().max(d1.abs()).max_element();
    let h0 = frame.normal.dot(d0);
    let h1 = frame.normal.dot(d1);
    let height_margin = margin + FRAME_DIRECTION_ERROR * extent;
    if (h0 > height_margin && h1 > height_margin) || (h0 < -height_margin && h1 < -height_margin) {
        return true;
    }
    let dual_norm = frame.dual_b.abs().element_sum() + frame.dual_c.abs().element_sum();
    let weight_margin = FRAME_DIRECTION_ERROR * dual_norm * extent;
    // The line of the part meets the plane, far enough from parallel that where is known
    // well: within `2 hm / (H − 2 hm) ≤ 4 hm / H` (in units of the part) of `h0 / H`, with
    // `hm` the height margin and `H = |h0 − h1| > 4 hm`, since each height is within `hm`
    // of the exact one. That point (at most half a part beyond its ends, so within twice
    // `extent` of the first corner) beyond an edge by more than its weights' margin: the
    // line misses the triangle, and the exact test too. The weights are taken times `H`,
    // with no division.
    let across = (h0 - h1).abs();
    if across > 4.0 * height_margin {
        let (sign, part) = (1f64.copysign(h0 - h1), d1 - d0);
        let x = across * d0 + (sign * h0) * part;
        let (u, v) = (frame.dual_b.dot(x), frame.dual_c.dot(x));
        let m = 2.0 * weight_margin * across
            + dual_norm * 4.0 * height_margin * part.abs().max_element();
        return u < -m || v < -m || across - u - v < -m;
    }
    // Nearly parallel: both ends beyond the same edge.
    let (u0, v0) = (frame.dual_b.dot(d0), frame.dual_c.dot(d0));
    let (u1, v1) = (frame.dual_b.dot(d1), frame.dual_c.dot(d1));
    (u0 < -weight_margin && u1 < -weight_margin)
        || (v0 < -weight_margin && v1 < -weight_margin)
        || (1.0 - u0 - v0 < -weight_margin && 1.0 - u1 - v1 < -weight_margin)
}

/// The distance from a triangle's plane (metres) beyond which [`cannot_cross`] trusts the
/// sign of a height of a point at its first corner: a billionth of a cell, some five
/// orders of magnitude above the rounding of heights at the coordinates a map covers.
pub(crate) fn plane_margin(map: &VoxelMap) -> f64 {
    1e-9 * map.grid().cell_size()
}

/// The first crossing by testing every triangle: the oracle for [`first_crossing`].
///
/// # Performance
/// `O(n)`: for tests and verification, never for a tick.
pub fn first_crossing_brute_force(surface: &Surface, p0: DVec3, p1: DVec3) -> Option<Crossing> {
    first_crossing_brute_force_where(surface, p0, p1, |_| true)
}

/// [`first_crossing_brute_force`] counting only the crossings that `accept` keeps: the
/// oracle for [`first_crossing_where`].
pub fn first_crossing_brute_force_where(
    surface: &Surface,
    p0: DVec3,
    p1: DVec3,
    accept: impl Fn(&SegmentHit) -> bool,
) -> Option<Crossing> {
    let segment = Segment::new(p0, p1);
    let mut best: Option<(SegmentHit, u32)> = None;
    for t in 0..surface.triangle_count() as u32 {
        if let Some(hit) = triangle_hit(surface, TriId(t), (p0, p1), || segment)
            && accept(&hit)
            && best.is_none_or(|(b, _)| hit.t < b.t)
        {
            best = Some((hit, t));
        }
    }
    best.map(|(hit, t)| crossing_from_hit(surface, hit, t))
}

/// Every crossing of the segment with the surface, by testing every triangle, in order of
/// `t` then triangle: the oracle for counting crossings.
pub fn all_crossings_brute_force(surface: &Surface, p0: DVec3, p1: DVec3) -> Vec<Crossing> {
    let segment = Segment::new(p0, p1);
    let mut hits: Vec<Crossing> = (0..surface.triangle_count() as u32)
        .filter_map(|t| {
            triangle_hit(surface, TriId(t), (p0, p1), || segment)
                .map(|hit| crossing_from_hit(surface, hit, t))
        })
        .collect();
    hits.sort_by(|a, b| a.t.total_cmp(&b.t).then(a.triangle.cmp(&b.triangle)));
    hits
}

/// The crossing of triangle `t` from its segment–triangle hit.
pub(crate) fn crossing_from_hit(surface: &Surface, hit: SegmentHit, t: u32) -> Crossing {
    let [a, b, c] = surface.corners(TriId(t));
    let [wa, wb, wc] = hit.weights;
    Crossing {
        t: hit.t,
        triangle: TriId(t),
        weights: hit.weights,
        point: wa * a + wb * b + wc * c,
        face_normal: surface.frame(TriId(t)).normal,
        entering: hit.entering,
    }
}

#[cfg(test)]
mod tests;
