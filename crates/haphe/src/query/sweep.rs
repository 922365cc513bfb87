//! A sphere swept along a segment against the triangles of a surface: the first place
//! where a tool of radius `r`, its centre moving from `a` to `b`, touches a triangle. The
//! query of the sphere proxy (a tool with a size), as [`first_crossing`](super::first_crossing)
//! is the point proxy's.
//!
//! The tool's centre may not enter the offset of a triangle by `r` (the Minkowski sum of
//! the triangle and the ball: the face moved out both ways, a cylinder round each edge, a
//! sphere round each vertex). Its distance to a triangle along a line is a convex function
//! of the parameter, so a centre that is not moving closer never will: a sweep meets a
//! triangle at most once, where the distance first falls to `r` on the way in. A centre that
//! starts within a probe's reach of the offset (or inside it) meets the triangle at the
//! start when it moves closer, and never when it does not.

use glam::DVec3;

use super::bounds::beyond_bounds;
use super::closest::closest_point_triangle;
use crate::map::{CellBox, VoxelMap};
use crate::mesh::{Surface, TriId};

/// Where a swept sphere first touches a triangle, object frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SphereContact {
    /// Parameter along the probe `a → b` (0 at `a`, 1 at `b`).
    pub t: f64,
    /// The triangle touched.
    pub triangle: TriId,
    /// The triangle's point nearest to the centre at the contact.
    pub point: DVec3,
    /// Unit normal of the offset surface at the contact: from `point` toward the centre
    /// (the free side). Where the centre lies on the triangle, the face normal turned
    /// against the motion.
    pub normal: DVec3,
}

/// Most cells of the map a sweep looks up per triangle of the surface before it tests
/// every triangle instead (a long sweep, or a radius of many cells).
const SWEEP_CELLS_PER_TRIANGLE: u64 = 4;

/// The first contact of the sphere of `radius` metres swept from `a` to `b` (object
/// frame) with a triangle of `surface`, counting a start within `reach` of a triangle's
/// offset as a contact at `t = 0` when the centre moves closer; the lowest triangle index
/// among contacts at the same `t`. A `one_sided` surface is touched only from the front
/// (the side of its normal). Equals [`first_sphere_contact_brute_force`]. Triangle `hint`
/// (a likely first contact: the one the tool rests on) is tested first: every triangle
/// after it is then tested only up to its contact, which spares most of the work when it
/// is the first and changes no answer.
///
/// # Work
/// Looks up the map's cells around the segment grown by `radius + reach`, piece by piece
/// along it (each piece about as long as `radius` or a cell), and stops after the first
/// piece whose triangles give a contact within it; testing every triangle when the cells
/// would cost more. No allocation, no lock, no panic; non-finite input gives `None`.
pub fn first_sphere_contact(
    surface: &Surface,
    map: &VoxelMap,
    (a, b): (DVec3, DVec3),
    (radius, reach, one_sided): (f64, f64, bool),
    hint: Option<TriId>,
) -> Option<SphereContact> {
    let grow = radius + reach;
    if !(a.is_finite() && b.is_finite() && grow.is_finite() && radius >= 0.0)
        || beyond_bounds(
            surface,
            a,
            b,
            grow + 1e-12 * a.abs().max(b.abs()).max_element(),
        )
    {
        return None;
    }
    let grid = map.grid();
    let length = a.distance(b);
    let piece = grow.max(grid.cell_size());
    let pieces = (length / piece).ceil().clamp(1.0, 1e6) as u64;
    let g = DVec3::splat(grow);
    let whole = CellBox::around(grid, a.min(b) - g, a.max(b) + g);
    let budget = SWEEP_CELLS_PER_TRIANGLE.saturating_mul(surface.triangle_count() as u64);
    if map.clip_cells(whole)?.count() > budget {
        return first_sphere_contact_brute_force(surface, (a, b), radius, reach, one_sided);
    }
    let mut best: Option<SphereContact> = None;
    // The triangles tested last: a triangle listed in several cells is tested once while
    // it stays among them (testing it again would change nothing).
    let mut seen = Seen::new();
    if let Some(t) = hint.filter(|t| t.index() < surface.triangle_count()) {
        seen.first_time(t.0);
        consider(surface, t, (a, b), (radius, reach), one_sided, &mut best);
    }
    for k in 0..pieces {
        let (s0, s1) = (k as f64 / pieces as f64, (k + 1) as f64 / pieces as f64);
        let (p0, p1) = (a + s0 * (b - a), a + s1 * (b - a));
        let cells = CellBox::around(grid, p0.min(p1) - g, p0.max(p1) + g).intersect(whole);
        let (mid, half) = (p0.midpoint(p1), p0.distance(p1) / 2.0);
        map.visit_cells(cells, |c, triangles| {
            if cell_beyond(grid, c, mid, half + grow) {
                return;
            }
            for &t in triangles.iter().filter(|&&t| seen.first_time(t)) {
                consider(
                    surface,
                    TriId(t),
                    (a, b),
                    (radius, reach),
                    one_sided,
                    &mut best,
                );
            }
        });
        // A contact at or before this piece's end is the first: a triangle touched earlier
        // lies within `radius` of an earlier piece, so in cells already visited.
        if best.is_some_and(|c| c.t <= s1) {
            break;
        }
    }
    best
}

