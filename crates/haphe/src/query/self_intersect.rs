//! Self-intersections: pairs of triangles of one surface that cross or touch each other
//! anywhere but in the corners they share. Where a surface passes through itself, inside
//! and outside are not defined, and a user would feel walls that are not there.

use crate::par::*;
use glam::DVec3;

use super::intersect_triangle_triangle;
use crate::map::VoxelMap;
use crate::mesh::{Surface, TriId};

/// How many intersecting pairs a [`SelfIntersections`] lists (all are counted).
pub(crate) const LISTED_SELF_INTERSECTIONS: usize = 100;

/// The self-intersections of a surface.
#[derive(Debug, Clone, PartialEq, Eq, Default, serde::Serialize)]
pub struct SelfIntersections {
    /// How many triangle pairs intersect.
    pub count: usize,
    /// Of those, pairs whose interiors pass through each other (each has corners strictly
    /// on both sides of the other's plane), or that overlap in one plane: where the surface
    /// really crosses itself and inside/outside is not defined.
    pub crossing: usize,
    /// Of those, pairs that only touch: a corner or an edge of one lies on the other (as at
    /// a T-junction of a CAD mesh), with no crossing.
    pub touching: usize,
    /// The first pairs `[a, b]` (`a < b`, in increasing order), at most
    /// 100, as triangle indices of the mesh the surface was
    /// built from ([`Surface::source_triangle`]), like its report.
    pub pairs: Vec<[u32; 2]>,
    /// How many candidate pairs (sharing a cell) were tested exactly.
    pub candidates: usize,
    /// Pairs of coincident triangles (the same three corners, in any order), found first
    /// by sorting the triangles' corner triples. They are duplicate faces, not counted in
    /// `count` (which, as [`intersect_triangle_triangle`], does not count triangles that
    /// share all their corners); each copy's intersections with other triangles are.
    pub coincident: usize,
    /// Whether every candidate pair was tested. `false` when the candidates exceeded the
    /// work budget (256 candidate pairs per triangle, at least 2²¹): `count` is then a
    /// lower bound.
    pub complete: bool,
}

/// The fewest candidate pairs the search tests before it may stop.
pub const SELF_INTERSECTION_BUDGET_MIN: usize = 1 << 21;

/// Candidate pairs per triangle the search tests before it stops (a smooth surface has
/// about ten per triangle; only stacked or repeated triangles reach this).
pub const SELF_INTERSECTION_BUDGET_PER_TRIANGLE: usize = 256;

/// The most candidate pairs [`self_intersections`] tests on a surface of `triangles`
/// triangles: [`SELF_INTERSECTION_BUDGET_PER_TRIANGLE`] per triangle, and at least
/// 2²¹ (`SELF_INTERSECTION_BUDGET_MIN`).
pub fn self_intersection_budget(triangles: usize) -> usize {
    triangles
        .saturating_mul(SELF_INTERSECTION_BUDGET_PER_TRIANGLE)
        .max(SELF_INTERSECTION_BUDGET_MIN)
}

