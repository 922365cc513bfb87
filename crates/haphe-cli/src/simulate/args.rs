//! The arguments `haphe simulate` and `haphe run` share: the objects of the session (a
//! mesh file, a scene file or a built-in shape, and the material of a lone object) and the
//! files the session writes.

use std::path::PathBuf;

use anyhow::anyhow;
use haphe::mesh::Units;
use haphe::scene::Material;

use super::Model;

/// Where the objects come from (exactly one of `--mesh`, `--scene`, `--shape`), and the
/// material of a `--mesh` or `--shape` object.
#[derive(clap::Args, Debug)]
#[command(group(clap::ArgGroup::new("model").required(true).args(["mesh", "scene", "shape"])))]
pub struct ModelArgs {
    /// A mesh file (OBJ, STL, PLY, OFF) placed with the centre of its bounding box at the
    /// origin.
    #[arg(long, value_name = "FILE")]
    pub mesh: Option<PathBuf>,
    /// A scene file (TOML): objects, poses, materials, motions (see docs/guide.md).
    #[arg(long, value_name = "FILE.toml")]
    pub scene: Option<PathBuf>,
    /// A built-in shape at the origin: sphere, torus, box, thin-plate, concave-corner, blob.
    #[arg(long, value_name = "NAME")]
    pub shape: Option<String>,
    /// Triangles of the built-in shape.
    #[arg(long, default_value_t = 20_000)]
    pub triangles: usize,
    /// Length unit of the mesh file: m, mm, cm, in, or metres per unit.
    #[arg(long, default_value = "m", value_parser = crate::validate::parse_units)]
    pub units: Units,
    /// Stiffness of a --mesh or --shape object, N/m.
    #[arg(long, default_value_t = 600.0)]
    pub stiffness: f64,
    /// Damping of a --mesh or --shape object, N·s/m.
    #[arg(long, default_value_t = 1.0)]
    pub damping: f64,
    /// Static friction coefficient of a --mesh or --shape object.
    #[arg(long, default_value_t = 0.3)]
    pub static_friction: f64,
    /// Dynamic friction coefficient of a --mesh or --shape object.
    #[arg(long, default_value_t = 0.2)]
    pub dynamic_friction: f64,
}

impl ModelArgs {
    /// The model to load.
    pub fn model(&self) -> Model<'_> {
        Model {
            scene: self.scene.as_deref(),
            mesh: self.mesh.as_deref(),
            shape: self.shape.as_deref(),
            triangles: self.triangles,
            units: self.units,
        }
    }

    /// The material of a `--mesh` or `--shape` object, checked as a scene file's are.
    ///
    /// # Errors
    /// A value out of its range, named as its option.
    pub fn material(&self) -> anyhow::Result<Material> {
        material_of_flags(
            self.stiffness,
            self.damping,
            self.static_friction,
            self.dynamic_friction,
        )
    }
}

/// The material of the flags `--stiffness`, `--damping`, `--static-friction` and
/// `--dynamic-friction`, checked by the library's table of domains.
///
/// # Errors
/// A value outside its domain, named as its flag.
pub fn material_of_flags(
    stiffness: f64,
    damping: f64,
    static_friction: f64,
    dynamic_friction: f64,
) -> anyhow::Result<Material> {
    Material::builder()
        .stiffness(stiffness)
        .damping(damping)
        .friction(static_friction, dynamic_friction)
        .build()
        .map_err(|e| anyhow!("--{}", e.to_string().replace('_', "-")))
}

/// The files a session writes.
#[derive(clap::Args, Debug)]
pub struct OutputArgs {
    /// Write every tick to this CSV file.
    #[arg(long, value_name = "FILE.csv")]
    pub out: Option<PathBuf>,
    /// Draw force, penetration and the side view of the path to this PNG.
    #[arg(long, value_name = "FILE.png")]
    pub plot: Option<PathBuf>,
}
