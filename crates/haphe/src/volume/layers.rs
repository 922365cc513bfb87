//! What a volume's material is made of: a table from values to how each material feels
//! and how fast the tool cuts it (enamel harder than dentin, cortical bone harder than
//! cancellous bone).

use std::str::FromStr;

use crate::scene::{Material, Param, ParamError, Spec, SpecError, number};

/// How a layer is spelled (`--layer`).
const LAYER_FORM: &str =
    "`NAME:FROM:RATE:STIFFNESS[:STATIC_FRICTION[:DYNAMIC_FRICTION]]` (the lowest value, m/s, N/m)";

/// One material of a volume: the values from `from` up to the next layer's `from`.
#[derive(Debug, Clone, PartialEq)]
pub struct Layer {
    /// What the material is called (in summaries).
    pub name: String,
    /// The lowest value of the material (a label, or the start of a range).
    pub from: f32,
    /// How the material feels.
    pub material: Material,
    /// How fast the tool removes it, m/s: the depth it sinks in a second under the cut
    /// force (a voxel goes after `voxel / rate` seconds of pressing).
    pub rate: f64,
}

impl Layer {
    /// The rate a material is cut at unless told otherwise, m/s: the tool sinks 20 mm a
    /// second into it at the cut force.
    pub const DEFAULT_RATE: f64 = 0.02;

    /// The material `name` for values from `from` up, feeling like `material`, cut at
    /// `rate` m/s.
    ///
    /// # Errors
    /// [`ParamError`] naming [`Param::CutRate`] or [`Param::LayerValue`] (not finite)
    /// outside its domain.
    pub fn new(name: &str, from: f32, material: Material, rate: f64) -> Result<Layer, ParamError> {
        Param::LayerValue.check(f64::from(from))?;
        Ok(Layer {
            name: name.to_owned(),
            from,
            material,
            rate: Param::CutRate.check(rate)?,
        })
    }
}

impl FromStr for Layer {
    type Err = SpecError;

    /// `NAME:FROM:RATE:STIFFNESS[:STATIC_FRICTION[:DYNAMIC_FRICTION]]`: the material
    /// `NAME` for values from `FROM` up, cut at `RATE` m/s, of `STIFFNESS` N/m and the
    /// friction coefficients (none unless given; the dynamic equal to the static unless
    /// given), no damping.
    ///
    /// ```
    /// use haphe::volume::Layer;
    /// let enamel: Layer = "enamel:2:0.002:900:0.4".parse()?;
    /// assert_eq!((enamel.from, enamel.rate), (2.0, 0.002));
    /// assert_eq!(enamel.material.dynamic_friction(), 0.4);
    /// assert!("enamel:2:0:900".parse::<Layer>().is_err());
    /// # Ok::<(), haphe::scene::SpecError>(())
    /// ```
    fn from_str(text: &str) -> Result<Layer, SpecError> {
        let spec = Spec::split(text);
        if spec.kind.is_empty() || !(3..=5).contains(&spec.values.len()) {
            return Err(spec.form(LAYER_FORM));
        }
        let values = spec
            .values
            .iter()
            .map(|v| number(text, v))
            .collect::<Result<Vec<f64>, SpecError>>()?;
        let (from, rate, stiffness) = (values[0], values[1], values[2]);
        let friction = values.get(3).copied().unwrap_or(0.0);
        let dynamic = values.get(4).copied().unwrap_or(friction);
        let material = Material::builder()
            .stiffness(stiffness)
            .friction(friction, dynamic)
            .build()
            .map_err(|e| spec.param(e))?;
        // The value is checked as a number first: `from` as f32 would make a huge finite
        // number infinite.
        Param::LayerValue.check(from).map_err(|e| spec.param(e))?;
        Layer::new(spec.kind, from as f32, material, rate).map_err(|e| spec.param(e))
    }
}

/// The layers of a volume sorted by `from`; values below the first are the first's.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Layers {
    layers: Vec<Layer>,
}

impl Layers {
    /// The table of `layers` (sorted here by `from`); one material of the default when
    /// empty.
    pub(crate) fn new(mut layers: Vec<Layer>) -> Layers {
        if layers.is_empty() {
            return Layers::default();
        }
        layers.sort_by(|a, b| a.from.total_cmp(&b.from));
        Layers { layers }
    }

    /// The index in [`Layers::layers`] of the layer of `value` (see [`Layers::of`]).
    pub(crate) fn index_of(&self, value: f32) -> usize {
        self.layers
            .partition_point(|l| l.from <= value)
            .saturating_sub(1)
    }

    /// The layer of `value`: the last whose `from` is at most the value (the first for a
    /// value below every `from`).
    pub(crate) fn of(&self, value: f32) -> &Layer {
        &self.layers[self.index_of(value)]
    }

    /// The layers, sorted by `from`.
    pub(crate) fn layers(&self) -> &[Layer] {
        &self.layers
    }

    /// Whether the layers give the surface materials of their own: any was asked for
    /// (the default table leaves the object's material).
    pub(crate) fn are_felt(&self) -> bool {
        *self != Layers::default()
    }

    /// The material of each triangle from its material value (see
    /// [`Chunks::triangle_values`](super::extract::Chunks::triangle_values)), as
    /// indices into the layers (a layer beyond the 65 535th is not felt: its triangles
    /// keep the object's material).
    pub(crate) fn indices_of(&self, values: &[f32]) -> Vec<u16> {
        values
            .iter()
            .map(|&v| u16::try_from(self.index_of(v)).unwrap_or(u16::MAX))
            .collect()
    }
}

impl Default for Layers {
    /// One material: [`Material::DEFAULT`], cut at [`Layer::DEFAULT_RATE`].
    fn default() -> Layers {
        Layers {
            layers: vec![Layer {
                name: "material".to_owned(),
                from: f32::MIN,
                material: Material::DEFAULT,
                rate: Layer::DEFAULT_RATE,
            }],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_value_takes_the_last_layer_starting_at_or_below_it() {
        let soft = Material::new(300.0).unwrap();
        let hard = Material::new(900.0).unwrap();
        let layers = Layers::new(vec![
            Layer::new("enamel", 2.0, hard, 0.002).unwrap(),
            Layer::new("dentin", 1.0, soft, 0.01).unwrap(),
        ]);
        assert_eq!(layers.of(0.5).name, "dentin");
        assert_eq!(layers.of(1.0).name, "dentin");
        assert_eq!(layers.of(1.9).name, "dentin");
        assert_eq!(layers.of(2.0).name, "enamel");
        assert_eq!(layers.of(f32::INFINITY).name, "enamel");
        assert!(Layer::new("x", 1.0, soft, 0.0).is_err());
        assert!(Layer::new("x", f32::NAN, soft, 0.01).is_err());
        assert_eq!(Layers::new(Vec::new()), Layers::default());
    }
}
