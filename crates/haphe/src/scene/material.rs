//! What a surface feels like: stiffness, damping and friction.

use super::InvalidValue;

/// The haptic material of an object.
///
/// Friction follows Coulomb's law on the proxy: it sticks while the tangential force stays
/// within `static_friction` times the normal force, and once it slips it is held back by
/// `dynamic_friction` times the normal force, until it sticks again.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    /// Spring constant between proxy and device, N/m.
    pub stiffness: f64,
    /// Damping along the contact normal, N·s/m.
    pub damping: f64,
    /// Static friction coefficient (dimensionless, ≥ 0).
    pub static_friction: f64,
    /// Dynamic friction coefficient (dimensionless, 0 ≤ dynamic ≤ static).
    pub dynamic_friction: f64,
}

impl Default for Material {
    /// 500 N/m, no damping, no friction: safe on every common desktop device.
    fn default() -> Material {
        Material {
            stiffness: 500.0,
            damping: 0.0,
            static_friction: 0.0,
            dynamic_friction: 0.0,
        }
    }
}

impl Material {
    /// Checks every field: finite and non-negative, the dynamic friction coefficient at
    /// most the static one. Scene files, command-line flags and code use this one check.
    ///
    /// # Errors
    /// An [`InvalidValue`] naming the first field that is not usable.
    pub fn checked(self) -> Result<Material, InvalidValue> {
        for (field, v) in [
            ("stiffness", self.stiffness),
            ("damping", self.damping),
            ("static_friction", self.static_friction),
            ("dynamic_friction", self.dynamic_friction),
        ] {
            InvalidValue::check_range(field, v, 0.0, f64::MAX)?;
        }
        if self.dynamic_friction > self.static_friction {
            return Err(InvalidValue {
                field: "dynamic_friction",
                value: self.dynamic_friction,
                expected: format!("at most static_friction ({})", self.static_friction),
            });
        }
        Ok(self)
    }

    /// The material with every field made usable: non-finite or negative values become 0,
    /// and the dynamic coefficient is capped by the static one.
    pub fn sanitised(self) -> Material {
        let clean = |x: f64| if x.is_finite() && x > 0.0 { x } else { 0.0 };
        let static_friction = clean(self.static_friction);
        Material {
            stiffness: clean(self.stiffness),
            damping: clean(self.damping),
            static_friction,
            dynamic_friction: clean(self.dynamic_friction).min(static_friction),
        }
    }
}
