//! Triangulation of the polygons of OBJ, OFF and PLY faces.
//!
//! A polygon is a list of vertex indices into a position slice. Triangles pass through as
//! they are; larger polygons are projected into their plane (the Newell normal, so a slightly
//! warped polygon works too) and cut by ear clipping, which handles non-convex outlines such
//! as an L or a wall with a notch. Convex polygons, degenerate ones (no area, a non-finite or
//! missing corner) and polygons whose ear clipping fails or runs over its work budget get a
//! fan instead. A non-convex polygon whose ear clipping runs over its work budget (thousands
//! of corners) is refused with [`PolygonTooComplex`], which the readers report with the
//! file's place: a fan of it would overlap itself, silently. Every output triangle keeps the
//! polygon's winding, and an `n`-gon always gives `n − 2` triangles (a degenerate polygon
//! gives degenerate triangles, which the mesh report lists), so counts are predictable.
//!
//! Self-intersecting polygons have no correct triangulation; they get some triangulation
//! with `n − 2` triangles and never a panic.

use glam::{DVec2, DVec3};

/// Relative tolerance under which a 2D cross product (an area, length²) counts as zero: it
/// is scaled by the square of the polygon's extent. It absorbs the rounding of the projection
/// into the polygon's plane, so collinear corners (T-junctions, common in CAD exports) are
/// recognised as flat instead of as tiny reflex or convex turns.
const COLLINEAR_REL_TOL: f64 = 1e-12;

/// Cap on the point-in-triangle tests spent on one polygon (a few milliseconds). Ear
/// clipping is quadratic in the number of corners, cubic in the worst case; when the cap is
/// reached the polygon is refused ([`PolygonTooComplex`]), so a pathological polygon costs
/// bounded time. A non-convex polygon of up to about 2 000 corners fits.
pub(crate) const EAR_TEST_BUDGET: usize = 1 << 22;

/// A non-convex polygon that ear clipping could not cut within [`EAR_TEST_BUDGET`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct PolygonTooComplex {
    /// Its corners.
    pub(crate) corners: usize,
}

/// Scratch space for triangulating polygons, reused across polygons so that a file with
/// many quads does not allocate per face.
#[derive(Debug, Default)]
pub(crate) struct Triangulator {
    /// The corners projected into the polygon's plane.
    flat: Vec<DVec2>,
    /// Ring of remaining corners: previous corner of each.
    prev: Vec<usize>,
    /// Ring of remaining corners: next corner of each.
    next: Vec<usize>,
    /// The triangles of one polygon as places in it, before they are turned into vertices.
    local: Vec<[u32; 3]>,
}

impl Triangulator {
    /// Appends the triangles of `polygon` (indices into `positions`) to `out`, keeping the
    /// polygon's winding: `polygon.len() − 2` triangles, none for fewer than three corners.
    ///
    /// Indices out of range of `positions` are passed through (the polygon is fanned); the
    /// callers check ranges before, with the file's place.
    ///
    /// # Errors
    /// [`PolygonTooComplex`] when ear clipping runs over [`EAR_TEST_BUDGET`]; `out` is then
    /// left as it was.
    ///
    /// # Performance
    /// Linear for triangles and convex polygons; ear clipping is quadratic in the corners and
    /// capped by [`EAR_TEST_BUDGET`].
    pub(crate) fn triangulate(
        &mut self,
        polygon: &[u32],
        positions: &[DVec3],
        out: &mut Vec<[u32; 3]>,
    ) -> Result<(), PolygonTooComplex> {
        let mut local = std::mem::take(&mut self.local);
        local.clear();
        let done = self.triangulate_corners(polygon, positions, &mut local);
        if done.is_ok() {
            out.extend(local.iter().map(|t| t.map(|k| polygon[k as usize])));
        }
        self.local = local;
        done
    }

