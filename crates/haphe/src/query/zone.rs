//! Clear zones: the room in front of (and behind) a triangle where a short proxy move
//! provably meets nothing, so that the tick can skip its crossing and touching searches.
//!
//! A proxy sliding on a face moves a skin's width above it. Over a convex or flat patch of
//! surface nothing else comes near that path: every triangle around lies below the face's
//! plane. The zone of triangle `T` records how far the triangles near `T` rise above (and
//! sink below) `T`'s plane; a move whose two ends stay over `T`'s neighbourhood, higher
//! than that rise plus the probe's reach and lower than the zone's height, is then farther
//! than the reach from every triangle — no crossing and no touching, exactly as the
//! searches would find.

use glam::DVec3;

use super::behind::{AxisPlane, lies_behind};
use crate::map::{CellBox, VoxelMap};
use crate::mesh::{Surface, TriFrame, TriId};

/// How far a zone spreads beyond its triangle, in barycentric weight: its footprint holds
/// the points whose weights are all at least `-ZONE_SPREAD` (the triangle scaled by
/// `1 + 3·ZONE_SPREAD` about its centroid, so about one ring of neighbours).
pub const ZONE_SPREAD: f64 = 0.5;

/// Height of a zone over its triangle's plane (and depth behind it) as a fraction of the
/// map's cell size; also the distance the gathered cells reach beyond the zone.
pub(crate) const ZONE_HEIGHT_OF_CELL: f64 = 0.0625;

/// Most map cells read to build one zone; a triangle whose zone would read more (a large
/// triangle over fine cells) gets [`ClearZone::NONE`].
pub const MAX_ZONE_CELLS: u64 = 512;

/// Relative rounding allowed in a zone's heights and in the tests against it: far above
/// the rounding of a plane height in `f64`, far below any skin.
const ZONE_ROUNDING: f64 = 1e-9;

/// The clear zone of one triangle `T` (object frame, metres).
///
/// Every triangle other than `T` either rises at most `front` metres above `T`'s plane
/// (on the side of its normal) and sinks at most `back` metres behind it, or keeps at
/// least `height` metres from the zone: the points whose barycentric weights in `T` are
/// all at least `-`[`ZONE_SPREAD`] and whose height over `T`'s plane lies within
/// `±height`. So a point of the zone at height `h > front` is at least
/// `min(h − front, height)` from every triangle, `T` included (behind the plane, likewise
/// with `back`).
///
/// When `below` holds, more is known: every other triangle of the zone lies on or behind
/// `T`'s plane and meets it only outside `T`'s interior (shown exactly; see
/// `query/behind.rs`: in an axis plane by exact signs, in a tilted one only for corners
/// shared with `T`). A segment through the zone from in front of the plane then crosses
/// nothing before it crosses the plane, and where it crosses strictly inside `T`, `T` is
/// its first crossing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClearZone {
    /// Highest rise of a nearby triangle over `T`'s plane, metres (rounded up; ≥ 0).
    pub front: f32,
    /// Deepest sink of a nearby triangle behind `T`'s plane, metres (rounded up; ≥ 0).
    pub back: f32,
    /// Height (and depth) of the zone, and the distance every other triangle keeps from
    /// it, metres (rounded down).
    pub height: f32,
    /// Every other triangle of the zone lies on or behind `T`'s plane, meeting it only
    /// outside `T`'s interior (a convex or flat neighbourhood; see above).
    pub below: bool,
}

impl ClearZone {
    /// A zone that clears nothing (degenerate triangle, or one too large for its cells).
    pub const NONE: ClearZone = ClearZone {
        front: f32::INFINITY,
        back: f32::INFINITY,
        height: 0.0,
        below: false,
    };

