//! Constraint planes and the point the proxy aims for: the closest point to the goal that
//! lies on the outer side of every active plane (at most three, the god-object's face,
//! concave edge and concave corner).

use glam::DVec3;

/// Most constraint planes active at once: a face, a concave edge (two faces), a concave
/// corner (three faces). A fourth crossing in one tick stops the proxy where it is.
pub const MAX_CONSTRAINTS: usize = 3;

/// A constraint plane, world frame: the proxy must stay where `normal · x ≥ offset`.
///
/// The plane is a touched triangle's plane moved out by the skin along the normal of the
/// side the proxy came from ([`Plane::facing`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plane {
    /// Unit normal pointing to the free side, world frame.
    pub normal: DVec3,
    /// `normal · x` on the plane, metres.
    pub offset: f64,
}

impl Plane {
    /// The plane of a triangle with unit normal `normal` through `point` (both world
    /// frame), turned to face the side the path `from → to` comes from, and moved `skin`
    /// metres toward it. The side is that of `from`; when `from` lies on the plane, the
    /// side the path leaves.
    #[inline]
    pub fn facing(normal: DVec3, point: DVec3, from: DVec3, to: DVec3, skin: f64) -> Plane {
        let h = normal.dot(from - point);
        let front = if h != 0.0 {
            h > 0.0
        } else {
            normal.dot(to - from) <= 0.0
        };
        let normal = if front { normal } else { -normal };
        Plane {
            normal,
            offset: normal.dot(point) + skin,
        }
    }

    /// The constraint plane of a surface met by the move `from → to`: for a one-sided
    /// surface, the front of the face (its normal's side); for a two-sided one, the side
    /// the move comes from ([`Plane::facing`]).
    #[inline]
    pub fn of_hit(
        normal: DVec3,
        point: DVec3,
        one_sided: bool,
        from: DVec3,
        to: DVec3,
        skin: f64,
    ) -> Plane {
        if one_sided {
            Plane {
                normal,
                offset: normal.dot(point) + skin,
            }
        } else {
            Plane::facing(normal, point, from, to, skin)
        }
    }

    /// Signed height of `p` above the plane, metres (negative behind it).
    #[inline]
    pub fn height(&self, p: DVec3) -> f64 {
        self.normal.dot(p) - self.offset
    }
}

/// The active constraint planes of one tick (at most [`MAX_CONSTRAINTS`]), on the stack.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Constraints {
    planes: [Plane; MAX_CONSTRAINTS],
    len: usize,
}

impl Default for Plane {
    /// A placeholder (zero normal); never active.
    fn default() -> Plane {
        Plane {
            normal: DVec3::ZERO,
            offset: 0.0,
        }
    }
}

impl Constraints {
    /// No constraint.
    pub const NONE: Constraints = Constraints {
        planes: [Plane {
            normal: DVec3::ZERO,
            offset: 0.0,
        }; MAX_CONSTRAINTS],
        len: 0,
    };

    /// The active planes, in the order they were touched.
    pub fn planes(&self) -> &[Plane] {
        &self.planes[..self.len]
    }

    /// Number of active planes.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether no plane is active.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Whether [`MAX_CONSTRAINTS`] planes are active.
    pub fn is_full(&self) -> bool {
        self.len == MAX_CONSTRAINTS
    }

    /// Adds `plane`; `false` (and no change) when full.
    pub fn push(&mut self, plane: Plane) -> bool {
        if self.is_full() {
            return false;
        }
        self.planes[self.len] = plane;
        self.len += 1;
        true
    }

