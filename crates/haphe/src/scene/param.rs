//! The numbers a user gives the library, by name.

use std::fmt;

/// A number a user gives the library. Its [`Display`](fmt::Display) is the name the
/// front ends spell it with (`stiffness`, `max_force`, `motion frequency`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Param {
    /// A material's spring constant between proxy and device, N/m.
    Stiffness,
    /// A material's damping along the contact normal, N·s/m.
    Damping,
    /// A material's static friction coefficient.
    StaticFriction,
    /// A material's dynamic friction coefficient (at most the static one).
    DynamicFriction,
    /// The largest force the proxy renders, N.
    MaxForce,
    /// The distance the proxy keeps from a touched surface, m.
    Skin,
    /// The radius beyond which device points are pulled back, m.
    WorkspaceRadius,
    /// The radius of the tool, a sphere centred on the proxy, m (0: a point).
    ToolRadius,
    /// A pose's translation (an object's position), m.
    Position,
    /// A pose's or a mapping's rotation, as a quaternion (normalised when used).
    Rotation,
    /// The servo rate, Hz.
    RateHz,
    /// The safe start's force ramp, s.
    RampSeconds,
    /// The spin before each deadline of a real-time loop, s.
    SpinSeconds,
    /// A device mapping's scale, world metres per device metre.
    Scale,
    /// Where a device mapping puts the device's origin or its workspace's centre, m.
    Centre,
    /// A linear motion's velocity, m/s.
    MotionVelocity,
    /// An oscillating motion's amplitude, m.
    MotionAmplitude,
    /// An oscillating motion's frequency, Hz.
    MotionFrequency,
    /// A rotating motion's axis.
    MotionAxis,
    /// A rotating motion's angular speed, rad/s (either sign).
    MotionRate,
    /// A texture's height amplitude, m.
    TextureAmplitude,
    /// A texture's wavelength, m.
    TextureWavelength,
    /// A vibration effect's frequency, Hz.
    VibrationFrequency,
    /// An effect's force (a vibration's amplitude, a magnet's pull, a constant force, a
    /// stick-slip's breakaway force), N.
    EffectForce,
    /// A viscosity effect's drag coefficient, N·s/m.
    Viscosity,
    /// A spring or stick-slip effect's stiffness, N/m.
    EffectStiffness,
    /// How far a magnet effect reaches from the surface, m.
    MagnetDistance,
    /// The contact force from which a cutting tool removes material, N.
    CutForce,
    /// How fast a volume's material is removed under the cut force: the depth the tool
    /// sinks in a second, m/s.
    CutRate,
    /// The spacing of a grid a mesh is voxelised on, m.
    VoxelSize,
    /// The lowest value of a volume's material layer (a label, a Hounsfield unit).
    LayerValue,
}

impl Param {
    /// Every parameter, in table order.
    pub const ALL: [Param; 31] = [
        Param::Stiffness,
        Param::Damping,
        Param::StaticFriction,
        Param::DynamicFriction,
        Param::MaxForce,
        Param::Skin,
        Param::WorkspaceRadius,
        Param::ToolRadius,
        Param::Position,
        Param::Rotation,
        Param::RateHz,
        Param::RampSeconds,
        Param::SpinSeconds,
        Param::Scale,
        Param::Centre,
        Param::MotionVelocity,
        Param::MotionAmplitude,
        Param::MotionFrequency,
        Param::MotionAxis,
        Param::MotionRate,
        Param::TextureAmplitude,
        Param::TextureWavelength,
        Param::VibrationFrequency,
        Param::EffectForce,
        Param::Viscosity,
        Param::EffectStiffness,
        Param::MagnetDistance,
        Param::CutForce,
        Param::CutRate,
        Param::VoxelSize,
        Param::LayerValue,
    ];

    /// The name the front ends spell it with.
    pub const fn name(self) -> &'static str {
        match self {
            Param::Stiffness => "stiffness",
            Param::Damping => "damping",
            Param::StaticFriction => "static_friction",
            Param::DynamicFriction => "dynamic_friction",
            Param::MaxForce => "max_force",
            Param::Skin => "skin",
            Param::WorkspaceRadius => "workspace_radius",
            Param::ToolRadius => "tool_radius",
            Param::Position => "position",
            Param::Rotation => "rotation",
            Param::RateHz => "rate_hz",
            Param::RampSeconds => "ramp_seconds",
            Param::SpinSeconds => "spin_seconds",
            Param::Scale => "scale",
            Param::Centre => "centre",
            Param::MotionVelocity => "motion velocity",
            Param::MotionAmplitude => "motion amplitude",
            Param::MotionFrequency => "motion frequency",
            Param::MotionAxis => "motion axis",
            Param::MotionRate => "motion rate",
            Param::TextureAmplitude => "texture amplitude",
            Param::TextureWavelength => "texture wavelength",
            Param::VibrationFrequency => "vibration frequency",
            Param::EffectForce => "effect force",
            Param::Viscosity => "viscosity",
            Param::EffectStiffness => "effect stiffness",
            Param::MagnetDistance => "magnet distance",
            Param::CutForce => "cut_force",
            Param::CutRate => "cut rate",
            Param::VoxelSize => "voxel size",
            Param::LayerValue => "layer value",
        }
    }
}

impl fmt::Display for Param {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}