    /// The zone of triangle `t` of `surface`, from the triangles that `map` lists in the
    /// cells around it.
    ///
    /// # Performance
    /// Reads at most [`MAX_ZONE_CELLS`] cells and every triangle listed there (a few
    /// microseconds for a triangle about a cell wide). No allocation.
    pub fn of(surface: &Surface, map: &VoxelMap, t: TriId) -> ClearZone {
        let Some((reach, height)) = Reach::of_triangle(surface, map, t) else {
            return ClearZone::NONE;
        };
        let grid = map.grid();
        let Some(cells) = map.clip_cells(CellBox::around(grid, reach.lo, reach.hi)) else {
            // The zone lies beyond the grid, where there is no triangle at all.
            return ClearZone {
                front: 0.0,
                back: 0.0,
                height: round_down(height),
                below: true,
            };
        };
        if cells.count() > MAX_ZONE_CELLS {
            return ClearZone::NONE;
        }
        let (front, back, below) = measure(surface, map, t, &reach, cells);
        // The rounding of those heights: a few ulps of the zone's extent.
        let slack = ZONE_ROUNDING * (reach.hi - reach.lo).max_element();
        ClearZone {
            front: round_up(front + slack),
            back: round_up(back + slack),
            height: round_down(height),
            below,
        }
    }

    /// The box (object frame) holding every point whose triangles decide the zone of
    /// triangle `t`: a triangle with no point in it leaves the zone unchanged. `None` for
    /// `t` out of range or a degenerate triangle (its zone is [`ClearZone::NONE`]).
    pub(crate) fn reach_box(surface: &Surface, map: &VoxelMap, t: TriId) -> Option<(DVec3, DVec3)> {
        let (reach, _) = Reach::of_triangle(surface, map, t)?;
        // The cells `of` reads reach a cell beyond the box.
        let h = map.grid().cell_size();
        Some((reach.lo - DVec3::splat(h), reach.hi + DVec3::splat(h)))
    }

    /// Whether the straight move `from → to` (object frame) of a point, with every point
    /// within `reach` metres of it, keeps more than `reach` from every triangle of the
    /// surface: both ends lie in the zone of `frame`'s triangle (its frame), on the same
    /// side of its plane and beyond that side's rise by more than `reach`. Then no probe of
    /// the move meets a triangle and no triangle lies within `reach` of its end.
    ///
    /// # Real-time
    /// Constant time, no allocation, no panic; `false` for non-finite input.
    #[inline]
    pub fn clears(&self, frame: &TriFrame, from: DVec3, to: DVec3, reach: f64) -> bool {
        let (h0, h1) = (frame.height(from), frame.height(to));
        let (near, far, rise) = if h0 > 0.0 && h1 > 0.0 {
            (h0.min(h1), h0.max(h1), f64::from(self.front))
        } else if h0 < 0.0 && h1 < 0.0 {
            (-h0.max(h1), -h0.min(h1), f64::from(self.back))
        } else {
            return false;
        };
        let height = f64::from(self.height);
        let slack = self.slack(offset(frame, from).max(offset(frame, to)));
        far <= height - slack
            && near - rise > reach + slack
            && height > reach + slack
            && in_footprint(frame.barycentric(from))
            && in_footprint(frame.barycentric(to))
    }

    /// Whether `p` (object frame) lies in the zone of `frame`'s triangle in front of its
    /// plane: over the footprint, higher than the rounding of its height and lower than the
    /// zone's top by as much.
    #[inline]
    pub(crate) fn holds_in_front(&self, frame: &TriFrame, p: DVec3) -> bool {
        let h = frame.height(p);
        let slack = self.slack(offset(frame, p));
        h > slack && h < f64::from(self.height) - slack && in_footprint(frame.barycentric(p))
    }

    /// The rounding allowed in a test against the zone of points at most `offset` metres
    /// (in any coordinate) from the frame's origin: of their heights, and of the frame
    /// change before them.
    #[inline]
    fn slack(&self, offset: f64) -> f64 {
        ZONE_ROUNDING * f64::from(self.height) + 1e-15 * offset
    }

