//! Where the moving objects are: the poses of the scene's scripted motions at a tick's
//! time, computed off the servo thread from the same [`ObjectMotion::pose_at`] the servo
//! applies at that time (so they are the poses the tick rendered against, exactly), once
//! per display frame for a live view and once per row for a replay.

use haphe::servo::ObjectMotion;
use serde::Serialize;

/// Values per moving object per replay row in [`encode_poses`]: rotation x y z w, then
/// translation x y z.
pub const POSE_VALUES: usize = 7;

/// The pose of one moving object, as the page places its mesh.
#[derive(Debug, Clone, Copy, Serialize, PartialEq)]
pub struct ObjectPose {
    /// The object's id in the scene.
    pub id: u32,
    /// Rotation, object axes to world axes, quaternion x y z w.
    pub rotation: [f64; 4],
    /// Position of the object origin, metres, world frame.
    pub translation: [f64; 3],
}

/// The poses of the objects `motions` move, at time `t` (seconds since the start).
pub fn poses_at(motions: &[ObjectMotion], t: f64) -> Vec<ObjectPose> {
    motions
        .iter()
        .map(|m| {
            let pose = m.pose_at(t);
            let q = pose.rotation();
            ObjectPose {
                id: m.id.0,
                rotation: [q.x, q.y, q.z, q.w],
                translation: pose.translation().to_array(),
            }
        })
        .collect()
}

/// The poses of every row of a replay, little-endian f32: for each time of `times`, for
/// each motion in order, [`POSE_VALUES`] values.
pub fn encode_poses(motions: &[ObjectMotion], times: impl Iterator<Item = f64>) -> Vec<u8> {
    let mut out = Vec::new();
    for t in times {
        for p in poses_at(motions, t) {
            for v in p.rotation.into_iter().chain(p.translation) {
                out.extend_from_slice(&(v as f32).to_le_bytes());
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use haphe::DVec3;
    use haphe::scene::{ObjectId, Pose};
    use haphe::servo::Motion;

    #[test]
    fn poses_follow_the_motion_and_encode_per_row() {
        let motions = [ObjectMotion {
            id: ObjectId(3),
            base: Pose::from_translation(DVec3::new(1.0, 0.0, 0.0)).expect("a valid pose"),
            motion: Motion::Linear {
                velocity: DVec3::new(0.0, 0.5, 0.0),
            },
        }];
        let p = poses_at(&motions, 2.0);
        assert_eq!(p.len(), 1);
        assert_eq!(p[0].id, 3);
        assert_eq!(p[0].translation, [1.0, 1.0, 0.0]);
        assert_eq!(p[0].rotation, [0.0, 0.0, 0.0, 1.0]);
        let bytes = encode_poses(&motions, [0.0, 2.0].into_iter());
        assert_eq!(bytes.len(), 2 * POSE_VALUES * 4);
        let f = |i: usize| f32::from_le_bytes(bytes[4 * i..4 * i + 4].try_into().expect("4"));
        assert_eq!((f(4), f(5)), (1.0, 0.0));
        assert_eq!((f(POSE_VALUES + 4), f(POSE_VALUES + 5)), (1.0, 1.0));
        assert!(poses_at(&[], 1.0).is_empty());
    }
}
