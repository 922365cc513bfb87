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

/// The largest force a device renders unless told otherwise, newtons: that of a common
/// desktop device (a 3D Systems Touch renders 3.3 N). The default of the proxy
/// ([`ProxyOptions`](crate::proxy::ProxyOptions)), the simulated devices, the network
/// device, the command's `--max-force` and the Python and C bindings.
pub const DEFAULT_MAX_FORCE_N: f64 = 3.3;

impl Default for Material {
    /// [`Material::DEFAULT`].
    fn default() -> Material {
        Material::DEFAULT
    }
}

impl Material {
    /// The material of an object unless told otherwise, whatever the entry point (the
    /// library, scene files, the command's `--mesh` and `--shape` objects, Python, C):
    /// 500 N/m, no damping, no friction.
    ///
    /// 500 N/m is safe on every common desktop device (a Touch renders about 1000 N/m
    /// stably) and puts the saturation depth at 6.6 mm with [`DEFAULT_MAX_FORCE_N`]. Damping
    /// and friction change what the hand feels and how the proxy moves (the reference
    /// god-object has neither), so they are asked for, never implied.
    pub const DEFAULT: Material = Material {
        stiffness: 500.0,
        damping: 0.0,
        static_friction: 0.0,
        dynamic_friction: 0.0,
    };

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