    /// The zone packed into 64 bits (never 0, which [`ClearZone::from_bits`] never sees).
    pub(crate) fn to_bits(self) -> u64 {
        // `height` is not stored: it is the same for every triangle of a map.
        u64::from(self.front.to_bits())
            | (u64::from(self.back.to_bits()) << 32)
            | ZONE_SET
            | if self.below { ZONE_BELOW } else { 0 }
    }
}

/// Whether barycentric weights `w` lie in a zone's footprint.
#[inline]
fn in_footprint(w: [f64; 3]) -> bool {
    w.iter().all(|&w| w >= -ZONE_SPREAD)
}

/// The box of a zone grown by its height (what other triangles keep from it) and a little
/// for the rounding of the cell lookup, and the planes that bound it.
struct Reach {
    lo: DVec3,
    hi: DVec3,
    /// The zone's height, grown by the rounding.
    grow: f64,
    /// The triangle's unit normal, and the outward unit normals of the spread triangle's
    /// edges (in its plane) with their offsets from the frame's origin.
    sides: [(DVec3, f64); 4],
}

impl Reach {
    /// The reach of triangle `t`'s zone on `map`, and the zone's height; `None` for `t`
    /// out of range, a degenerate triangle or a grid without a usable height (the zone is
    /// then [`ClearZone::NONE`]).
    fn of_triangle(surface: &Surface, map: &VoxelMap, t: TriId) -> Option<(Reach, f64)> {
        if t.index() >= surface.triangle_count() {
            return None;
        }
        let frame = surface.frame(t);
        let height = map.grid().cell_size() * ZONE_HEIGHT_OF_CELL;
        if frame.is_degenerate() || !(height > 0.0 && height.is_finite()) {
            return None;
        }
        Some((Reach::of(frame, surface.corners(t), height), height))
    }