    /// The point closest to `goal` on the free side of every plane (within `tolerance`
    /// metres), world frame: the exact solution of that small quadratic program, found by
    /// trying the goal, its projection onto each plane, onto each pair's line and onto the
    /// triple's point, and keeping the nearest candidate that satisfies every plane. `None`
    /// when no candidate does (planes that leave no room, or nearly parallel pairs).
    ///
    /// # Real-time
    /// At most 8 candidates, no allocation, no panic.
    #[inline(always)]
    pub fn closest_feasible(&self, goal: DVec3, tolerance: f64) -> Option<DVec3> {
        // No plane, or one (the common cases, inlined into the caller): the goal, or its
        // projection, the only candidate.
        match self.planes() {
            [] => Some(goal),
            [plane] => {
                if plane.height(goal) >= -tolerance {
                    return Some(goal);
                }
                let x = project_on_plane(goal, plane);
                (x.is_finite() && plane.height(x) >= -tolerance).then_some(x)
            }
            _ => self.closest_of_several(goal, tolerance),
        }
    }

    /// [`Constraints::closest_feasible`] for two or three planes (kept out of line, so that
    /// the common cases stay small enough to inline).
    #[inline(never)]
    fn closest_of_several(&self, goal: DVec3, tolerance: f64) -> Option<DVec3> {
        let planes = self.planes();
        let feasible = |x: DVec3| planes.iter().all(|p| p.height(x) >= -tolerance);
        if feasible(goal) {
            return Some(goal);
        }
        let mut best: Option<(DVec3, f64)> = None;
        let mut offer = |x: Option<DVec3>| {
            if let Some(x) = x
                && x.is_finite()
                && feasible(x)
            {
                let d2 = x.distance_squared(goal);
                if best.is_none_or(|(_, b2)| d2 < b2) {
                    best = Some((x, d2));
                }
            }
        };
        let n = planes.len();
        for plane in planes {
            offer(Some(project_on_plane(goal, plane)));
        }
        for i in 0..n {
            for j in i + 1..n {
                offer(project_on_line(goal, &planes[i], &planes[j]));
            }
        }
        if n == 3 {
            offer(corner_point(&planes[0], &planes[1], &planes[2]));
        }
        best.map(|(x, _)| x)
    }
}

/// Smallest `1 − (n_i · n_j)²` for two planes to count as crossing in a line: planes closer
/// to parallel than about 0.06° have no usable line (the pair's other candidates remain).
pub(crate) const MIN_PAIR_SINE_SQUARED: f64 = 1e-6;

/// Smallest `|det(n_0, n_1, n_2)|` for three planes to meet in a usable point.
pub(crate) const MIN_TRIPLE_DETERMINANT: f64 = 1e-6;

fn project_on_plane(goal: DVec3, plane: &Plane) -> DVec3 {
    goal - plane.height(goal) * plane.normal
}

/// The point of the line `a ∩ b` closest to `goal`.
fn project_on_line(goal: DVec3, a: &Plane, b: &Plane) -> Option<DVec3> {
    // x = goal + λa·na + λb·nb with na·x = oa and nb·x = ob.
    let c = a.normal.dot(b.normal);
    let det = 1.0 - c * c;
    if det < MIN_PAIR_SINE_SQUARED {
        return None;
    }
    let ra = -a.height(goal);
    let rb = -b.height(goal);
    let la = (ra - c * rb) / det;
    let lb = (rb - c * ra) / det;
    Some(goal + la * a.normal + lb * b.normal)
}

/// The point where three planes meet.
fn corner_point(a: &Plane, b: &Plane, c: &Plane) -> Option<DVec3> {
    let det = a.normal.dot(b.normal.cross(c.normal));
    if det.abs() < MIN_TRIPLE_DETERMINANT {
        return None;
    }
    Some(
        (a.offset * b.normal.cross(c.normal)
            + b.offset * c.normal.cross(a.normal)
            + c.offset * a.normal.cross(b.normal))
            / det,
    )
}

