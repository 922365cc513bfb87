//! How large a scene is: the box bounding its objects, and the check of a tool radius
//! against it (a tool that holds the whole scene is a mistake, not a tool).

use glam::DVec3;

use super::world::Scene;
use super::{Param, ParamError};

impl Scene {
    /// The axis-aligned box `(min, max)` bounding the objects as placed now, metres, world
    /// frame: the union of each object's own bounding box (its surface's vertices, object
    /// frame) with its eight corners placed by the object's pose. `None` without objects.
    ///
    /// # Performance
    /// Eight points per object; no vertex is visited.
    pub fn bounding_box(&self) -> Option<(DVec3, DVec3)> {
        self.objects.iter().fold(None, |acc, o| {
            let (lo, hi) = o.shape.surface().bounds();
            let corners = (0..8).map(|i: u32| {
                let pick = |bit: u32, a: f64, b: f64| if i & bit == 0 { a } else { b };
                o.pose.to_world(DVec3::new(
                    pick(1, lo.x, hi.x),
                    pick(2, lo.y, hi.y),
                    pick(4, lo.z, hi.z),
                ))
            });
            corners.fold(acc, |acc, p| match acc {
                None => Some((p, p)),
                Some((a, b)) => Some((a.min(p), b.max(p))),
            })
        })
    }

    /// `tool_radius` (metres) when it fits this scene: in its domain
    /// ([`Param::ToolRadius`]) and at most the diagonal of [`Scene::bounding_box`] (a tool
    /// of a larger radius holds the whole scene inside it). Any radius in the domain fits
    /// an empty scene.
    ///
    /// # Errors
    /// [`ParamError`] naming `tool_radius`: outside its domain, or larger than the scene.
    pub fn check_tool_radius(&self, tool_radius: f64) -> Result<f64, ParamError> {
        let r = Param::ToolRadius.check(tool_radius)?;
        match self.bounding_box() {
            Some((lo, hi)) if r > (hi - lo).length() => Err(ParamError::LargerThanScene {
                param: Param::ToolRadius,
                value: r,
                diagonal: (hi - lo).length(),
            }),
            _ => Ok(r),
        }
    }
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use glam::DQuat;

    use crate::map::MapOptions;
    use crate::mesh::shapes;
    use crate::scene::{Material, ObjectId, Pose, SceneObject, Shape};

    use super::*;

    /// A scene of one cube of side `side` centred at `at`, turned by `rotation`.
    fn cube_scene(side: f64, at: DVec3, rotation: DQuat) -> Scene {
        let shape = Shape::from_mesh(
            "cube",
            shapes::cuboid(DVec3::splat(0.5 * side), [1, 1, 1]),
            &MapOptions::default(),
        )
        .expect("a cube's shape");
        let mut scene = Scene::local(1);
        let pose = Pose::new(rotation, at).expect("a valid pose");
        scene
            .insert(SceneObject::new(
                ObjectId(0),
                Arc::new(shape),
                pose,
                Material::default(),
            ))
            .map_err(|(e, _)| e)
            .expect("room");
        scene
    }

    #[test]
    fn the_box_of_a_placed_cube_is_its_corners() {
        let at = DVec3::new(1.0, -2.0, 0.5);
        let scene = cube_scene(0.2, at, DQuat::IDENTITY);
        let (lo, hi) = scene.bounding_box().expect("one object");
        assert!((lo - (at - DVec3::splat(0.1))).length() < 1e-12, "{lo}");
        assert!((hi - (at + DVec3::splat(0.1))).length() < 1e-12, "{hi}");
        // Turned 45° about z: the box is as wide as the square's diagonal in x and y.
        let turned = cube_scene(0.2, at, DQuat::from_rotation_z(std::f64::consts::FRAC_PI_4));
        let (lo, hi) = turned.bounding_box().expect("one object");
        let half = 0.1 * std::f64::consts::SQRT_2;
        assert!(((hi - lo).x - 2.0 * half).abs() < 1e-12);
        assert!(((hi - lo).z - 0.2).abs() < 1e-12);
        assert!(Scene::local(1).bounding_box().is_none());
    }

    #[test]
    fn a_tool_radius_fits_up_to_the_scene_diagonal() {
        // A 10 cm cube: its diagonal is 10√3 cm.
        let scene = cube_scene(0.1, DVec3::ZERO, DQuat::IDENTITY);
        let diagonal = 0.1 * 3f64.sqrt();
        assert_eq!(scene.check_tool_radius(0.0), Ok(0.0));
        assert_eq!(
            scene.check_tool_radius(diagonal * 0.999),
            Ok(diagonal * 0.999)
        );
        let e = scene
            .check_tool_radius(diagonal * 1.001)
            .expect_err("larger than the scene");
        assert_eq!(e.param(), Param::ToolRadius);
        let message = e.named("--tool-radius").to_string();
        assert!(
            message.starts_with("--tool-radius must be at most 0.1732 m, the diagonal"),
            "{message}"
        );
        assert!(
            message.ends_with(&format!("not {}", diagonal * 1.001)),
            "{message}"
        );
        // The domain is checked first, whatever the scene.
        for bad in [-1e-3, f64::NAN, f64::INFINITY, 0.6] {
            let e = scene
                .check_tool_radius(bad)
                .expect_err("outside the domain");
            assert!(matches!(e, ParamError::OutOfDomain { .. }), "{bad}: {e}");
            assert!(Scene::local(1).check_tool_radius(bad).is_err());
        }
        assert_eq!(Scene::local(1).check_tool_radius(0.5), Ok(0.5));
    }
}