    /// The reach of the zone of height `height` over the triangle of `frame` with `corners`:
    /// the triangle spread by [`ZONE_SPREAD`], lifted by `±height` along its normal.
    fn of(frame: &TriFrame, corners: [DVec3; 3], height: f64) -> Reach {
        let centroid = (corners[0] + corners[1] + corners[2]) / 3.0;
        let scale = 1.0 + 3.0 * ZONE_SPREAD;
        let spread = corners.map(|v| centroid + scale * (v - centroid));
        let (mut lo, mut hi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
        for v in spread {
            for lift in [-height, height] {
                let x = v + lift * frame.normal;
                (lo, hi) = (lo.min(x), hi.max(x));
            }
        }
        let grow = height * (1.0 + ZONE_ROUNDING);
        let mut sides = [(frame.normal, 0.0); 4];
        for i in 0..3 {
            let edge = spread[(i + 2) % 3] - spread[(i + 1) % 3];
            let out = edge.cross(frame.normal).normalize_or_zero();
            sides[i + 1] = (out, out.dot(spread[(i + 1) % 3] - frame.origin));
        }
        Reach {
            lo: lo - DVec3::splat(grow),
            hi: hi + DVec3::splat(grow),
            grow,
            sides,
        }
    }

    /// Whether the cell of `grid` whose centre lies at `centre` from the frame's origin
    /// (half a side `half`) meets the grown zone: within `2·height` of the plane and within
    /// `height` of the spread triangle's edges (in its plane). Only those cells matter.
    #[inline]
    fn meets(&self, centre: DVec3, half: f64) -> bool {
        let (n, _) = self.sides[0];
        let within_slab = n.dot(centre).abs() - half * n.abs().element_sum() <= 2.0 * self.grow;
        within_slab
            && self.sides[1..]
                .iter()
                .all(|&(m, at)| m.dot(centre) - at - half * m.abs().element_sum() <= self.grow)
    }
}

/// How far the triangles other than `t` that `map` lists in the `cells` meeting `reach`
/// rise above `t`'s plane and sink behind it (metres, not yet rounded), and whether they
/// all lie behind it (see [`ClearZone::below`]).
fn measure(
    surface: &Surface,
    map: &VoxelMap,
    t: TriId,
    reach: &Reach,
    cells: CellBox,
) -> (f64, f64, bool) {
    let frame = surface.frame(t);
    let grid = map.grid();
    let half = 0.5 * grid.cell_size();
    let (mut front, mut back) = (0.0f64, 0.0f64);
    let mut below = true;
    let own = surface.triangle(t);
    let axis_plane = AxisPlane::of(surface.corners(t), frame.normal);
    let (triangles, vertices) = (surface.triangles(), surface.vertices());
    // Triangles already measured (a triangle is listed in every cell it overlaps): a small
    // open-addressed set on the stack; when it is full, measuring again is merely slower.
    let mut seen = [u32::MAX; SEEN_SLOTS];
    map.visit_cells(cells, |cell, listed| {
        if !reach.meets(grid.cell_centre(cell) - frame.origin, half) {
            return;
        }
        for &u in listed {
            if u == t.0 || !first_sight(&mut seen, u) {
                continue;
            }
            let ids = triangles[u as usize];
            let corners = ids.map(|v| vertices[v as usize]);
            let heights = corners.map(|p| frame.height(p));
            below = below && lies_behind(frame, own, axis_plane.as_ref(), ids, corners, heights);
            for h in heights {
                front = front.max(h);
                back = back.max(-h);
            }
        }
    });
    (front, back, below)
}

/// The largest coordinate distance of `p` from the origin of `frame`, metres.
#[inline]
fn offset(frame: &TriFrame, p: DVec3) -> f64 {
    (p - frame.origin).abs().max_element()
}

/// Slots of the set of triangles already measured while building a zone.
const SEEN_SLOTS: usize = 256;

/// Whether `u` is not in `seen` yet; adds it when there is room near its slot.
#[inline]
fn first_sight(seen: &mut [u32; SEEN_SLOTS], u: u32) -> bool {
    let start = (u.wrapping_mul(0x9E37_79B1) >> 24) as usize;
    for k in 0..4 {
        let slot = &mut seen[(start + k) % SEEN_SLOTS];
        if *slot == u {
            return false;
        }
        if *slot == u32::MAX {
            *slot = u;
            return true;
        }
    }
    true
}

/// Marks a stored zone (a rise is never negative, so its sign bit is free).
const ZONE_SET: u64 = 1 << 31;

/// The bit of a packed zone that holds `below` (the sign bit of `back`, never set: `back`
/// is at least 0).
const ZONE_BELOW: u64 = 1 << 63;

/// A zone unpacked from [`ClearZone::to_bits`], with the map's zone height.
pub(crate) fn zone_from_bits(bits: u64, height: f32) -> ClearZone {
    ClearZone {
        front: f32::from_bits((bits as u32) & !(ZONE_SET as u32)),
        back: f32::from_bits(((bits & !ZONE_BELOW) >> 32) as u32),
        height,
        below: bits & ZONE_BELOW != 0,
    }
}

/// The zone height of a map's triangles, metres (rounded down).
pub(crate) fn zone_height(map: &VoxelMap) -> f32 {
    round_down(map.grid().cell_size() * ZONE_HEIGHT_OF_CELL)
}

/// `x` as an `f32` no smaller than it (infinity for NaN).
fn round_up(x: f64) -> f32 {
    let f = x as f32;
    if f64::from(f) >= x {
        f
    } else if x.is_nan() {
        f32::INFINITY
    } else {
        f.next_up()
    }
}

/// `x` as an `f32` no larger than it (0 for NaN).
fn round_down(x: f64) -> f32 {
    let f = x as f32;
    if f64::from(f) <= x {
        f
    } else if x.is_nan() {
        0.0
    } else {
        f.next_down()
    }
}
