//! What the page draws of the scene: each object's surface (positions and triangles, in
//! the object frame) and its pose, sent once at connect as one binary message; and the
//! scene's force effects ([`EffectMark`]), sent with the page's `/info`.

use glam::{DQuat, DVec3};
use haphe::scene::Scene;
use haphe::servo::ObjectMotion;
use serde::Serialize;

use crate::effects::EffectMark;
use crate::feed::ShapeFeed;

/// One object as the page draws it.
#[derive(Debug, Clone)]
pub struct ObjectMesh {
    /// The object's id in the scene (traces name it).
    pub id: u32,
    /// A name for the page (file or shape name).
    pub name: String,
    /// Vertex positions, metres, object frame.
    pub positions: Vec<[f32; 3]>,
    /// Triangles, counter-clockwise seen from outside.
    pub triangles: Vec<[u32; 3]>,
    /// For each triangle, its face index in the file it came from (what traces record).
    pub source: Vec<u32>,
    /// Rotation, object axes to world axes.
    pub rotation: DQuat,
    /// Position of the object origin, metres, world frame.
    pub translation: DVec3,
}

/// The scene as the page draws it.
#[derive(Debug, Clone, Default)]
pub struct Model {
    /// The objects.
    pub objects: Vec<ObjectMesh>,
    /// The objects' scripted motions (a replay draws them moved; a live view takes the
    /// servo's own, [`LiveSource::motions`](crate::LiveSource::motions)).
    pub motions: Vec<ObjectMotion>,
    /// The tool's radius, metres (0: a point), that a replay draws the proxy as a sphere
    /// of (a live view takes the servo's own,
    /// [`ProxyOptions::tool_radius`](haphe::proxy::ProxyOptions::tool_radius)).
    pub tool_radius: f64,
    /// The scene's force effects, where they act.
    pub effects: Vec<EffectMark>,
    /// The versions of objects whose shape another thread changes (deforms or cuts), as
    /// it publishes them.
    pub feeds: Vec<ShapeFeed>,
}

/// What the page learns at connect besides the meshes (JSON).
#[derive(Debug, Clone, Serialize)]
pub struct ObjectInfo {
    /// Id in the scene.
    pub id: u32,
    /// Name.
    pub name: String,
    /// Triangles.
    pub triangles: usize,
}

/// Magic number at the start of the mesh message: `HPV1`, little-endian.
pub const MESH_MAGIC: u32 = u32::from_le_bytes(*b"HPV1");

impl Model {
    /// The objects of `scene` as they are placed now, and its effects; `names[i]` names
    /// the `i`-th object (missing names become `object N`).
    pub fn from_scene(scene: &Scene, names: &[String]) -> Model {
        let objects = scene
            .objects()
            .iter()
            .enumerate()
            .map(|(i, o)| {
                let s = o.shape.surface();
                ObjectMesh {
                    id: o.id.0,
                    name: names
                        .get(i)
                        .cloned()
                        .unwrap_or_else(|| format!("object {}", o.id.0)),
                    positions: s
                        .vertices()
                        .iter()
                        .map(|v| [v.x as f32, v.y as f32, v.z as f32])
                        .collect(),
                    triangles: s.triangles().to_vec(),
                    source: s.source_triangles().to_vec(),
                    rotation: o.pose.rotation(),
                    translation: o.pose.translation(),
                }
            })
            .collect();
        Model {
            objects,
            motions: Vec::new(),
            tool_radius: 0.0,
            effects: scene.effects().iter().map(EffectMark::of).collect(),
            feeds: Vec::new(),
        }
    }

    /// The model with an object whose shape changes (deformed or cut): the page redraws
    /// it from each version `feed` receives.
    pub fn with_shape_feed(mut self, feed: ShapeFeed) -> Model {
        self.feeds.push(feed);
        self
    }

    /// The model with the scripted motions of its objects.
    pub fn with_motions(mut self, motions: Vec<ObjectMotion>) -> Model {
        self.motions = motions;
        self
    }

