//! One check for every number a user gives the library — materials, the proxy's options,
//! poses, servo rates, device mappings, motions — the table of domains (`Param`), whichever
//! front end the number comes from.

use haphe::DVec3;
use haphe::glam::DQuat;
use haphe::proxy::ProxyOptions;
use haphe::scene::{DomainKind, Effect, Material, Param, ParamError, Pose, Texture, Zone};
use haphe::servo::{
    DeviceMapping, MAX_MOTION_AMPLITUDE, Motion, RealtimeOptions, ServoOptions, simulated_spec,
};
use haphe::volume::{CutOptions, Layer, Volume, VolumeError};

/// What each parameter must accept besides a typical value, stated here from the
/// physics rather than read from the table: whether 0 and a negative value (−1) are
/// usable, and a value far beyond any device (`None`: no value is absurd).
struct Expected {
    param: Param,
    typical: f64,
    zero: bool,
    negative: bool,
    absurd: Option<f64>,
}

const EXPECTED: [Expected; 31] = [
    // A material with no stiffness renders nothing; damping and friction may be absent.
    expect(Param::Stiffness, 800.0, false, false, Some(1e7)),
    expect(Param::Damping, 1.0, true, false, Some(1e5)),
    expect(Param::StaticFriction, 0.5, true, false, Some(100.0)),
    expect(Param::DynamicFriction, 0.3, true, false, Some(100.0)),
    // A proxy that renders no force, keeps no skin or has no workspace is a mistake.
    expect(Param::MaxForce, 3.3, false, false, Some(1e4)),
    expect(Param::Skin, 1e-6, false, false, Some(1.0)),
    expect(Param::WorkspaceRadius, 1.0, false, false, Some(1e12)),
    // A tool of no size is the point; a tool of metres is a unit mixed up.
    expect(Param::ToolRadius, 1e-3, true, false, Some(10.0)),
    // A position is a point: any sign, the origin included; not beyond 10⁹ m.
    expect(Param::Position, 0.2, true, true, Some(1e12)),
    // A quaternion of any non-zero length is a rotation (normalised).
    expect(Param::Rotation, 1.0, false, true, None),
    expect(Param::RateHz, 1000.0, false, false, Some(1e6)),
    expect(Param::RampSeconds, 0.05, true, false, Some(1e4)),
    expect(Param::SpinSeconds, 2e-4, true, false, Some(100.0)),
    expect(Param::Scale, 2.0, false, false, Some(1e9)),
    expect(Param::Centre, 0.1, true, true, Some(1e12)),
    expect(Param::MotionVelocity, 0.1, true, true, Some(1e4)),
    expect(Param::MotionAmplitude, 0.01, true, true, Some(1e4)),
    expect(Param::MotionFrequency, 2.0, true, false, Some(1e5)),
    expect(Param::MotionAxis, 1.0, false, true, None),
    // Turning either way, or not at all.
    expect(Param::MotionRate, 1.0, true, true, Some(1e5)),
    // A texture of no height is none; a wavelength of nothing is no texture.
    expect(Param::TextureAmplitude, 1e-4, true, false, Some(1.0)),
    expect(Param::TextureWavelength, 2e-3, false, false, Some(100.0)),
    expect(Param::VibrationFrequency, 150.0, false, false, Some(1e6)),
    // An effect may be switched off by a zero force, stiffness or viscosity.
    expect(Param::EffectForce, 0.3, true, true, Some(1e4)),
    expect(Param::Viscosity, 2.0, true, false, Some(1e5)),
    expect(Param::EffectStiffness, 100.0, true, false, Some(1e7)),
    expect(Param::MagnetDistance, 0.01, false, false, Some(100.0)),
    // A cut force of 0 cuts on any contact; a rate of 0 would never cut.
    expect(Param::CutForce, 0.5, true, false, Some(1e4)),
    expect(Param::CutRate, 0.01, false, false, Some(1e3)),
    expect(Param::VoxelSize, 5e-4, false, false, Some(100.0)),
    // A layer starts at any value of a scan: labels, Hounsfield units.
    expect(Param::LayerValue, 1200.0, true, true, None),
];

const fn expect(
    param: Param,
    typical: f64,
    zero: bool,
    negative: bool,
    absurd: Option<f64>,
) -> Expected {
    Expected {
        param,
        typical,
        zero,
        negative,
        absurd,
    }
}

