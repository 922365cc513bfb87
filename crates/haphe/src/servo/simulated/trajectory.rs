//! Smooth timed paths for simulated devices: a cubic Hermite curve through timed key
//! points.

use glam::DVec3;

/// Why a path could not be made.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum TrajectoryError {
    /// A path needs at least one key.
    #[error("a path needs at least one key point")]
    Empty,
    /// Key `index` has a non-finite time or position.
    #[error("key {index}: time and position must be finite")]
    NonFinite {
        /// Index of the key.
        index: usize,
    },
    /// Key `index` is not later than the key before it.
    #[error("key {index}: times must increase strictly")]
    NotIncreasing {
        /// Index of the key.
        index: usize,
    },
    /// The scene has no object to build a path over.
    #[error("the scene has no object to move over")]
    EmptyScene,
    /// A button press of a simulated device is not usable: a button beyond 31, or times
    /// that are not finite, the press before the release.
    #[error(
        "press of button {button}: the button must be 0 to 31 and its times finite, the press before the release"
    )]
    Press {
        /// The button (bit index).
        button: u32,
    },
}

/// A timed path: positions (metres) at key times (seconds), joined by cubic Hermite
/// segments.
///
/// The tangent at an inner key is the Catmull–Rom one, `(p₊ − p₋) / (t₊ − t₋)`, except
/// where the path stops or turns back (a neighbouring segment of zero length, or the two
/// segments pointing apart): there it is zero, so the path never overshoots a resting
/// point. The path starts and ends at rest and stays at its end points before the first
/// and after the last key. Keys equally spaced on a line in equal times give a constant
/// velocity between them.
#[derive(Debug, Clone, PartialEq)]
pub struct Trajectory {
    times: Vec<f64>,
    points: Vec<DVec3>,
    tangents: Vec<DVec3>,
}

impl Trajectory {
    /// A path through `keys` (time in seconds, position in metres).
    ///
    /// # Errors
    /// [`TrajectoryError`] when there is no key, a value is not finite, or times do not increase.
    pub fn from_keys(keys: &[(f64, DVec3)]) -> Result<Trajectory, TrajectoryError> {
        if keys.is_empty() {
            return Err(TrajectoryError::Empty);
        }
        for (index, &(t, p)) in keys.iter().enumerate() {
            if !t.is_finite() || !p.is_finite() {
                return Err(TrajectoryError::NonFinite { index });
            }
            if index > 0 && t <= keys[index - 1].0 {
                return Err(TrajectoryError::NotIncreasing { index });
            }
        }
        let times: Vec<f64> = keys.iter().map(|k| k.0).collect();
        let points: Vec<DVec3> = keys.iter().map(|k| k.1).collect();
        let n = points.len();
        let tangents = (0..n)
            .map(|i| {
                if i == 0 || i + 1 == n {
                    return DVec3::ZERO;
                }
                let before = points[i] - points[i - 1];
                let after = points[i + 1] - points[i];
                if before == DVec3::ZERO || after == DVec3::ZERO || before.dot(after) <= 0.0 {
                    DVec3::ZERO
                } else {
                    (points[i + 1] - points[i - 1]) / (times[i + 1] - times[i - 1])
                }
            })
            .collect();
        Ok(Trajectory {
            times,
            points,
            tangents,
        })
    }

    /// A path that stays at `p` (metres).
    pub fn still(p: DVec3) -> Trajectory {
        Trajectory {
            times: vec![0.0],
            points: vec![if p.is_finite() { p } else { DVec3::ZERO }],
            tangents: vec![DVec3::ZERO],
        }
    }

    /// Time of the last key, seconds.
    pub fn end_time(&self) -> f64 {
        self.times.last().copied().unwrap_or(0.0)
    }

    /// The key points (time in seconds, position in metres).
    pub fn keys(&self) -> impl Iterator<Item = (f64, DVec3)> + '_ {
        self.times.iter().copied().zip(self.points.iter().copied())
    }

    /// Position (metres) and velocity (m/s) at time `t` (seconds).
    ///
    /// # Real-time
    /// No allocation; a binary search over the keys.
    pub fn sample(&self, t: f64) -> (DVec3, DVec3) {
        let n = self.times.len();
        let (Some(&first), Some(&last)) = (self.points.first(), self.points.last()) else {
            return (DVec3::ZERO, DVec3::ZERO);
        };
        if !t.is_finite() || n == 1 || t <= self.times[0] {
            return (first, DVec3::ZERO);
        }
        if t >= self.times[n - 1] {
            return (last, DVec3::ZERO);
        }
        // The segment [i, i + 1] holding t: the last key at or before t.
        let i = self.times.partition_point(|&k| k <= t).saturating_sub(1);
        let i = i.min(n - 2);
        let (t0, t1) = (self.times[i], self.times[i + 1]);
        let h = t1 - t0;
        let s = (t - t0) / h;
        let (p0, p1) = (self.points[i], self.points[i + 1]);
        let (m0, m1) = (self.tangents[i] * h, self.tangents[i + 1] * h);
        let s2 = s * s;
        let s3 = s2 * s;
        let p = (2.0 * s3 - 3.0 * s2 + 1.0) * p0
            + (s3 - 2.0 * s2 + s) * m0
            + (-2.0 * s3 + 3.0 * s2) * p1
            + (s3 - s2) * m1;
        let v = ((6.0 * s2 - 6.0 * s) * p0
            + (3.0 * s2 - 4.0 * s + 1.0) * m0
            + (-6.0 * s2 + 6.0 * s) * p1
            + (3.0 * s2 - 2.0 * s) * m1)
            / h;
        (p, v)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn passes_through_keys_and_rests_at_the_ends() {
        let keys = [
            (0.0, DVec3::ZERO),
            (1.0, DVec3::X),
            (2.0, DVec3::new(1.0, 1.0, 0.0)),
            (3.0, DVec3::new(1.0, 1.0, 0.0)),
        ];
        let path = Trajectory::from_keys(&keys).expect("valid");
        for &(t, p) in &keys {
            assert!(path.sample(t).0.distance(p) < 1e-12);
        }
        assert_eq!(path.sample(-1.0), (DVec3::ZERO, DVec3::ZERO));
        assert_eq!(path.sample(9.0).1, DVec3::ZERO);
        // Velocity is the derivative of position.
        let (t, dt) = (1.3, 1e-6);
        let fd = (path.sample(t + dt).0 - path.sample(t - dt).0) / (2.0 * dt);
        assert!(fd.distance(path.sample(t).1) < 1e-6);
    }

    #[test]
    fn equal_steps_on_a_line_give_constant_speed() {
        let keys: Vec<(f64, DVec3)> = (0..6)
            .map(|i| (f64::from(i), DVec3::Z * -f64::from(i)))
            .collect();
        let path = Trajectory::from_keys(&keys).expect("valid");
        for t in [1.0, 1.5, 2.25, 3.9] {
            assert!((path.sample(t).1.z + 1.0).abs() < 1e-12, "{t}");
        }
    }

    #[test]
    fn bad_keys_are_refused() {
        assert_eq!(Trajectory::from_keys(&[]), Err(TrajectoryError::Empty));
        assert_eq!(
            Trajectory::from_keys(&[(0.0, DVec3::ZERO), (0.0, DVec3::X)]),
            Err(TrajectoryError::NotIncreasing { index: 1 })
        );
        assert_eq!(
            Trajectory::from_keys(&[(0.0, DVec3::NAN)]),
            Err(TrajectoryError::NonFinite { index: 0 })
        );
    }
}
