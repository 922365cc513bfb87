//! One check for materials, motions and the maximum force, whichever front end they come
//! from.

use haphe::DVec3;
use haphe::scene::{Material, check_max_force};
use haphe::servo::{MAX_MOTION_AMPLITUDE, Motion};

#[test]
fn materials_are_checked() {
    let good = Material {
        stiffness: 600.0,
        damping: 1.0,
        static_friction: 0.3,
        dynamic_friction: 0.2,
    };
    assert_eq!(good.checked(), Ok(good));
    for (bad, field) in [
        (
            Material {
                stiffness: -1.0,
                ..good
            },
            "stiffness",
        ),
        (
            Material {
                damping: f64::NAN,
                ..good
            },
            "damping",
        ),
        (
            Material {
                stiffness: f64::INFINITY,
                ..good
            },
            "stiffness",
        ),
        (
            Material {
                static_friction: -0.1,
                ..good
            },
            "static_friction",
        ),
        (
            Material {
                dynamic_friction: 0.5,
                ..good
            },
            "dynamic_friction",
        ),
    ] {
        let err = bad.checked().unwrap_err();
        assert_eq!(err.field, field, "{bad:?}");
        assert!(
            err.to_string().starts_with(&format!("{field} must be")),
            "{err}"
        );
    }
    assert!(check_max_force(3.3).is_ok());
    assert!(check_max_force(-1.0).is_err());
    assert!(check_max_force(f64::NAN).is_err());
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
