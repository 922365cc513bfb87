//! The objects of a session: a scene file, a mesh file placed at the origin, or a
//! built-in shape.

use std::path::Path;
use std::sync::Arc;

use anyhow::{anyhow, bail};
use haphe::map::MapOptions;
use haphe::mesh::Units;
use haphe::mesh::shapes::Catalog;
use haphe::scene::{Material, ObjectId, Pose, SceneObject};
use haphe::volume::{CutOptions, Cutter, Layer, Volume};

use crate::input::mesh::UnitsGiven;
use crate::input::scene::{LoadedObject, LoadedScene, load_scene, mesh_shape, shape_of};
use crate::input::volume::read_volume;

/// Where the objects of a run come from: one of a scene file, a mesh file, a built-in shape.
pub struct Model<'a> {
    pub scene: Option<&'a Path>,
    pub mesh: Option<&'a Path>,
    pub shape: Option<&'a str>,
    pub triangles: usize,
    pub units: Units,
    /// A volume file (NIfTI-1), with its iso value.
    pub volume: Option<(&'a Path, Option<f32>)>,
    /// With a mesh: voxelise it on a grid of this spacing, metres, and make it a volume.
    pub voxel: Option<f64>,
    /// The volume's layers, as `--layer` spells them.
    pub layers: &'a [String],
}

/// Loads the objects of a run (a --mesh or --shape object gets `material`), with a scene
/// file's tool radius, and says what they are.
pub fn load_model(model: Model<'_>, material: Material) -> anyhow::Result<(LoadedScene, String)> {
    if let Some(loaded) = load_volume(&model, material)? {
        return Ok(loaded);
    }
    let map = MapOptions::default();
    Ok(if let Some(file) = model.scene {
        (load_scene(file, &map)?, file.display().to_string())
    } else if let Some(file) = model.mesh {
        let shape = Arc::new(mesh_shape(file, model.units, &map, UnitsGiven::Flag)?);
        // The paths explore the workspace around the origin: the mesh is placed there.
        let (lo, hi) = shape.surface().bounds();
        let centre = (lo + hi) * 0.5;
        if centre.length() > 1e-9 {
            eprintln!(
                "haphe: {} placed with its centre at the origin (moved by {:.6?} m)",
                file.display(),
                (-centre).to_array()
            );
        }
        let o = SceneObject::new(
            ObjectId(0),
            shape,
            Pose::from_translation(-centre)
                .map_err(|e| anyhow!("{}: placing it at the origin: {e}", file.display()))?,
            material,
        );
        (
            vec![LoadedObject {
                name: file.display().to_string(),
                object: o,
                motion: None,
            }]
            .into(),
            file.display().to_string(),
        )
    } else {
        let name = model.shape.unwrap_or("blob");
        let which: Catalog = name.parse().map_err(|e| anyhow!("--shape {name:?}: {e}"))?;
        Catalog::check_triangles(model.triangles).map_err(|e| anyhow!("--triangles: {e}"))?;
        let shape = Arc::new(shape_of(which, model.triangles, &map)?);
        let o = SceneObject::new(ObjectId(0), shape, Pose::IDENTITY, material);
        (
            vec![LoadedObject {
                name: name.to_string(),
                object: o,
                motion: None,
            }]
            .into(),
            format!("the built-in {name}"),
        )
    })
}

/// The volume object of `model` (with its cutter) when it names one: a volume file, or a
/// mesh voxelised (`voxel`); `None` for the other models.
///
/// # Errors
/// The file cannot be read, or the mesh voxelised, naming the file; a `--layer` refused,
/// or given without a volume.
pub fn load_volume(
    model: &Model<'_>,
    material: Material,
) -> anyhow::Result<Option<(LoadedScene, String)>> {
    let layers = model
        .layers
        .iter()
        .map(|spec| spec.parse::<Layer>().map_err(|e| anyhow!("--layer: {e}")))
        .collect::<anyhow::Result<Vec<Layer>>>()?;
    let is_volume = model.volume.is_some() || (model.mesh.is_some() && model.voxel.is_some());
    if !layers.is_empty() && !is_volume {
        bail!("--layer needs a volume: --volume FILE.nii, or --mesh FILE with --voxel SIZE");
    }
    if let Some((file, iso)) = model.volume {
        let (volume, info) = read_volume(file, iso)?;
        for note in &info.notes {
            eprintln!("haphe: {}: {note}", file.display());
        }
        return volume_object(&file.display().to_string(), volume, (material, layers)).map(Some);
    }
    if let (Some(file), Some(voxel)) = (model.mesh, model.voxel) {
        let map = MapOptions::default();
        let shape = mesh_shape(file, model.units, &map, UnitsGiven::Flag)?;
        let volume = Volume::from_shape(&shape, voxel)
            .map_err(|e| anyhow!("{}: voxelising it: {}", file.display(), e))?;
        return volume_object(&file.display().to_string(), volume, (material, layers)).map(Some);
    }
    Ok(None)
}

/// The object of `volume` (named `name`): the surface of its material extracted, placed
/// with the centre of its grid at the origin, and the cutter that owns it; its triangles
/// feel like their `layers` when there are any.
fn volume_object(
    name: &str,
    volume: Volume,
    (material, layers): (Material, Vec<Layer>),
) -> anyhow::Result<(LoadedScene, String)> {
    let [nx, ny, nz] = volume.dims();
    let centre = volume.centre();
    let mut cutter = Cutter::new(name, volume, MapOptions::default())?;
    if !layers.is_empty() {
        cutter.set_options(CutOptions::default().with_layers(layers))?;
        for l in cutter.options().layers() {
            eprintln!(
                "haphe: {name}: {} from {}: {} N/m, friction {}/{}, cut at {} mm/s",
                l.name,
                l.from,
                l.material.stiffness(),
                l.material.static_friction(),
                l.material.dynamic_friction(),
                l.rate * 1e3
            );
        }
    }
    let shape = Arc::clone(cutter.shape());
    eprintln!(
        "haphe: {name}: a volume of {nx} × {ny} × {nz} voxels, its surface {} triangles, placed with the centre of its grid at the origin (moved by {:.6?} m)",
        shape.surface().triangle_count(),
        (-centre).to_array()
    );
    let pose = Pose::from_translation(-centre)
        .map_err(|e| anyhow!("{name}: placing it at the origin: {e}"))?;
    let object = SceneObject::new(ObjectId(0), shape, pose, material);
    let mut loaded: LoadedScene = vec![LoadedObject {
        name: name.to_owned(),
        object,
        motion: None,
    }]
    .into();
    loaded.cutter = Some(cutter);
    Ok((loaded, format!("the volume {name}")))
}