    /// Like [`Triangulator::triangulate`], but each output triangle names its corners by
    /// their place in `polygon` (`0..polygon.len()`), not by vertex: what a reader needs
    /// to carry data of the polygon's corners (texture coordinates) into the triangles.
    ///
    /// # Errors
    /// As [`Triangulator::triangulate`].
    pub(crate) fn triangulate_corners(
        &mut self,
        polygon: &[u32],
        positions: &[DVec3],
        out: &mut Vec<[u32; 3]>,
    ) -> Result<(), PolygonTooComplex> {
        let n = polygon.len();
        match n {
            0..=2 => {}
            3 => out.push([0, 1, 2]),
            _ => {
                let Some(tol) = self.project(polygon, positions) else {
                    fan(n, out);
                    return Ok(());
                };
                if self.is_convex(tol) {
                    fan(n, out);
                } else {
                    let before = out.len();
                    if self.clip_ears(n, tol, out).is_none() {
                        out.truncate(before);
                        return Err(PolygonTooComplex { corners: n });
                    }
                }
            }
        }
        Ok(())
    }

    /// Projects the corners into the plane of the Newell normal, oriented so the polygon
    /// runs counter-clockwise in 2D. Returns the zero tolerance for 2D cross products, or
    /// `None` when the polygon is degenerate (no area, a missing or non-finite corner).
    fn project(&mut self, polygon: &[u32], positions: &[DVec3]) -> Option<f64> {
        let corner = |i: u32| positions.get(i as usize).copied().filter(|p| p.is_finite());
        let origin = corner(polygon[0])?;
        // Twice the area vector: Σ (pᵢ − p₀) × (pᵢ₊₁ − p₀), relative to the first corner
        // for precision far from the origin.
        let mut area2 = DVec3::ZERO;
        let (mut lo, mut hi) = (origin, origin);
        let mut last = DVec3::ZERO;
        for &i in &polygon[1..] {
            let p = corner(i)?;
            lo = lo.min(p);
            hi = hi.max(p);
            let d = p - origin;
            area2 += last.cross(d);
            last = d;
        }
        let extent2 = (hi - lo).length_squared();
        let area2_len = area2.length();
        if !(area2_len.is_finite()
            && extent2.is_finite()
            && area2_len > COLLINEAR_REL_TOL * extent2)
        {
            return None;
        }
        let normal = area2 / area2_len;
        let u = normal.any_orthonormal_vector();
        let v = normal.cross(u);
        self.flat.clear();
        for &i in polygon {
            let d = corner(i)? - origin;
            self.flat.push(DVec2::new(d.dot(u), d.dot(v)));
        }
        Some(COLLINEAR_REL_TOL * extent2)
    }

    /// True when no corner turns right (beyond the tolerance): a fan is then correct.
    fn is_convex(&self, tol: f64) -> bool {
        let n = self.flat.len();
        (0..n).all(|i| {
            let (a, b, c) = (
                self.flat[(i + n - 1) % n],
                self.flat[i],
                self.flat[(i + 1) % n],
            );
            (b - a).perp_dot(c - b) >= -tol
        })
    }

    /// Ear clipping over the projected corners; fans what is left if no ear is found in a
    /// full turn around the ring (the polygon self-intersects). `None` when the budget runs
    /// out.
    fn clip_ears(&mut self, n: usize, tol: f64, out: &mut Vec<[u32; 3]>) -> Option<()> {
        self.prev.clear();
        self.prev.extend((0..n).map(|i| (i + n - 1) % n));
        self.next.clear();
        self.next.extend((0..n).map(|i| (i + 1) % n));
        let mut budget = EAR_TEST_BUDGET;
        let mut remaining = n;
        let mut i = 0;
        let mut misses = 0;
        while remaining > 3 {
            if misses >= remaining {
                break;
            }
            let (a, c) = (self.prev[i], self.next[i]);
            match self.is_ear(a, i, c, tol, &mut budget) {
                Some(true) => {
                    out.push([a as u32, i as u32, c as u32]);
                    self.next[a] = c;
                    self.prev[c] = a;
                    remaining -= 1;
                    misses = 0;
                    i = c;
                }
                Some(false) => {
                    misses += 1;
                    i = c;
                }
                None => return None,
            }
        }
        // Fan whatever is left (three corners in the normal case).
        let start = i;
        let mut k = self.next[start];
        for _ in 0..remaining.saturating_sub(2) {
            let k_next = self.next[k];
            out.push([start as u32, k as u32, k_next as u32]);
            k = k_next;
        }
        Some(())
    }

