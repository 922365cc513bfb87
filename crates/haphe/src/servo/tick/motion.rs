//! Scripted object motions, applied by the servo loop at the start of each tick.

use glam::{DQuat, DVec3};

use crate::scene::{InvalidValue, ObjectId, Pose};

/// How an object moves over time, from its base pose.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Motion {
    /// Constant velocity, m/s, world frame.
    Linear {
        /// Velocity, m/s.
        velocity: DVec3,
    },
    /// Back and forth: `base + amplitude · sin(2π f t)`.
    Oscillating {
        /// Amplitude and direction, metres, world frame.
        amplitude: DVec3,
        /// Frequency, Hz.
        frequency: f64,
    },
    /// Turning about an axis through the object's origin (its base translation).
    Rotating {
        /// Axis, world frame (normalised when used; a zero axis means no rotation).
        axis: DVec3,
        /// Angular speed, rad/s.
        rate: f64,
    },
}

/// An object of the scene that moves: its name, its pose at `t = 0` and its motion.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ObjectMotion {
    /// The moving object.
    pub id: ObjectId,
    /// `world_from_object` at `t = 0`.
    pub base: Pose,
    /// The motion.
    pub motion: Motion,
}

/// The fastest linear motion accepted, m/s.
pub const MAX_MOTION_SPEED: f64 = 100.0;
/// The largest oscillation amplitude accepted, metres.
pub const MAX_MOTION_AMPLITUDE: f64 = 100.0;
/// The highest oscillation frequency accepted, Hz (a 1 kHz servo samples it twice a cycle
/// at 500 Hz; faster motions are aliased noise).
pub const MAX_MOTION_FREQUENCY: f64 = 500.0;
/// The fastest rotation accepted, rad/s.
pub const MAX_MOTION_RATE: f64 = 1000.0;

impl Motion {
    /// Checks the motion's numbers: finite, at most 100 m/s, 100 m of amplitude, 500 Hz
    /// and 1000 rad/s (`MAX_MOTION_SPEED`, `MAX_MOTION_AMPLITUDE`, `MAX_MOTION_FREQUENCY`,
    /// `MAX_MOTION_RATE`), and a rotation axis of non-zero length. Scene files and code use this one check.
    ///
    /// # Errors
    /// An [`InvalidValue`] naming the first value that is not usable.
    pub fn checked(self) -> Result<Motion, InvalidValue> {
        match self {
            Motion::Linear { velocity } => {
                InvalidValue::check_vector("motion velocity", velocity, MAX_MOTION_SPEED)?;
            }
            Motion::Oscillating {
                amplitude,
                frequency,
            } => {
                InvalidValue::check_vector("motion amplitude", amplitude, MAX_MOTION_AMPLITUDE)?;
                InvalidValue::check_range(
                    "motion frequency",
                    frequency,
                    0.0,
                    MAX_MOTION_FREQUENCY,
                )?;
            }
            Motion::Rotating { axis, rate } => {
                InvalidValue::check_vector("motion axis", axis, f64::MAX)?;
                if axis.length() < 1e-12 {
                    return Err(InvalidValue {
                        field: "motion axis",
                        value: axis.length(),
                        expected: "a direction (of non-zero length)".into(),
                    });
                }
                InvalidValue::check_range("motion rate", rate, -MAX_MOTION_RATE, MAX_MOTION_RATE)?;
            }
        }
        Ok(self)
    }
}

impl ObjectMotion {
    /// The pose at time `t`, seconds (`world_from_object`).
    ///
    /// # Real-time
    /// No allocation; a few operations.
    pub fn pose_at(&self, t: f64) -> Pose {
        let (r, p) = (self.base.rotation(), self.base.translation());
        match self.motion {
            Motion::Linear { velocity } => Pose::new(r, p + velocity * t),
            Motion::Oscillating {
                amplitude,
                frequency,
            } => Pose::new(
                r,
                p + amplitude * (std::f64::consts::TAU * frequency * t).sin(),
            ),
            Motion::Rotating { axis, rate } => {
                let axis = axis.normalize_or_zero();
                if axis == DVec3::ZERO {
                    return self.base;
                }
                Pose::new(DQuat::from_axis_angle(axis, rate * t) * r, p)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn poses_over_time() {
        let base = Pose::from_translation(DVec3::new(1.0, 0.0, 0.0));
        let id = ObjectId(0);
        let linear = ObjectMotion {
            id,
            base,
            motion: Motion::Linear { velocity: DVec3::Y },
        };
        assert_eq!(linear.pose_at(2.0).translation(), DVec3::new(1.0, 2.0, 0.0));
        let osc = ObjectMotion {
            id,
            base,
            motion: Motion::Oscillating {
                amplitude: DVec3::Z * 0.1,
                frequency: 1.0,
            },
        };
        assert!((osc.pose_at(0.25).translation().z - 0.1).abs() < 1e-12);
        let rot = ObjectMotion {
            id,
            base,
            motion: Motion::Rotating {
                axis: DVec3::Z,
                rate: std::f64::consts::FRAC_PI_2,
            },
        };
        let p = rot.pose_at(1.0).to_world(DVec3::X);
        assert!(p.distance(DVec3::new(1.0, 1.0, 0.0)) < 1e-12);
    }
}