/// A small cube voxelised at `voxel` metres: the voxel size's refusal.
fn voxelised(voxel: f64) -> Result<(), ParamError> {
    let cube = haphe::mesh::shapes::cuboid(DVec3::splat(0.01), [1; 3]);
    let shape = haphe::scene::Shape::from_mesh("cube", cube, &Default::default()).expect("a cube");
    match Volume::from_shape(&shape, voxel) {
        Err(VolumeError::VoxelSize(e)) => Err(e),
        // A voxel above the cube's size still makes a grid (of a few voxels).
        Ok(_) | Err(VolumeError::VoxelCount { .. }) => Ok(()),
        Err(other) => panic!("voxel {voxel}: {other}"),
    }
}

/// Gives `v` to the public constructor that takes `param`, every other value typical.
fn build(param: Param, v: f64) -> Result<(), ParamError> {
    let x = DVec3::new(v, 0.0, 0.0);
    let material = Material::builder();
    let proxy = ProxyOptions::default();
    match param {
        Param::Stiffness => material.stiffness(v).build().map(drop),
        Param::Damping => material.damping(v).build().map(drop),
        Param::StaticFriction => material.friction(v, 0.0).build().map(drop),
        Param::DynamicFriction => material.friction(10.0, v).build().map(drop),
        Param::MaxForce => proxy.with_max_force(v).map(drop),
        Param::Skin => proxy.with_skin(v).map(drop),
        Param::WorkspaceRadius => proxy.with_workspace_radius(v).map(drop),
        Param::ToolRadius => proxy.with_tool_radius(v).map(drop),
        Param::Position => {
            let a = Pose::from_translation(x);
            // As text: an error's NaN is not equal to itself.
            let b = Pose::new(DQuat::IDENTITY, x);
            assert_eq!(format!("{a:?}"), format!("{b:?}"), "{v}");
            a.map(drop)
        }
        Param::Rotation => Pose::new(DQuat::from_xyzw(v, 0.0, 0.0, 0.0), DVec3::ZERO).map(drop),
        Param::RateHz => ServoOptions::new(v).map(drop),
        Param::RampSeconds => ServoOptions::default().with_ramp_seconds(v).map(drop),
        Param::SpinSeconds => RealtimeOptions::default()
            .with_spin_seconds(Some(v))
            .map(drop),
        Param::Scale => DeviceMapping::new(DQuat::IDENTITY, v, DVec3::ZERO)
            .and(DeviceMapping::centred(&simulated_spec(), v, DVec3::ZERO))
            .map(drop),
        Param::Centre => DeviceMapping::centred(&simulated_spec(), 1.0, x)
            .and(DeviceMapping::new(DQuat::IDENTITY, 1.0, x))
            .map(drop),
        Param::MotionVelocity => Motion::Linear { velocity: x }.checked().map(drop),
        Param::MotionAmplitude => Motion::Oscillating {
            amplitude: x,
            frequency: 1.0,
        }
        .checked()
        .map(drop),
        Param::MotionFrequency => Motion::Oscillating {
            amplitude: DVec3::X * 0.01,
            frequency: v,
        }
        .checked()
        .map(drop),
        Param::MotionAxis => Motion::Rotating { axis: x, rate: 1.0 }.checked().map(drop),
        Param::MotionRate => Motion::Rotating {
            axis: DVec3::Z,
            rate: v,
        }
        .checked()
        .map(drop),
        Param::TextureAmplitude => Texture::sine(v, 1.0).map(drop),
        Param::TextureWavelength => Texture::noise(0.0, v).map(drop),
        Param::VibrationFrequency => Effect::vibration(v, 0.3).map(drop),
        // A vector: the constant force's component.
        Param::EffectForce => Effect::constant(x).map(drop),
        Param::Viscosity => Effect::viscosity(v, Zone::Everywhere).map(drop),
        Param::EffectStiffness => Effect::spring(v, DVec3::ZERO).map(drop),
        Param::MagnetDistance => Effect::magnet(v, 1.0).map(drop),
        Param::CutForce => CutOptions::new(1e-3, v).map(drop),
        Param::CutRate => Layer::new("dentin", 1.0, Material::DEFAULT, v).map(drop),
        Param::VoxelSize => voxelised(v),
        Param::LayerValue => Layer::new("dentin", v as f32, Material::DEFAULT, 0.01).map(drop),
        other => panic!("no constructor in this test for {other}"),
    }
}