    /// Whether corners `a`, `b`, `c` (consecutive on the ring) form an ear: a strictly
    /// convex turn at `b` and no other remaining corner inside or on the triangle. Corners at
    /// the same place as `a`, `b` or `c` (the two sides of a bridge into a hole) do not
    /// block. `None` when the budget is spent.
    fn is_ear(&self, a: usize, b: usize, c: usize, tol: f64, budget: &mut usize) -> Option<bool> {
        let (pa, pb, pc) = (self.flat[a], self.flat[b], self.flat[c]);
        if (pb - pa).perp_dot(pc - pb) <= tol {
            return Some(false);
        }
        let mut k = self.next[c];
        while k != a {
            *budget = budget.checked_sub(1)?;
            let p = self.flat[k];
            if p != pa && p != pb && p != pc && in_triangle(p, pa, pb, pc, tol) {
                return Some(false);
            }
            k = self.next[k];
        }
        Some(true)
    }
}

/// True when `p` lies inside or on the counter-clockwise triangle `a b c` (within `tol`).
fn in_triangle(p: DVec2, a: DVec2, b: DVec2, c: DVec2, tol: f64) -> bool {
    (b - a).perp_dot(p - a) >= -tol
        && (c - b).perp_dot(p - b) >= -tol
        && (a - c).perp_dot(p - c) >= -tol
}

/// Fan from the first corner of an `n`-gon: `n − 2` triangles with the polygon's winding,
/// as places in the polygon.
fn fan(n: usize, out: &mut Vec<[u32; 3]>) {
    out.extend((1..n.saturating_sub(1)).map(|k| [0, k as u32, k as u32 + 1]));
}

