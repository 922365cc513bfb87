//! Scripted object motions, applied by the servo loop at the start of each tick.

use glam::{DQuat, DVec3};

use crate::scene::{ObjectId, Param, ParamError, Pose};

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

/// The largest oscillation amplitude accepted, metres (the table of domains: [`Param`]).
pub const MAX_MOTION_AMPLITUDE: f64 = Param::MotionAmplitude.domain().high;

impl Motion {
    /// Checks the motion's numbers against the table of domains ([`Param`]): finite,
    /// within the domains of [`Param::MotionVelocity`], [`Param::MotionAmplitude`],
    /// [`Param::MotionFrequency`] (a 1 kHz servo samples 500 Hz twice a cycle; faster
    /// motions are aliased noise) and [`Param::MotionRate`], and a rotation axis of non-zero
    /// length. Scene files and code use this one check.
    ///
    /// # Errors
    /// A [`ParamError`] naming the first value that is not usable.
    pub fn checked(self) -> Result<Motion, ParamError> {
        match self {
            Motion::Linear { velocity } => {
                Param::MotionVelocity.check_vector(velocity.to_array())?;
            }
            Motion::Oscillating {
                amplitude,
                frequency,
            } => {
                Param::MotionAmplitude.check_vector(amplitude.to_array())?;
                Param::MotionFrequency.check(frequency)?;
            }
            Motion::Rotating { axis, rate } => {
                Param::MotionAxis.check_vector(axis.to_array())?;
                Param::MotionRate.check(rate)?;
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
            Motion::Linear { velocity } => Pose::sanitised(r, p + velocity * t),
            Motion::Oscillating {
                amplitude,
                frequency,
            } => Pose::sanitised(
                r,
                p + amplitude * (std::f64::consts::TAU * frequency * t).sin(),
            ),
            Motion::Rotating { axis, rate } => {
                let axis = axis.normalize_or_zero();
                if axis == DVec3::ZERO {
                    return self.base;
                }
                Pose::sanitised(DQuat::from_axis_angle(axis, rate * t) * r, p)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn poses_over_time() {
        let base = Pose::from_translation(DVec3::new(1.0, 0.0, 0.0)).unwrap();
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