/// Finds every pair of triangles that intersect other than in shared corners. Coincident
/// triangles (the same three corners) are found first, by sorting the triangles' corner
/// triples, and only one of each group takes part in the rest of the search (its pairs
/// counted once per copy). Then the
/// pairs listed together in some cell of `map` (a triangle pair that meets shares a cell,
/// since cells list every triangle that overlaps them), deduplicated, are tested exactly
/// with [`intersect_triangle_triangle`]. Neighbours sharing an edge or a vertex are
/// reported only where they overlap beyond it (a fold).
///
/// # Performance
/// Offline: parallel; proportional to the number of pairs sharing a cell (about ten per
/// triangle with the map's default cell size), and never more than 256 of them per
/// triangle (at least 2²¹ in all; `self_intersection_budget`): a surface whose triangles
/// are stacked in a few cells stops there, with [`SelfIntersections::complete`] false.
pub fn self_intersections(surface: &Surface, map: &VoxelMap) -> SelfIntersections {
    let triangles = surface.triangles();
    let Coincident {
        is_copy,
        copies,
        coincident,
    } = Coincident::of(triangles);
    // Candidate pairs, cell by cell, within the budget.
    let (lists, complete) = cell_lists(map, &is_copy, self_intersection_budget(triangles.len()));
    let mut candidates: Vec<u64> = lists
        .par_iter()
        .flat_map_iter(|list| {
            list.iter().enumerate().flat_map(move |(i, &a)| {
                list[i + 1..]
                    .iter()
                    .map(move |&b| (u64::from(a.min(b)) << 32) | u64::from(a.max(b)))
            })
        })
        .collect();
    drop(lists);
    candidates.par_sort_unstable();
    candidates.dedup();
    // Each pair found stands for as many pairs as its triangles have copies.
    let found: Vec<([u32; 2], bool, usize)> = candidates
        .par_iter()
        .filter_map(|&key| {
            let (a, b) = (TriId((key >> 32) as u32), TriId(key as u32));
            let (ta, tb) = (surface.corners(a), surface.corners(b));
            if clearly_apart(ta, tb) {
                return None;
            }
            let weight = copies[a.0 as usize] as usize * copies[b.0 as usize] as usize;
            let (a, b) = (surface.source_triangle(a), surface.source_triangle(b));
            intersect_triangle_triangle(ta, tb)
                .then(|| ([a.min(b), a.max(b)], crosses(ta, tb), weight))
        })
        .collect();
    // Coincident pairs are duplicate faces (the report lists them): as for the exact test,
    // triangles that share all their corners do not count as intersecting.
    let count = found.iter().map(|f| f.2).sum::<usize>();
    let crossing = found.iter().filter(|f| f.1).map(|f| f.2).sum::<usize>();
    let mut pairs: Vec<[u32; 2]> = found.iter().map(|f| f.0).collect();
    pairs.par_sort_unstable();
    pairs.truncate(LISTED_SELF_INTERSECTIONS);
    SelfIntersections {
        count,
        crossing,
        touching: count - crossing,
        pairs,
        candidates: candidates.len(),
        coincident,
        complete,
    }
}

/// The coincident triangles (the same three corners) of a surface: one of each group
/// stands for the others.
struct Coincident {
    /// Whether a triangle is a copy of a lower one.
    is_copy: Vec<bool>,
    /// How many triangles each representative stands for (1 for most).
    copies: Vec<u32>,
    /// The number of coincident pairs.
    coincident: usize,
}

impl Coincident {
    /// Found in O(n log n): a run of equal sorted corner triples.
    fn of(triangles: &[[u32; 3]]) -> Coincident {
        let mut keyed: Vec<([u32; 3], u32)> = triangles
            .par_iter()
            .enumerate()
            .map(|(t, corners)| {
                let mut key = *corners;
                key.sort_unstable();
                (key, t as u32)
            })
            .collect();
        keyed.par_sort_unstable();
        let mut is_copy = vec![false; triangles.len()];
        // How many triangles each representative stands for (1 for most).
        let mut copies = vec![1u32; triangles.len()];
        let mut coincident = 0usize;
        for run in keyed.chunk_by(|a, b| a.0 == b.0) {
            let k = run.len();
            if k < 2 {
                continue;
            }
            coincident += k * (k - 1) / 2;
            copies[run[0].1 as usize] = k as u32;
            for &(_, t) in &run[1..] {
                is_copy[t as usize] = true;
            }
        }
        Coincident {
            is_copy,
            copies,
            coincident,
        }
    }
}

/// The triangle lists of the map's surface cells without the copies, as many as `budget`
/// candidate pairs allow (the last one cut), and whether they are all there.
fn cell_lists(map: &VoxelMap, is_copy: &[bool], budget: usize) -> (Vec<Vec<u32>>, bool) {
    let mut lists: Vec<Vec<u32>> = Vec::new();
    let mut planned = 0usize;
    let mut complete = true;
    for list in map.surface_cell_triangles() {
        let list: Vec<u32> = list
            .iter()
            .copied()
            .filter(|&t| !is_copy[t as usize])
            .collect();
        let pairs = list.len() * list.len().saturating_sub(1) / 2;
        if planned + pairs > budget {
            // The part of this cell the budget allows: the pairs of its first `k`
            // triangles, `k (k - 1) / 2` of them.
            let room = budget - planned;
            let k = (((8 * room + 1) as f64).sqrt() as usize)
                .div_ceil(2)
                .min(list.len());
            let k = (0..=k)
                .rev()
                .find(|k| k * k.saturating_sub(1) / 2 <= room)
                .unwrap_or(0);
            lists.push(list[..k].to_vec());
            complete = false;
            break;
        }
        planned += pairs;
        lists.push(list);
    }
    (lists, complete)
}

/// Relative margin of [`clearly_apart`]: a corner must be farther than this fraction of the
/// triangles' size from a plane to count as clearly off it (far above the rounding of the
/// float test, so the shortcut never hides an intersection the exact test would find).
const APART_MARGIN_REL: f64 = 1e-9;