    /// The model with the tool's radius, metres, for a replay.
    pub fn with_tool_radius(mut self, tool_radius: f64) -> Model {
        self.tool_radius = tool_radius;
        self
    }

    /// The world box of all vertices, metres; `None` without vertices.
    pub fn bounds(&self) -> Option<(DVec3, DVec3)> {
        let mut points = self.objects.iter().flat_map(|o| {
            o.positions.iter().map(|p| {
                o.translation
                    + o.rotation * DVec3::new(f64::from(p[0]), f64::from(p[1]), f64::from(p[2]))
            })
        });
        let first = points.next()?;
        Some(points.fold((first, first), |(lo, hi), p| (lo.min(p), hi.max(p))))
    }

    /// Names and sizes, for the page.
    pub fn info(&self) -> Vec<ObjectInfo> {
        self.objects
            .iter()
            .map(|o| ObjectInfo {
                id: o.id,
                name: o.name.clone(),
                triangles: o.triangles.len(),
            })
            .collect()
    }

    /// The binary mesh message, little-endian: `HPV1`, object count (u32); per object:
    /// id, vertex count, triangle count (u32 each), rotation x y z w and translation x y z
    /// (f32 each), positions (3 f32 per vertex), triangles (3 u32 each), source face
    /// indices (u32 each).
    pub fn encode(&self) -> Vec<u8> {
        let mut out = Vec::new();
        let u32s = |out: &mut Vec<u8>, v: u32| out.extend_from_slice(&v.to_le_bytes());
        let f32s = |out: &mut Vec<u8>, v: f32| out.extend_from_slice(&v.to_le_bytes());
        u32s(&mut out, MESH_MAGIC);
        u32s(&mut out, self.objects.len() as u32);
        for o in &self.objects {
            u32s(&mut out, o.id);
            u32s(&mut out, o.positions.len() as u32);
            u32s(&mut out, o.triangles.len() as u32);
            let q = o.rotation;
            for v in [q.x, q.y, q.z, q.w] {
                f32s(&mut out, v as f32);
            }
            for v in o.translation.to_array() {
                f32s(&mut out, v as f32);
            }
            for p in &o.positions {
                p.iter().for_each(|&v| f32s(&mut out, v));
            }
            for t in &o.triangles {
                t.iter().for_each(|&v| u32s(&mut out, v));
            }
            for &s in &o.source {
                u32s(&mut out, s);
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use haphe::map::MapOptions;
    use haphe::mesh::shapes::Catalog;
    use haphe::mesh::{Surface, SurfaceOptions};
    use haphe::scene::{Material, ObjectId, Pose, SceneObject, Shape};

    use super::*;

    #[test]
    fn the_message_holds_every_vertex_and_triangle() {
        let surface = Surface::new(
            Catalog::Sphere.with_triangles(200),
            &SurfaceOptions::default(),
        )
        .expect("surface");
        let shape = Arc::new(Shape::build(surface, &MapOptions::default()).expect("map"));
        let mut scene = Scene::local(1);
        scene
            .insert(SceneObject::new(
                ObjectId(7),
                shape,
                Pose::from_translation(DVec3::new(1.0, 0.0, 0.0)).expect("a valid pose"),
                Material::default(),
            ))
            .map_err(|(e, _)| e)
            .expect("room");
        let model = Model::from_scene(&scene, &[]);
        let o = &model.objects[0];
        assert_eq!((o.id, o.name.as_str()), (7, "object 7"));
        let bytes = model.encode();
        let expected = 8 + 12 + 28 + 12 * o.positions.len() + 16 * o.triangles.len();
        assert_eq!(bytes.len(), expected);
        assert_eq!(&bytes[..4], b"HPV1");
        let (lo, hi) = model.bounds().expect("vertices");
        assert!(lo.x > 0.0 && hi.x > 1.0 && (0.5 * (lo + hi) - DVec3::X).length() < 0.1);
    }
}
