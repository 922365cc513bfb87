//! What a surface feels like: stiffness, damping and friction.

use super::invalid::ParamError;
use super::param::Param;

/// The haptic material of an object, every value within its domain (see [`Param`]).
///
/// Friction follows Coulomb's law on the proxy: it sticks while the tangential force stays
/// within `static_friction` times the normal force, and once it slips it is held back by
/// `dynamic_friction` times the normal force, until it sticks again.
///
/// Built by [`Material::new`] or [`Material::builder`], which check every value, so a
/// material holds no value outside its domain. Its fields are private: a struct literal
/// does not build.
///
/// ```compile_fail
/// let m = haphe::scene::Material { stiffness: f64::NAN, damping: 0.0, static_friction: 0.0, dynamic_friction: 0.0 };
/// ```
///
/// ```
/// # fn main() -> Result<(), haphe::scene::ParamError> {
/// use haphe::scene::Material;
/// let m = Material::builder().stiffness(800.0).damping(1.0).friction(0.5, 0.3).build()?;
/// assert_eq!(m.dynamic_friction(), 0.3);
/// assert!(Material::new(f64::NAN).is_err());
/// # Ok(())
/// # }
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    /// Spring constant between proxy and device, N/m.
    pub(crate) stiffness: f64,
    /// Damping along the contact normal, N·s/m.
    pub(crate) damping: f64,
    /// Static friction coefficient (dimensionless, ≥ 0).
    pub(crate) static_friction: f64,
    /// Dynamic friction coefficient (dimensionless, 0 ≤ dynamic ≤ static).
    pub(crate) dynamic_friction: f64,
}

impl Default for Material {
    /// [`Material::DEFAULT`].
    fn default() -> Material {
        Material::DEFAULT
    }
}

impl Material {
    /// The material of an object unless told otherwise, whatever the entry point (the
    /// library, scene files, the command's `--mesh` and `--shape` objects, Python, C):
    /// 500 N/m, no damping, no friction. Inside every domain of [`Param`] (a unit test
    /// builds it with [`Material::builder`]).
    ///
    /// 500 N/m is safe on every common desktop device (a Touch renders about 1000 N/m
    /// stably) and puts the saturation depth at 6.6 mm with
    /// [`DEFAULT_MAX_FORCE_N`](super::DEFAULT_MAX_FORCE_N). Damping and friction change
    /// what the hand feels and how the proxy moves (the reference god-object has neither),
    /// so they are asked for, never implied.
    pub const DEFAULT: Material = Material {
        stiffness: 500.0,
        damping: 0.0,
        static_friction: 0.0,
        dynamic_friction: 0.0,
    };

    /// A material of `stiffness` N/m, no damping, no friction.
    ///
    /// # Errors
    /// [`ParamError`] naming `stiffness` outside its domain (above 0, at most 10⁶ N/m).
    pub fn new(stiffness: f64) -> Result<Material, ParamError> {
        Material::builder().stiffness(stiffness).build()
    }

    /// A builder starting from the default material ([`Material::default`]).
    pub fn builder() -> MaterialBuilder {
        Material::default().to_builder()
    }

    /// A builder starting from this material.
    pub fn to_builder(self) -> MaterialBuilder {
        MaterialBuilder { values: self }
    }

    /// Spring constant between proxy and device, N/m.
    pub const fn stiffness(&self) -> f64 {
        self.stiffness
    }

    /// Damping along the contact normal, N·s/m.
    pub const fn damping(&self) -> f64 {
        self.damping
    }

    /// Static friction coefficient.
    pub const fn static_friction(&self) -> f64 {
        self.static_friction
    }

    /// Dynamic friction coefficient (at most the static one).
    pub const fn dynamic_friction(&self) -> f64 {
        self.dynamic_friction
    }
}

/// The values of a [`Material`] to be, checked together by [`MaterialBuilder::build`].
#[derive(Debug, Clone, Copy, PartialEq)]
#[must_use = "a builder does nothing until `build` checks it"]
pub struct MaterialBuilder {
    /// Not checked yet.
    values: Material,
}

impl MaterialBuilder {
    /// The spring constant, N/m.
    pub fn stiffness(mut self, stiffness: f64) -> MaterialBuilder {
        self.values.stiffness = stiffness;
        self
    }

    /// The damping along the contact normal, N·s/m.
    pub fn damping(mut self, damping: f64) -> MaterialBuilder {
        self.values.damping = damping;
        self
    }

    /// The static and dynamic friction coefficients.
    pub fn friction(mut self, static_friction: f64, dynamic_friction: f64) -> MaterialBuilder {
        self.values.static_friction = static_friction;
        self.values.dynamic_friction = dynamic_friction;
        self
    }

    /// The material, every value checked against its domain ([`Param`]) in the order
    /// stiffness, damping, static friction, dynamic friction.
    ///
    /// # Errors
    /// [`ParamError`] naming the first value outside its domain, or
    /// [`ParamError::FrictionOrder`] when the dynamic coefficient exceeds the static one
    /// (the proxy sticks inside the static cone and slips back to the dynamic one, which
    /// must be the narrower).
    pub fn build(self) -> Result<Material, ParamError> {
        let v = self.values;
        Param::Stiffness.check(v.stiffness)?;
        Param::Damping.check(v.damping)?;
        Param::StaticFriction.check(v.static_friction)?;
        Param::DynamicFriction.check(v.dynamic_friction)?;
        if v.dynamic_friction > v.static_friction {
            return Err(ParamError::FrictionOrder {
                static_friction: v.static_friction,
                dynamic_friction: v.dynamic_friction,
            });
        }
        Ok(v)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_is_inside_every_domain() {
        let d = Material::DEFAULT;
        let built = Material::builder()
            .stiffness(d.stiffness)
            .damping(d.damping)
            .friction(d.static_friction, d.dynamic_friction)
            .build();
        assert_eq!(built, Ok(d));
        assert_eq!(Material::new(d.stiffness), Ok(d));
    }
}
