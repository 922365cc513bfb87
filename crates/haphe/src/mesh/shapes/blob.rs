//! Blobs: geodesic spheres whose vertices are moved along their rays by smooth,
//! deterministic noise, so the surface is lumpy but stays star-shaped.
//!
//! The noise is a weighted sum of a few plane waves `sin(ν·(d·ω) + φ)` restricted to the
//! unit sphere, with directions `d`, spatial frequencies `ν` and phases `φ` drawn from a
//! `splitmix64` generator seeded by the caller: smooth (analytic), cheap, and the same for
//! the same seed.
//!
//! Why it cannot self-intersect: every vertex keeps its direction `ω` from the centre and
//! only its distance changes, to `radius + amplitude·noise(ω) > 0`. A triangle with corners
//! `rₐωₐ, r_b ω_b, r_c ω_c` then lies inside the cone spanned by `ωₐ, ω_b, ω_c`, and those
//! cones tile space without overlapping (they are the cones over the faces of the
//! undisplaced sphere). So each ray from the centre crosses the surface once.

use crate::rng::SplitMix64;
use std::f64::consts::TAU;

use crate::par::*;
use glam::DVec3;

use super::length::is_positive_length;
use super::sphere::{MAX_SPHERE_SUBDIVISIONS, unit_geodesic_sphere};
use crate::mesh::Mesh;

/// Largest noise amplitude, as a fraction of the radius, that [`blob`] and
/// [`geodesic_blob`] accept; larger amplitudes are clamped. Below 1, so every vertex stays
/// at least `0.1·radius` from the centre and the blob stays star-shaped.
pub const MAX_BLOB_AMPLITUDE_FRACTION: f64 = 0.9;

/// Plane waves summed into the noise.
const NOISE_WAVES: usize = 6;

/// Range of the waves' spatial frequency, radians per unit of `d·ω`: one to a few lumps
/// across the sphere.
const WAVE_FREQUENCY_MIN: f64 = 1.5;
const WAVE_FREQUENCY_MAX: f64 = 4.5;

/// A lumpy sphere centred on the origin (object frame): a [`sphere`](super::sphere) of
/// `radius` metres with `subdivisions` (`20·4^subdivisions` triangles) whose vertices are
/// moved along their rays by at most `noise_amplitude` metres, with smooth noise fixed by
/// `seed`. This is [`geodesic_blob`] with frequency `2^subdivisions`.
///
/// The same arguments give the same mesh, bit for bit; another seed gives other lumps.
///
/// `subdivisions` is clamped to at most [`MAX_SPHERE_SUBDIVISIONS`]; `noise_amplitude` is
/// clamped into `[0, `[`MAX_BLOB_AMPLITUDE_FRACTION`]`·radius]`. A `radius` that is not
/// finite and positive, or a `noise_amplitude` that is not finite, gives an empty mesh.
///
/// # Performance
/// The noise is evaluated in parallel on the rayon thread pool (feature `parallel`); each vertex depends only on
/// its own direction, so the result does not depend on the scheduling.
///
/// # Examples
/// ```
/// use haphe::mesh::shapes::blob;
/// let lumpy = blob(0.1, 3, 0.02, 7);
/// assert_eq!(lumpy.triangles.len(), 1280);
/// assert!(lumpy.vertices.iter().all(|p| (p.length() - 0.1).abs() <= 0.02));
/// assert_eq!(lumpy, blob(0.1, 3, 0.02, 7));
/// assert_ne!(lumpy, blob(0.1, 3, 0.02, 8));
/// ```
pub fn blob(radius: f64, subdivisions: u32, noise_amplitude: f64, seed: u64) -> Mesh {
    geodesic_blob(
        radius,
        1 << subdivisions.min(MAX_SPHERE_SUBDIVISIONS),
        noise_amplitude,
        seed,
    )
}