/// The triangle nearest to the centre `p` (object frame) of a tool whose offset reaches
/// `grow` metres (its radius and a probe's reach), among those within `grow` of it; the
/// lowest triangle index among equally near ones: the same answer as
/// [`nearest_within`](super::nearest_within) and its brute force, searched in the cells
/// of the cube around `p` (each triangle once while it stays among the last tested, each
/// after a test of the sphere round its corners), or in every triangle when those cells
/// would cost more. How the tool notices a surface it comes to rest on.
///
/// # Real-time
/// No allocation, no lock, no panic; non-finite input gives `None`.
pub(crate) fn nearest_to_tool(
    surface: &Surface,
    map: &VoxelMap,
    p: DVec3,
    grow: f64,
) -> Option<super::NearTriangle> {
    if !(p.is_finite() && grow >= 0.0 && grow.is_finite())
        || beyond_bounds(surface, p, p, grow + 1e-12 * p.abs().max_element())
    {
        return None;
    }
    let g = DVec3::splat(grow);
    let cells = CellBox::around(map.grid(), p - g, p + g);
    let budget = SWEEP_CELLS_PER_TRIANGLE.saturating_mul(surface.triangle_count() as u64);
    if map.clip_cells(cells)?.count() > budget {
        return super::nearest_within_brute_force(surface, p, grow);
    }
    let mut best = None;
    let mut seen = Seen::new();
    map.visit_cells(cells, |c, triangles| {
        if cell_beyond(map.grid(), c, p, grow) {
            return;
        }
        for &t in triangles.iter().filter(|&&t| seen.first_time(t)) {
            let t = TriId(t);
            if !beyond_sphere(surface.corners(t), (p, DVec3::ZERO), grow) {
                super::near::consider(surface, t, p, grow, &mut best);
            }
        }
    });
    best
}

/// Whether cell `c`'s box lies farther than `distance` from `p`: then no triangle within
/// `distance` of `p` needs it (such a triangle's point near `p` lies in a cell nearer, which
/// lists it). A relative margin far above the rounding keeps the test on the safe side.
#[inline]
pub(crate) fn cell_beyond(grid: &crate::map::Grid, c: [u32; 3], p: DVec3, distance: f64) -> bool {
    let (lo, hi) = grid.cell_bounds(c);
    let gap = p.distance_squared(p.clamp(lo, hi));
    let reach = distance * (1.0 + 1e-9) + 1e-12 * p.abs().max_element();
    gap > reach * reach
}

/// The last few triangles a sweep tested, on the stack.
pub(crate) struct Seen {
    ids: [u32; SEEN],
    next: usize,
}

/// How many triangles [`Seen`] keeps: about those of the cells around a tool.
const SEEN: usize = 32;