/// A float shortcut for the common case, sound by its margin: the corners of one triangle
/// that it does not share with the other all lie clearly on one side of the other's plane.
/// Then the triangles can meet only in their shared corners (or not at all), which the
/// exact test would also say. Most candidate pairs are neighbours around a vertex or an
/// edge of a smooth surface, and end here.
fn clearly_apart(ta: [DVec3; 3], tb: [DVec3; 3]) -> bool {
    let size = (ta[1] - ta[0])
        .abs()
        .max((ta[2] - ta[0]).abs())
        .max((tb[1] - tb[0]).abs())
        .max((tb[2] - tb[0]).abs())
        .max_element();
    let scale = size.max(ta[0].abs().max_element());
    let margin = APART_MARGIN_REL * scale;
    let one_side = |plane: [DVec3; 3], points: [DVec3; 3]| {
        let n = (plane[1] - plane[0]).cross(plane[2] - plane[0]);
        let length = n.length();
        if !(length > 0.0 && length.is_finite()) {
            return false;
        }
        let n = n / length;
        let (mut above, mut below) = (false, false);
        for q in points.iter().filter(|q| !plane.contains(q)) {
            let h = n.dot(*q - plane[0]);
            if h > margin {
                above = true;
            } else if h < -margin {
                below = true;
            } else {
                return false;
            }
        }
        above != below
    };
    one_side(ta, tb) || one_side(tb, ta)
}

/// A corner closer than this fraction of the larger triangle's longest edge to the other
/// triangle's plane counts as lying on it, when telling crossing from touching: files that
/// store coordinates as `f32` (STL, most PLY) round a corner that was designed to lie on a
/// plane (a T-junction) by up to about 6e-8 of the coordinates' size, which exact tests
/// would read as a crossing.
pub(crate) const TOUCH_TOLERANCE_REL: f64 = 1e-6;

/// For two intersecting triangles: whether they cross (each has corners clearly on both
/// sides of the other's plane) or overlap in one plane, rather than only touch.
fn crosses(ta: [DVec3; 3], tb: [DVec3; 3]) -> bool {
    let longest = |t: [DVec3; 3]| {
        (t[1] - t[0])
            .length()
            .max((t[2] - t[1]).length())
            .max((t[0] - t[2]).length())
    };
    let tolerance = TOUCH_TOLERANCE_REL * longest(ta).max(longest(tb));
    // Signed distances of `points` from the plane of `plane`, rounded to 0 within the
    // tolerance.
    let sides = |plane: [DVec3; 3], points: [DVec3; 3]| {
        let n = (plane[1] - plane[0])
            .cross(plane[2] - plane[0])
            .normalize_or_zero();
        points.map(|q| {
            let h = n.dot(q - plane[0]);
            if h.abs() <= tolerance { 0.0 } else { h }
        })
    };
    let straddles = |s: [f64; 3]| s.iter().any(|&x| x > 0.0) && s.iter().any(|&x| x < 0.0);
    let (sb, sa) = (sides(ta, tb), sides(tb, ta));
    if sb.iter().all(|&x| x == 0.0) && sa.iter().all(|&x| x == 0.0) {
        return interiors_overlap_coplanar(ta, tb);
    }
    straddles(sa) && straddles(sb)
}

/// For two triangles in one plane: whether their interiors overlap (not just touch along
/// an edge or at a corner). They do unless an edge line of one has the whole other
/// triangle on its outer side or on it (exact 2D orientation tests, in the coordinate
/// plane the triangles project to without collapsing).
fn interiors_overlap_coplanar(ta: [DVec3; 3], tb: [DVec3; 3]) -> bool {
    let n = (ta[1] - ta[0]).cross(ta[2] - ta[0]).abs();
    let drop = if n.x >= n.y && n.x >= n.z {
        0
    } else if n.y >= n.z {
        1
    } else {
        2
    };
    let flat = |p: DVec3| {
        let (u, v) = match drop {
            0 => (p.y, p.z),
            1 => (p.z, p.x),
            _ => (p.x, p.y),
        };
        robust::Coord { x: u, y: v }
    };
    let (a, b) = (ta.map(flat), tb.map(flat));
    let separates = |tri: [robust::Coord<f64>; 3], other: [robust::Coord<f64>; 3]| {
        let orientation = robust::orient2d(tri[0], tri[1], tri[2]);
        (0..3).any(|i| {
            let (p, q) = (tri[i], tri[(i + 1) % 3]);
            other
                .iter()
                .all(|&r| robust::orient2d(p, q, r) * orientation <= 0.0)
        })
    };
    !(separates(a, b) || separates(b, a))
}