/// Triangulates one polygon with fresh scratch space; see [`Triangulator::triangulate`].
#[cfg(test)]
pub(crate) fn triangulate_polygon(polygon: &[u32], positions: &[DVec3], out: &mut Vec<[u32; 3]>) {
    let done = Triangulator::default().triangulate(polygon, positions, out);
    assert_eq!(done, Ok(()));
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Area vector (half the cross product sum) of a closed polygon.
    fn polygon_area_vector(points: &[DVec3]) -> DVec3 {
        let o = points[0];
        points
            .windows(2)
            .map(|w| (w[0] - o).cross(w[1] - o))
            .sum::<DVec3>()
            * 0.5
    }

    /// Triangulates `points` (a polygon in order) and checks: n − 2 triangles, each with
    /// positive area along the polygon's normal, areas summing to the polygon's area.
    fn check_exact_cover(points: &[DVec3]) -> Vec<[u32; 3]> {
        let polygon: Vec<u32> = (0..points.len() as u32).collect();
        let mut out = Vec::new();
        triangulate_polygon(&polygon, points, &mut out);
        assert_eq!(out.len(), points.len() - 2, "{out:?}");
        let area = polygon_area_vector(points);
        let normal = area.normalize();
        let mut sum = 0.0;
        for &[a, b, c] in &out {
            let (pa, pb, pc) = (points[a as usize], points[b as usize], points[c as usize]);
            let t = 0.5 * (pb - pa).cross(pc - pa);
            let along = t.dot(normal);
            assert!(
                along > 0.0,
                "triangle {a} {b} {c} is flipped or flat: {along}"
            );
            sum += t.length();
        }
        let expected = area.length();
        assert!(
            (sum - expected).abs() <= 1e-9 * expected,
            "triangles cover {sum}, polygon has {expected}: {out:?}"
        );
        out
    }

    fn flat(xy: &[(f64, f64)]) -> Vec<DVec3> {
        xy.iter().map(|&(x, y)| DVec3::new(x, y, 0.0)).collect()
    }

    /// The same points in a tilted plane far from the origin.
    fn tilted(points: &[DVec3]) -> Vec<DVec3> {
        let rotation = glam::DQuat::from_euler(glam::EulerRot::XYZ, 0.7, -0.4, 1.1);
        points
            .iter()
            .map(|&p| rotation * p + DVec3::new(100.0, -50.0, 20.0))
            .collect()
    }

    #[test]
    fn triangle_passes_through() {
        let mut out = Vec::new();
        triangulate_polygon(&[4, 2, 7], &[], &mut out);
        assert_eq!(out, vec![[4, 2, 7]]);
    }

    #[test]
    fn fewer_than_three_corners_give_nothing() {
        let mut out = Vec::new();
        triangulate_polygon(&[1, 2], &flat(&[(0.0, 0.0); 3]), &mut out);
        assert!(out.is_empty());
    }

    #[test]
    fn convex_quad_gives_two_triangles_with_its_winding() {
        let quad = flat(&[(0.0, 0.0), (2.0, 0.0), (2.0, 1.0), (0.0, 1.0)]);
        check_exact_cover(&quad);
        check_exact_cover(&tilted(&quad));
        // Clockwise: the triangles follow, pointing the other way.
        let mut reversed = quad.clone();
        reversed.reverse();
        let out = check_exact_cover(&reversed);
        let [a, b, c] = out[0].map(|i| reversed[i as usize]);
        assert!((b - a).cross(c - a).z < 0.0);
    }

    #[test]
    fn non_convex_quad_is_cut_at_its_reflex_corner() {
        // A dart: corner 2 is reflex, so the fan from 0 would be wrong.
        let dart = flat(&[(0.0, 0.0), (2.0, 1.0), (0.5, 0.5), (1.0, 2.0)]);
        let out = check_exact_cover(&dart);
        assert!(out.iter().all(|t| t.contains(&2)));
        check_exact_cover(&tilted(&dart));
    }

    /// An L-shaped hexagon (one reflex corner).
    fn l_shape() -> Vec<DVec3> {
        flat(&[
            (0.0, 0.0),
            (3.0, 0.0),
            (3.0, 1.0),
            (1.0, 1.0),
            (1.0, 3.0),
            (0.0, 3.0),
        ])
    }

    #[test]
    fn l_shape_is_covered_exactly() {
        let l = l_shape();
        check_exact_cover(&l);
        check_exact_cover(&tilted(&l));
        // Starting at the reflex corner changes nothing.
        let mut rotated = l.clone();
        rotated.rotate_left(3);
        check_exact_cover(&rotated);
    }

    #[test]
    fn arrow_is_covered_exactly() {
        let arrow = flat(&[
            (0.0, 1.0),
            (3.0, 1.0),
            (3.0, 0.0),
            (5.0, 2.0),
            (3.0, 4.0),
            (3.0, 3.0),
            (0.0, 3.0),
        ]);
        check_exact_cover(&arrow);
        check_exact_cover(&tilted(&arrow));
        let chevron = flat(&[(0.0, 0.0), (2.0, 1.0), (4.0, 0.0), (2.0, 3.0)]);
        check_exact_cover(&chevron);
    }

    #[test]
    fn collinear_corners_and_a_notch_like_the_wallhole_side() {
        // The x = 10 side of odd/wallhole.obj in its own plane: a U with T-junctions.
        let u = flat(&[
            (0.0, -4.0),
            (5.0, -4.0),
            (5.0, -6.0),
            (0.0, -6.0),
            (0.0, -10.0),
            (5.0, -10.0),
            (10.0, -10.0),
            (10.0, -5.0),
            (10.0, 0.0),
            (5.0, 0.0),
            (0.0, 0.0),
        ]);
        check_exact_cover(&u);
    }

    #[test]
    fn bridged_hole_is_covered_exactly() {
        // A square with a square hole, joined by a bridge whose two sides share corners.
        let ring = flat(&[
            (0.0, 0.0),
            (4.0, 0.0),
            (4.0, 4.0),
            (0.0, 4.0),
            (0.0, 0.0),
            (1.0, 1.0),
            (1.0, 3.0),
            (3.0, 3.0),
            (3.0, 1.0),
            (1.0, 1.0),
        ]);
        let polygon: Vec<u32> = (0..ring.len() as u32).collect();
        let mut out = Vec::new();
        triangulate_polygon(&polygon, &ring, &mut out);
        assert_eq!(out.len(), ring.len() - 2);
        let area: f64 = out
            .iter()
            .map(|&[a, b, c]| {
                let (pa, pb, pc) = (ring[a as usize], ring[b as usize], ring[c as usize]);
                0.5 * (pb - pa).cross(pc - pa).z
            })
            .sum();
        assert!((area - 12.0).abs() < 1e-9, "{area} {out:?}");
    }

    /// A star of `n` corners (`n` even) in the plane z = 0, radii 10 and 7 in turn.
    fn star(n: usize) -> Vec<DVec3> {
        (0..n)
            .map(|i| {
                let angle = i as f64 / n as f64 * std::f64::consts::TAU;
                let r = if i % 2 == 0 { 10.0 } else { 7.0 };
                DVec3::new(r * angle.cos(), r * angle.sin(), 0.0)
            })
            .collect()
    }

    #[test]
    fn large_star_is_covered_exactly_and_quickly() {
        let n = 2000;
        let star = star(n);
        check_exact_cover(&star);
    }

    #[test]
    fn degenerate_polygons_fan_without_panicking() {
        let mut out = Vec::new();
        // Collinear.
        triangulate_polygon(
            &[0, 1, 2, 3],
            &flat(&[(0.0, 0.0), (1.0, 0.0), (2.0, 0.0), (3.0, 0.0)]),
            &mut out,
        );
        assert_eq!(out, vec![[0, 1, 2], [0, 2, 3]]);
        // One corner repeated everywhere, a non-finite corner, an index out of range.
        out.clear();
        triangulate_polygon(&[0, 0, 0, 0, 0], &flat(&[(1.0, 1.0)]), &mut out);
        assert_eq!(out.len(), 3);
        out.clear();
        let mut bad = flat(&[(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]);
        bad[2].x = f64::NAN;
        triangulate_polygon(&[0, 1, 2, 3], &bad, &mut out);
        assert_eq!(out.len(), 2);
        out.clear();
        triangulate_polygon(&[0, 1, 9, 3], &bad, &mut out);
        assert_eq!(out, vec![[0, 1, 9], [0, 9, 3]]);
    }

    #[test]
    fn self_intersecting_polygons_give_n_minus_2_triangles() {
        // A bow tie and a pentagram: no correct answer, but no panic and the usual count.
        let bow_tie = flat(&[(0.0, 0.0), (2.0, 2.0), (2.0, 0.0), (0.0, 2.0)]);
        let pentagram: Vec<DVec3> = (0..5)
            .map(|i| {
                let angle = (i * 2) as f64 / 5.0 * std::f64::consts::TAU;
                DVec3::new(angle.cos(), angle.sin(), 0.0)
            })
            .collect();
        for points in [bow_tie, pentagram] {
            let polygon: Vec<u32> = (0..points.len() as u32).collect();
            let mut out = Vec::new();
            triangulate_polygon(&polygon, &points, &mut out);
            assert_eq!(out.len(), points.len() - 2);
        }
    }

    #[test]
    fn scratch_is_reused_across_polygons() {
        let mut triangulator = Triangulator::default();
        let l = l_shape();
        let mut out = Vec::new();
        triangulator
            .triangulate(&[0, 1, 2, 3, 4, 5], &l, &mut out)
            .unwrap();
        triangulator
            .triangulate(&[0, 1, 2, 3], &l, &mut out)
            .unwrap();
        assert_eq!(out.len(), 4 + 2);
    }

    #[test]
    fn corners_name_the_places_of_the_vertices_triangulate_gives() {
        let l = l_shape();
        // The polygon's vertices in another order than their places in it.
        let polygon = [3, 4, 5, 0, 1, 2];
        let mut by_vertex = Vec::new();
        let mut by_place = Vec::new();
        let mut triangulator = Triangulator::default();
        for p in [&polygon[..], &polygon[..3], &[0, 1, 2, 3][..]] {
            by_vertex.clear();
            by_place.clear();
            triangulator.triangulate(p, &l, &mut by_vertex).unwrap();
            triangulator
                .triangulate_corners(p, &l, &mut by_place)
                .unwrap();
            let mapped: Vec<[u32; 3]> = by_place.iter().map(|t| t.map(|k| p[k as usize])).collect();
            assert_eq!(mapped, by_vertex, "{p:?}");
            assert_eq!(by_place.len(), p.len() - 2);
        }
    }

    #[test]
    fn a_polygon_past_the_budget_is_refused_in_bounded_time_not_fanned() {
        // 20 000 corners of a star: ear clipping would need about 10^8 tests.
        let n = 20_000;
        let star = star(n);
        let polygon: Vec<u32> = (0..n as u32).collect();
        let mut out = vec![[7, 7, 7]];
        let start = std::time::Instant::now();
        let result = Triangulator::default().triangulate(&polygon, &star, &mut out);
        assert_eq!(result, Err(PolygonTooComplex { corners: n }));
        assert_eq!(out, vec![[7, 7, 7]], "nothing is left of the polygon");
        // The budget is a few milliseconds of tests; a debug build on a loaded machine
        // takes longer, and the whole polygon would take minutes.
        assert!(start.elapsed().as_secs_f64() < 5.0, "{:?}", start.elapsed());
    }
}
