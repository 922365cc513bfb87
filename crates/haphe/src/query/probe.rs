//! The segment a proxy move is tested with: the move itself, lengthened a little at both
//! ends so that surfaces within rounding of its end points are seen.

use glam::DVec3;

/// The segment tested for a proxy move `from → to` (metres, any one frame).
///
/// The watertight segment test decides crossings exactly, except where an end point lies
/// within rounding of a surface: the crossing there may be reported for neither of two
/// chained segments. A probe therefore reaches `reach` metres past `to`, so a move never
/// ends within reach of a surface ahead of it; and, for a one-sided surface (a closed
/// solid, by default), whose free side is known (the front), also `reach` metres before
/// `from`, counting only *entering* crossings, so a proxy that starts within rounding of a
/// face it moves into still meets it (a surface it leaves is never a crossing of that
/// kind). A two-sided surface has no known side: its probe starts at `from`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Probe {
    /// Start of the tested segment.
    pub p0: DVec3,
    /// End of the tested segment.
    pub p1: DVec3,
    /// Only entering crossings count (a one-sided surface).
    pub entering_only: bool,
    /// The probe parameter of `from`.
    from_t: f64,
    /// Probe length over move length.
    scale: f64,
}

impl Probe {
    /// The probe of the move `from → to`, reaching `reach` metres beyond it (behind
    /// `from` too when `one_sided`).
    #[inline]
    pub fn new(from: DVec3, to: DVec3, reach: f64, one_sided: bool) -> Probe {
        let d = to - from;
        let length = d.length();
        if !(length > 0.0 && length.is_finite() && reach >= 0.0) {
            return Probe {
                p0: from,
                p1: to,
                entering_only: one_sided,
                from_t: 0.0,
                scale: 1.0,
            };
        }
        let u = d / length;
        let back = if one_sided { reach } else { 0.0 };
        let total = length + back + reach;
        Probe {
            p0: from - back * u,
            p1: to + reach * u,
            entering_only: one_sided,
            from_t: back / total,
            scale: total / length,
        }
    }

    /// The parameter along the move `from → to` of a crossing at probe parameter `t`;
    /// crossings before `from` count as at `from` (0), crossings past `to` exceed 1.
    #[inline]
    pub fn move_t(&self, t: f64) -> f64 {
        ((t - self.from_t) * self.scale).max(0.0)
    }
}