impl Seen {
    pub(crate) fn new() -> Seen {
        Seen {
            ids: [u32::MAX; SEEN],
            next: 0,
        }
    }

    /// Whether `t` is not among the kept triangles (and keeps it, forgetting the oldest).
    #[inline]
    pub(crate) fn first_time(&mut self, t: u32) -> bool {
        if self.ids.contains(&t) {
            return false;
        }
        self.ids[self.next] = t;
        self.next = (self.next + 1) % SEEN;
        true
    }
}

/// [`first_sphere_contact`] by testing every triangle: the oracle.
///
/// # Performance
/// `O(n)`: for tests and verification, never for a tick.
pub fn first_sphere_contact_brute_force(
    surface: &Surface,
    (a, b): (DVec3, DVec3),
    radius: f64,
    reach: f64,
    one_sided: bool,
) -> Option<SphereContact> {
    if !(a.is_finite() && b.is_finite() && (radius + reach).is_finite() && radius >= 0.0) {
        return None;
    }
    let mut best = None;
    for t in 0..surface.triangle_count() {
        consider(
            surface,
            TriId(t as u32),
            (a, b),
            (radius, reach),
            one_sided,
            &mut best,
        );
    }
    best
}

/// Keeps the contact of triangle `t` in `best` when it comes before the kept one (the
/// lower index on ties).
#[inline]
pub(crate) fn consider(
    surface: &Surface,
    t: TriId,
    (a, b): (DVec3, DVec3),
    (radius, reach): (f64, f64),
    one_sided: bool,
    best: &mut Option<SphereContact>,
) {
    let corners = surface.corners(t);
    // Past the contact kept, nothing can come first: the segment is cut there (a contact
    // at that same parameter, with a lower index, still counts).
    let end = best.map_or(1.0, |c| c.t);
    if beyond_sphere(corners, (a, end * (b - a)), radius + reach) {
        return;
    }
    let face = surface.frame(t).normal;
    let Some((s, point, normal)) = sphere_triangle(corners, face, (a, b, end), radius, reach)
    else {
        return;
    };
    if one_sided && normal.dot(face) <= 0.0 {
        return;
    }
    if best.is_none_or(|c| s < c.t || (s == c.t && t.0 < c.triangle.0)) {
        *best = Some(SphereContact {
            t: s,
            triangle: t,
            point,
            normal,
        });
    }
}

/// The first contact of the sphere of `radius` swept from `a` to `b` with the triangle
/// `corners` (unit face normal `face`): its parameter in `[0, 1]`, the triangle's point
/// nearest to the centre there, and the unit normal from that point toward the centre.
/// A centre within `reach` of the offset at `a`, moving closer, touches at 0. `None` as
/// well for a triangle that cannot be touched up to the parameter `end`.
#[inline]
pub(crate) fn sphere_triangle(
    corners: [DVec3; 3],
    face: DVec3,
    (a, b, end): (DVec3, DVec3, f64),
    radius: f64,
    reach: f64,
) -> Option<(f64, DVec3, DVec3)> {
    let d = b - a;
    // A quick exit: the segment stays farther than the radius from the triangle's plane.
    let (ha, hb) = (face.dot(a - corners[0]), face.dot(b - corners[0]));
    let grow = radius + reach;
    if (ha > grow && hb > grow) || (ha < -grow && hb < -grow) {
        return None;
    }
    let start = closest_point_triangle(a, corners).point;
    let gap = a - start;
    let distance = gap.length();
    if distance <= grow {
        // At the start: touching when moving closer (the distance is convex along the
        // line, so a centre not moving closer never touches).
        if distance == 0.0 {
            let side = if face.dot(d) > 0.0 { -1.0 } else { 1.0 };
            return (d != DVec3::ZERO).then_some((0.0, start, side * face));
        }
        return (gap.dot(d) < 0.0).then(|| (0.0, start, gap / distance));
    }
    // The distance falls by at most the length travelled.
    if distance - end * d.length() > grow {
        return None;
    }
    let s = first_touch(corners, face, a, d, radius)?;
    if !(0.0..=1.0).contains(&s) {
        return None;
    }
    let centre = a + s * d;
    let point = closest_point_triangle(centre, corners).point;
    let normal = (centre - point).try_normalize()?;
    Some((s, point, normal))
}