/// How far the proxy gets along `from → to` before it reaches `plane` (the touched
/// triangle's plane moved out by the skin): the point where the path meets the plane,
/// or `from` itself when `from` is already at or behind it. Never goes past `to`.
#[inline]
pub fn advance_to_plane(from: DVec3, to: DVec3, plane: &Plane) -> DVec3 {
    let h0 = plane.height(from);
    let h1 = plane.height(to);
    if h0 <= 0.0 {
        return from;
    }
    if h1 >= 0.0 {
        return to;
    }
    let s = h0 / (h0 - h1);
    from + s.clamp(0.0, 1.0) * (to - from)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn plane(n: DVec3, o: f64) -> Plane {
        Plane {
            normal: n.normalize(),
            offset: o,
        }
    }

    fn with(planes: &[Plane]) -> Constraints {
        let mut c = Constraints::NONE;
        planes.iter().for_each(|&p| assert!(c.push(p)));
        c
    }

    #[test]
    fn feasible_goal_is_kept() {
        let c = with(&[plane(DVec3::Z, 0.0)]);
        let g = DVec3::new(1.0, 2.0, 3.0);
        assert_eq!(c.closest_feasible(g, 0.0), Some(g));
    }

    #[test]
    fn projects_on_one_plane() {
        let c = with(&[plane(DVec3::Z, 0.5)]);
        let x = c.closest_feasible(DVec3::new(1.0, 2.0, -3.0), 0.0).unwrap();
        assert_eq!(x, DVec3::new(1.0, 2.0, 0.5));
    }

    #[test]
    fn concave_edge_and_corner() {
        // The floor z ≥ 0 and the wall x ≥ 0: a goal below and behind lands on the edge.
        let c = with(&[plane(DVec3::Z, 0.0), plane(DVec3::X, 0.0)]);
        let x = c
            .closest_feasible(DVec3::new(-1.0, 3.0, -2.0), 0.0)
            .unwrap();
        assert!(x.distance(DVec3::new(0.0, 3.0, 0.0)) < 1e-15);
        // Below the floor but in front of the wall: only the floor is active.
        let x = c.closest_feasible(DVec3::new(1.0, 3.0, -2.0), 0.0).unwrap();
        assert_eq!(x, DVec3::new(1.0, 3.0, 0.0));
        let c = with(&[
            plane(DVec3::Z, 0.0),
            plane(DVec3::X, 0.0),
            plane(DVec3::Y, 0.0),
        ]);
        let x = c.closest_feasible(DVec3::splat(-1.0), 0.0).unwrap();
        assert!(x.length() < 1e-15);
    }

    #[test]
    fn obtuse_valley_keeps_the_nearest_feasible_candidate() {
        // Two planes meeting at 150°: the goal's projection on one violates the other.
        let a = plane(DVec3::new(0.0, 0.0, 1.0), 0.0);
        let b = plane(DVec3::new(-0.5, 0.0, 0.866), 0.0);
        let c = with(&[a, b]);
        let goal = DVec3::new(0.3, 0.0, -1.0);
        let x = c.closest_feasible(goal, 1e-12).unwrap();
        assert!(a.height(x) >= -1e-12 && b.height(x) >= -1e-12);
        // Brute force over a fine grid of the feasible region finds nothing closer.
        let d = x.distance(goal);
        for i in -200..=200 {
            for k in -200..=200 {
                let y = DVec3::new(i as f64 * 0.01, 0.0, k as f64 * 0.01);
                if a.height(y) >= 0.0 && b.height(y) >= 0.0 {
                    assert!(y.distance(goal) >= d - 1e-12);
                }
            }
        }
    }

    #[test]
    fn advance_stops_at_the_plane() {
        let p = plane(DVec3::Z, 0.1);
        let x = advance_to_plane(DVec3::new(0.0, 0.0, 1.1), DVec3::new(0.0, 0.0, -0.9), &p);
        assert!((x.z - 0.1).abs() < 1e-15);
        // Already behind: stays.
        let from = DVec3::new(0.0, 0.0, 0.05);
        assert_eq!(advance_to_plane(from, DVec3::ZERO, &p), from);
    }
}