/// A lumpy sphere centred on the origin (object frame): a
/// [`geodesic_sphere`](super::geodesic_sphere) of `radius` metres and `frequency`
/// (`20·frequency²` triangles) whose vertices are moved along their rays by at most
/// `noise_amplitude` metres, with smooth noise fixed by `seed`.
///
/// Arguments are handled as in [`blob`]; `frequency` is clamped into
/// `1..=`[`MAX_SPHERE_FREQUENCY`](super::MAX_SPHERE_FREQUENCY).
///
/// # Examples
/// ```
/// use haphe::mesh::shapes::geodesic_blob;
/// let lumpy = geodesic_blob(0.1, 10, 0.5, 1);
/// assert_eq!(lumpy.triangles.len(), 2000);
/// // The amplitude is clamped to 0.9 · radius.
/// assert!(lumpy.vertices.iter().all(|p| p.length() >= 0.1 - 0.09 - 1e-12));
/// ```
pub fn geodesic_blob(radius: f64, frequency: u32, noise_amplitude: f64, seed: u64) -> Mesh {
    if !is_positive_length(radius) || !noise_amplitude.is_finite() {
        return Mesh::default();
    }
    let amplitude = noise_amplitude.clamp(0.0, MAX_BLOB_AMPLITUDE_FRACTION * radius);
    if !(radius + amplitude).is_finite() {
        return Mesh::default();
    }
    let noise = RadialNoise::new(seed);
    let mut mesh = unit_geodesic_sphere(frequency);
    mesh.vertices
        .par_iter_mut()
        .for_each(|direction| *direction *= radius + amplitude * noise.at(*direction));
    mesh
}

/// Smooth noise on the unit sphere with values in `[−1, 1]`.
struct RadialNoise {
    waves: [PlaneWave; NOISE_WAVES],
    total_weight: f64,
}

/// One term `weight · sin(frequency · direction·ω + phase)`.
#[derive(Clone, Copy, Default)]
struct PlaneWave {
    direction: DVec3,
    frequency: f64,
    phase: f64,
    weight: f64,
}

impl RadialNoise {
    fn new(seed: u64) -> RadialNoise {
        let mut random = SplitMix64::new(seed);
        let mut waves = [PlaneWave::default(); NOISE_WAVES];
        for wave in &mut waves {
            // A uniform direction: uniform height and uniform angle around the z axis.
            let z = 2.0 * random.next_unit() - 1.0;
            let (sin_angle, cos_angle) = (TAU * random.next_unit()).sin_cos();
            let across = (1.0 - z * z).max(0.0).sqrt();
            let frequency =
                WAVE_FREQUENCY_MIN + (WAVE_FREQUENCY_MAX - WAVE_FREQUENCY_MIN) * random.next_unit();
            *wave = PlaneWave {
                direction: DVec3::new(across * cos_angle, across * sin_angle, z),
                frequency,
                phase: TAU * random.next_unit(),
                // Larger lumps weigh more, as in natural shapes.
                weight: 1.0 / frequency,
            };
        }
        let total_weight = waves.iter().map(|wave| wave.weight).sum();
        RadialNoise {
            waves,
            total_weight,
        }
    }

    /// The noise at the unit direction `direction`, in `[−1, 1]`.
    fn at(&self, direction: DVec3) -> f64 {
        let sum: f64 = self
            .waves
            .iter()
            .map(|wave| {
                wave.weight * (wave.frequency * wave.direction.dot(direction) + wave.phase).sin()
            })
            .sum();
        (sum / self.total_weight).clamp(-1.0, 1.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn noise_stays_within_unit_bounds_and_varies() {
        let noise = RadialNoise::new(42);
        let sphere = unit_geodesic_sphere(16);
        let values: Vec<f64> = sphere.vertices.iter().map(|&d| noise.at(d)).collect();
        assert!(values.iter().all(|v| (-1.0..=1.0).contains(v)));
        let spread = values.iter().copied().fold(f64::MIN, f64::max)
            - values.iter().copied().fold(f64::MAX, f64::min);
        assert!(spread > 0.5, "noise too flat: spread {spread}");
    }
}
