//! Proptest strategies over the generators: every generator, small resolutions (including
//! ones that get clamped) and sizes from 1 mm to 10 m.

use haphe::DVec3;
use haphe::mesh::Mesh;
use haphe::mesh::shapes::{
    concave_corner, cuboid, geodesic_blob, geodesic_sphere, sphere, thin_plate, torus,
};
use proptest::prelude::*;

/// A generator call with small resolutions and sizes from 1 mm to 10 m.
#[derive(Debug, Clone)]
pub enum Generator {
    Sphere {
        radius: f64,
        subdivisions: u32,
    },
    GeodesicSphere {
        radius: f64,
        frequency: u32,
    },
    Torus {
        major: f64,
        minor_fraction: f64,
        ring: u32,
        tube: u32,
    },
    Cuboid {
        half_extents: [f64; 3],
        divisions: [u32; 3],
    },
    ThinPlate {
        width: f64,
        depth: f64,
        thickness: f64,
        divisions: u32,
    },
    ConcaveCorner {
        size: f64,
        divisions: u32,
    },
    Blob {
        radius: f64,
        frequency: u32,
        amplitude_fraction: f64,
        seed: u64,
    },
}

impl Generator {
    pub fn build(&self) -> Mesh {
        match *self {
            Generator::Sphere {
                radius,
                subdivisions,
            } => sphere(radius, subdivisions),
            Generator::GeodesicSphere { radius, frequency } => geodesic_sphere(radius, frequency),
            Generator::Torus {
                major,
                minor_fraction,
                ring,
                tube,
            } => torus(major, major * minor_fraction, ring, tube),
            Generator::Cuboid {
                half_extents,
                divisions,
            } => cuboid(DVec3::from_array(half_extents), divisions),
            Generator::ThinPlate {
                width,
                depth,
                thickness,
                divisions,
            } => thin_plate(width, depth, thickness, divisions),
            Generator::ConcaveCorner { size, divisions } => concave_corner(size, divisions),
            Generator::Blob {
                radius,
                frequency,
                amplitude_fraction,
                seed,
            } => geodesic_blob(radius, frequency, radius * amplitude_fraction, seed),
        }
    }

    pub fn euler_characteristic(&self) -> i64 {
        if matches!(self, Generator::Torus { .. }) {
            0
        } else {
            2
        }
    }
}

fn length_m() -> impl Strategy<Value = f64> {
    (-3.0f64..1.0).prop_map(|exponent| 10f64.powf(exponent))
}

pub fn generator() -> impl Strategy<Value = Generator> {
    prop_oneof![
        (length_m(), 0..4u32).prop_map(|(radius, subdivisions)| Generator::Sphere {
            radius,
            subdivisions
        }),
        (length_m(), 0..20u32)
            .prop_map(|(radius, frequency)| Generator::GeodesicSphere { radius, frequency }),
        (length_m(), 0.01..0.99f64, 0..40u32, 0..40u32).prop_map(
            |(major, minor_fraction, ring, tube)| Generator::Torus {
                major,
                minor_fraction,
                ring,
                tube
            }
        ),
        (
            [length_m(), length_m(), length_m()],
            [0..12u32, 0..12u32, 0..12u32]
        )
            .prop_map(|(half_extents, divisions)| Generator::Cuboid {
                half_extents,
                divisions
            }),
        (length_m(), length_m(), 1e-5..1e-3f64, 0..30u32).prop_map(
            |(width, depth, thickness, divisions)| Generator::ThinPlate {
                width,
                depth,
                thickness,
                divisions
            }
        ),
        (length_m(), 0..10u32)
            .prop_map(|(size, divisions)| Generator::ConcaveCorner { size, divisions }),
        (length_m(), 0..20u32, 0.0..1.5f64, any::<u64>()).prop_map(
            |(radius, frequency, amplitude_fraction, seed)| Generator::Blob {
                radius,
                frequency,
                amplitude_fraction,
                seed
            }
        ),
    ]
}