/// Acceptance: NaN, ±∞, a negative value, zero and an absurd value through every
/// parameter's constructor: refused with an error naming the parameter, the value and the
/// domain, or accepted where the domain allows it.
#[test]
fn every_parameter_refuses_what_its_domain_does_not_allow() {
    assert_eq!(
        EXPECTED.iter().map(|e| e.param).collect::<Vec<_>>(),
        Param::ALL,
        "every parameter has its expectations here"
    );
    for e in &EXPECTED {
        let p = e.param;
        let mut cases = vec![
            (e.typical, true),
            (f64::NAN, false),
            (f64::INFINITY, false),
            (f64::NEG_INFINITY, false),
            (-1.0, e.negative),
            (0.0, e.zero),
        ];
        if let Some(absurd) = e.absurd {
            cases.push((absurd, false));
            cases.push((-absurd, false));
        }
        for (v, accepted) in cases {
            match build(p, v) {
                Ok(()) => assert!(accepted, "{p} = {v} was accepted"),
                Err(err) => {
                    assert!(!accepted, "{p} = {v} was refused: {err}");
                    assert_eq!(err.param(), p, "{p} = {v}: {err}");
                    let message = err.to_string();
                    assert!(message.starts_with(&format!("{p} must be")), "{message}");
                    // The value given (a vector's length, or its component given).
                    let value = err.value();
                    assert!(
                        value.total_cmp(&v).is_eq() || value.total_cmp(&v.abs()).is_eq(),
                        "{p} = {v}: {err}"
                    );
                }
            }
            // The table agrees (for a vector, about its length).
            let probe = match p.domain().kind {
                DomainKind::Number => v,
                DomainKind::Vector => v.abs(),
            };
            assert_eq!(p.domain().contains(probe), accepted, "the table, {p} = {v}");
        }
    }
}

#[test]
fn a_refusal_names_the_domain_with_its_unit() {
    let e = ProxyOptions::default().with_max_force(-1.0).unwrap_err();
    assert_eq!(
        e.to_string(),
        "max_force must be a finite number above 0 and at most 100 N, not -1"
    );
    assert_eq!(
        e.named("--max-force").to_string(),
        "--max-force must be a finite number above 0 and at most 100 N, not -1"
    );
    let e = Material::new(1e7).unwrap_err();
    assert_eq!(
        e.to_string(),
        "stiffness must be a finite number above 0 and at most 1000000 N/m, not 1e7"
    );
}

#[test]
fn the_dynamic_friction_is_at_most_the_static() {
    let good = Material::builder()
        .stiffness(600.0)
        .damping(1.0)
        .friction(0.3, 0.2)
        .build()
        .expect("a valid material");
    assert_eq!(good.to_builder().build(), Ok(good));
    assert_eq!(
        (
            good.stiffness(),
            good.damping(),
            good.static_friction(),
            good.dynamic_friction()
        ),
        (600.0, 1.0, 0.3, 0.2)
    );
    let err = good.to_builder().friction(0.3, 0.5).build().unwrap_err();
    assert_eq!(err.param(), Param::DynamicFriction);
    assert_eq!(
        err.to_string(),
        "dynamic_friction must be at most static_friction (0.3), not 0.5"
    );
    // The first value refused is named, in the order stiffness, damping, friction.
    let err = Material::builder()
        .stiffness(-1.0)
        .damping(f64::NAN)
        .build()
        .unwrap_err();
    assert_eq!(err.param(), Param::Stiffness);
}

#[test]
fn motions_are_checked() {
    assert!(Motion::Linear { velocity: DVec3::X }.checked().is_ok());
    let bad = [
        Motion::Linear {
            velocity: DVec3::new(f64::NAN, 0.0, 0.0),
        },
        Motion::Linear {
            velocity: DVec3::X * 1e6,
        },
        Motion::Oscillating {
            amplitude: DVec3::X * 1e308,
            frequency: 1.0,
        },
        Motion::Oscillating {
            amplitude: DVec3::X * (MAX_MOTION_AMPLITUDE * 1.5),
            frequency: 1.0,
        },
        Motion::Oscillating {
            amplitude: DVec3::X,
            frequency: f64::INFINITY,
        },
        Motion::Oscillating {
            amplitude: DVec3::X,
            frequency: -1.0,
        },
        Motion::Rotating {
            axis: DVec3::ZERO,
            rate: 1.0,
        },
        Motion::Rotating {
            axis: DVec3::Z,
            rate: f64::NAN,
        },
    ];
    for motion in bad {
        assert!(motion.checked().is_err(), "{motion:?}");
    }
}