/// Whether the segment `a → a + d` stays farther than `grow` from the sphere around the
/// triangle's corners (centred on their mean): no point of it comes within `grow` of the
/// triangle. Compares squares, with a relative margin far above their rounding.
#[inline]
pub(crate) fn beyond_sphere(corners: [DVec3; 3], (a, d): (DVec3, DVec3), grow: f64) -> bool {
    let centre = (corners[0] + corners[1] + corners[2]) / 3.0;
    let spread = corners
        .iter()
        .map(|&c| c.distance_squared(centre))
        .fold(0.0, f64::max)
        .sqrt();
    let dd = d.length_squared();
    let s = if dd > 0.0 {
        ((centre - a).dot(d) / dd).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let gap = centre.distance_squared(a + s * d);
    let reach = (grow + spread) * (1.0 + 1e-9);
    gap > reach * reach
}

/// The smallest parameter `s ≥ 0` at which the centre `a + s·d`, farther than `radius`
/// from the triangle at `s = 0`, comes within `radius` of it: the earliest entry into the
/// face's slab over the triangle, an edge's cylinder or a vertex's sphere.
#[inline]
fn first_touch(corners: [DVec3; 3], face: DVec3, a: DVec3, d: DVec3, radius: f64) -> Option<f64> {
    let mut first = f64::INFINITY;
    // The face moved out by the radius on the side the centre is on.
    let (h, dh) = (face.dot(a - corners[0]), face.dot(d));
    if h.abs() > radius && h * dh < 0.0 {
        let s = (h - radius.copysign(h)) / -dh;
        let x = a + s * d - (h + s * dh) * face;
        if inside_triangle(corners, face, x) {
            first = first.min(s);
        }
    }
    let r2 = radius * radius;
    for k in 0..3 {
        let (p, q) = (corners[k], corners[(k + 1) % 3]);
        if let Some(s) = enter_sphere(a - p, d, r2) {
            first = first.min(s);
        }
        let e = q - p;
        let ee = e.length_squared();
        if ee == 0.0 {
            continue;
        }
        // The cylinder round the edge: the components across it.
        let (m, v) = (a - p, d);
        let (mx, vx) = (m - e * (m.dot(e) / ee), v - e * (v.dot(e) / ee));
        if let Some(s) = enter_sphere(mx, vx, r2) {
            let along = (m + s * v).dot(e) / ee;
            if (0.0..=1.0).contains(&along) {
                first = first.min(s);
            }
        }
    }
    first.is_finite().then_some(first)
}

/// The smallest `s ≥ 0` with `|m + s·v|² = r2`, for `m` outside the sphere (or cylinder,
/// for components across an axis) moving in.
#[inline]
fn enter_sphere(m: DVec3, v: DVec3, r2: f64) -> Option<f64> {
    let (aa, bb, cc) = (v.length_squared(), m.dot(v), m.length_squared() - r2);
    if cc <= 0.0 || bb >= 0.0 || aa == 0.0 {
        return None;
    }
    let disc = bb * bb - aa * cc;
    if disc < 0.0 {
        return None;
    }
    // The smaller root, written without cancellation (bb < 0).
    let s = cc / (-bb + disc.sqrt());
    (s >= 0.0).then_some(s)
}

/// Whether `x`, in the triangle's plane, lies inside it or on its border.
#[inline]
fn inside_triangle([a, b, c]: [DVec3; 3], face: DVec3, x: DVec3) -> bool {
    face.dot((b - a).cross(x - a)) >= 0.0
        && face.dot((c - b).cross(x - b)) >= 0.0
        && face.dot((a - c).cross(x - c)) >= 0.0
}

#[cfg(test)]
mod tests;
