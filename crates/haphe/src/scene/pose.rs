//! Rigid poses: where an object's frame sits in the world.

use glam::{DQuat, DVec3};

use super::domain::ABSURD_DISTANCE_M;
use super::invalid::ParamError;
use super::param::Param;

/// A rigid transform `world_from_object`: a rotation, then a translation (metres).
///
/// Applied to a point `p_object` it gives `p_world = rotation · p_object + translation`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose {
    /// Unit quaternion, object axes to world axes.
    rotation: DQuat,
    /// Position of the object's origin in the world, metres.
    translation: DVec3,
    /// The rotation is the identity (a pure translation): points move by adding only.
    unrotated: bool,
}

impl Default for Pose {
    fn default() -> Pose {
        Pose::IDENTITY
    }
}

impl Pose {
    /// The object frame is the world frame.
    pub const IDENTITY: Pose = Pose {
        rotation: DQuat::IDENTITY,
        translation: DVec3::ZERO,
        unrotated: true,
    };

    /// A pose from a rotation (a quaternion of any non-zero length, normalised here) and a
    /// translation in metres.
    ///
    /// # Errors
    /// [`ParamError`] naming `rotation` for a quaternion that is not finite or of zero
    /// length, or `position` for a translation that is not finite or farther than
    /// `ABSURD_DISTANCE_M` from the origin.
    ///
    /// ```
    /// use haphe::glam::{DQuat, DVec3};
    /// use haphe::scene::{Param, Pose};
    /// assert!(Pose::new(DQuat::from_rotation_z(0.5), DVec3::X).is_ok());
    /// let e = Pose::new(DQuat::IDENTITY, DVec3::new(f64::NAN, 0.0, 0.0)).unwrap_err();
    /// assert_eq!(e.param(), Param::Position);
    /// ```
    pub fn new(rotation: DQuat, translation: DVec3) -> Result<Pose, ParamError> {
        Param::Rotation.check_vector(rotation.to_array())?;
        Param::Position.check_vector(translation.to_array())?;
        Ok(Pose::sanitised(rotation, translation))
    }

    /// A pose from a rotation and a translation computed on the servo path (a scripted
    /// motion): a non-finite or zero rotation gives the identity rotation, a non-finite
    /// translation gives zero, so that a tick never fails.
    pub(crate) fn sanitised(rotation: DQuat, translation: DVec3) -> Pose {
        let rotation = if rotation.is_finite() && rotation.length_squared() > 0.0 {
            rotation.normalize()
        } else {
            DQuat::IDENTITY
        };
        let translation = if translation.is_finite() {
            translation
        } else {
            DVec3::ZERO
        };
        Pose {
            rotation,
            translation,
            unrotated: rotation == DQuat::IDENTITY,
        }
    }

    /// A pure translation, metres: the same pose as `Pose::new(DQuat::IDENTITY,
    /// translation)`, without normalising the rotation.
    ///
    /// # Errors
    /// [`ParamError`] naming `position`, as [`Pose::new`].
    #[inline]
    pub fn from_translation(translation: DVec3) -> Result<Pose, ParamError> {
        // `0 · x` is 0 for a finite `x`, NaN otherwise: one compare for all three.
        if (translation * 0.0).element_sum() == 0.0
            && translation.length_squared() <= ABSURD_DISTANCE_M * ABSURD_DISTANCE_M
        {
            Ok(Pose {
                rotation: DQuat::IDENTITY,
                translation,
                unrotated: true,
            })
        } else {
            // The error, or a length that rounds to the bound.
            Pose::new(DQuat::IDENTITY, translation)
        }
    }

    /// Whether the rotation is the identity (a pure translation).
    #[inline]
    pub(crate) fn is_unrotated(&self) -> bool {
        self.unrotated
    }

    /// The rotation, object axes to world axes.
    pub fn rotation(&self) -> DQuat {
        self.rotation
    }

    /// The translation, metres.
    pub fn translation(&self) -> DVec3 {
        self.translation
    }

    /// `p_world` of a point given in the object frame.
    #[inline]
    pub fn to_world(&self, p_object: DVec3) -> DVec3 {
        if self.unrotated {
            return p_object + self.translation;
        }
        self.rotation * p_object + self.translation
    }

    /// `p_object` of a point given in the world frame.
    #[inline]
    pub fn to_object(&self, p_world: DVec3) -> DVec3 {
        if self.unrotated {
            return p_world - self.translation;
        }
        self.rotation.inverse() * (p_world - self.translation)
    }

    /// A direction (normal, velocity) from object axes to world axes.
    #[inline]
    pub fn vector_to_world(&self, v_object: DVec3) -> DVec3 {
        if self.unrotated {
            return v_object;
        }
        self.rotation * v_object
    }

    /// A direction from world axes to object axes.
    #[inline]
    pub fn vector_to_object(&self, v_world: DVec3) -> DVec3 {
        if self.unrotated {
            return v_world;
        }
        self.rotation.inverse() * v_world
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trip() {
        let pose = Pose::new(
            DQuat::from_axis_angle(DVec3::new(1.0, 2.0, 3.0).normalize(), 0.7),
            DVec3::new(0.1, -0.2, 0.3),
        )
        .unwrap();
        let p = DVec3::new(0.4, 0.5, -0.6);
        assert!(pose.to_object(pose.to_world(p)).distance(p) < 1e-15);
        assert!(pose.vector_to_object(pose.vector_to_world(p)).distance(p) < 1e-15);
    }

    #[test]
    fn a_translation_is_the_pose_with_the_identity_rotation() {
        for t in [
            DVec3::new(0.1, -2.0, 3e5),
            DVec3::ZERO,
            DVec3::NAN,
            DVec3::INFINITY,
            DVec3::new(2e9, 0.0, 0.0),
        ] {
            // As text: an error's NaN is not equal to itself.
            assert_eq!(
                format!("{:?}", Pose::from_translation(t)),
                format!("{:?}", Pose::new(DQuat::IDENTITY, t)),
            );
        }
    }

    #[test]
    fn bad_input_is_refused_naming_the_parameter() {
        let zero = DQuat::from_xyzw(0.0, 0.0, 0.0, 0.0);
        let e = Pose::new(zero, DVec3::ZERO).unwrap_err();
        assert_eq!(e.param(), Param::Rotation);
        let e = Pose::new(DQuat::IDENTITY, DVec3::new(0.0, f64::INFINITY, 0.0)).unwrap_err();
        assert_eq!(e.param(), Param::Position);
        assert_eq!(Pose::sanitised(zero, DVec3::NAN), Pose::IDENTITY);
    }
}
