//! Haptic textures: a height field over an object's surface that displaces the proxy's
//! constraint along the contact normal.
//!
//! A texture is a height `h` (metres, `|h| ≤ A`, the amplitude) at each surface point, in
//! the object's frame: a solid procedural field (sine, band-limited noise), which needs no
//! texture coordinates, or a grey image read through the shape's texture coordinates. On
//! a face the force is that of the surface moved out by `h` along the contact normal:
//!
//! - with `d` the device point's depth behind the contact plane, the felt depth is
//!   `e = d + h·φ(d)`, where `φ(d) = min(1, d / A)` fades the texture in over the first
//!   `A` of depth (so that touching down never starts on a bump: `e ≥ 0` and `e = 0` at
//!   `d = 0`);
//! - the force is `−∇` of the potential `k e² / 2`: along the normal `k e (1 + h φ'(d))`,
//!   and across it `−k e φ ∇h` (the slope of the bumps pushes the hand downhill).
//!
//! Being the gradient of a potential of the device point (the proxy follows the device
//! point across a frictionless face), a texture gives back over a closed path exactly the
//! work it took: it never injects energy. Sliding at speed `v` over a wavelength `L` is
//! felt at `v / L` Hz.

use std::f64::consts::TAU;
use std::path::Path;
use std::str::FromStr;
use std::sync::Arc;

use glam::DVec3;

use super::invalid::ParamError;
use super::param::Param;
use super::spec::{Spec, SpecError, number};
use super::texture_coords::UvPoint;

mod image;
pub use image::HeightImage;

/// The kinds a texture specification names.
const KINDS: &str = "`sine:A:L`, `noise:A:L`, `image:PNG:A`";

/// A haptic texture, every value checked: a height `h` (`|h| ≤ A`) over the surface that
/// moves the constraint out along the contact normal. With `d` the device point's depth
/// behind the contact plane, the felt depth is `e = d + h·min(1, d / A)` (faded in over
/// the first `A` of depth, so that touching down never starts on a bump) and the force is
/// `−∇(k e² / 2)`: along the normal `k e (1 + h φ')`, and across it `−k e φ ∇h` (the
/// bumps' slope pushes the hand downhill). Being the gradient of a potential, it gives
/// back over a closed path no more work than it took. Sliding at `v` over a wavelength `L`
/// is felt at `v / L` Hz.
///
/// ```
/// use haphe::scene::Texture;
/// let t: Texture = "sine:0.0002:0.002".parse()?;
/// assert_eq!(t.amplitude(), 0.0002);
/// assert!("sine:-1:0.002".parse::<Texture>().is_err());
/// # Ok::<(), haphe::scene::SpecError>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Texture {
    kind: Kind,
    amplitude: f64,
}

#[derive(Debug, Clone, PartialEq)]
enum Kind {
    /// The mean of three sines along the object's axes, of wavelength `L`.
    Sine { wavelength: f64 },
    /// A sum of plane waves in fixed directions, wavelengths around `L`: their wave
    /// vectors (radians per metre) and phases, computed once.
    Noise {
        wavelength: f64,
        waves: Box<[(DVec3, f64); NOISE_WAVES]>,
    },
    /// A height image read through the shape's texture coordinates: height
    /// `A · (2 value − 1)`.
    Image { image: Arc<HeightImage> },
}

/// The height of a texture at a point and its gradient, object frame: what the force
/// rule needs (see the module). `amplitude` 0: no texture.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Relief {
    /// Height, metres (`|height| ≤ amplitude`).
    pub(crate) height: f64,
    /// Gradient of the height (dimensionless), world frame once placed, in the contact
    /// plane once projected.
    pub(crate) gradient: DVec3,
    /// The texture's amplitude, metres: the depth over which it fades in.
    pub(crate) amplitude: f64,
}

impl Relief {
    /// No texture.
    pub(crate) const FLAT: Relief = Relief {
        height: 0.0,
        gradient: DVec3::ZERO,
        amplitude: 0.0,
    };
}

/// The plane waves of the noise texture: unit directions spread over the sphere (a
/// golden-angle spiral), wavelengths from 0.75 to 1.33 times the texture's, phases.
const NOISE_WAVES: usize = 8;

fn noise_wave(j: usize) -> (DVec3, f64, f64) {
    let golden = TAU * (1.0 - 1.0 / 1.618_033_988_749_895);
    let z = 1.0 - (2.0 * j as f64 + 1.0) / NOISE_WAVES as f64;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let a = golden * j as f64;
    let direction = DVec3::new(r * a.cos(), r * a.sin(), z);
    let scale = 0.75 * (16.0_f64 / 9.0).powf(j as f64 / (NOISE_WAVES - 1) as f64);
    let phase = (j as f64 * 2.399_963_229_728_653).rem_euclid(TAU);
    (direction, scale, phase)
}

impl Texture {
    /// A solid sine texture: the height `A · (sin(2πx/L) + sin(2πy/L) + sin(2πz/L)) / 3`
    /// in the object's frame (so `|h| ≤ A`; on a face across an axis, sliding along
    /// another feels ridges of amplitude `A/3` every `L`).
    ///
    /// # Errors
    /// [`ParamError`] naming the texture amplitude (0 to 1 cm) or wavelength (above 0, at
    /// most 1 m), or [`ParamError::TooSteep`] when `A > L / 2π`.
    pub fn sine(amplitude: f64, wavelength: f64) -> Result<Texture, ParamError> {
        let amplitude = checked(amplitude, wavelength)?;
        Ok(Texture {
            kind: Kind::Sine { wavelength },
            amplitude,
        })
    }

    /// A band-limited noise texture: the mean of eight plane waves in fixed directions,
    /// wavelengths from 0.75 L to 1.33 L (so `|h| ≤ A`).
    ///
    /// # Errors
    /// As [`Texture::sine`].
    pub fn noise(amplitude: f64, wavelength: f64) -> Result<Texture, ParamError> {
        let amplitude = checked(amplitude, wavelength)?;
        let waves = Box::new(std::array::from_fn(|j| {
            let (direction, scale, phase) = noise_wave(j);
            (direction * (TAU / (wavelength * scale)), phase)
        }));
        Ok(Texture {
            kind: Kind::Noise { wavelength, waves },
            amplitude,
        })
    }

    /// A height image read through the shape's texture coordinates: the height is
    /// `A · (2 value − 1)` (black `−A`, white `A`), bilinear between pixel centres (see
    /// [`HeightImage`]), its slope through the triangle's map from the surface to the
    /// image. Felt only on shapes with texture coordinates (an OBJ's `vt`, a PLY's `u,v`,
    /// a glTF's `TEXCOORD_0`, or [`Shape::with_texture_coords`](super::Shape::with_texture_coords));
    /// elsewhere the surface is plain. Its steepness depends on the image's pixels over
    /// the mesh's size and is not checked: keep the bumps wider than they are high.
    ///
    /// # Errors
    /// [`ParamError`] naming the texture amplitude (0 to 1 cm).
    pub fn image(image: Arc<HeightImage>, amplitude: f64) -> Result<Texture, ParamError> {
        Ok(Texture {
            kind: Kind::Image { image },
            amplitude: Param::TextureAmplitude.check(amplitude)?,
        })
    }

    /// The amplitude, metres: the largest height.
    pub fn amplitude(&self) -> f64 {
        self.amplitude
    }

    /// The height at `p` (object frame) and its gradient (object frame); for an image,
    /// at the texture coordinates `uv` gives (flat where it gives none).
    ///
    /// # Real-time
    /// No allocation; a few sines, or four pixels.
    pub(crate) fn relief(&self, p: DVec3, uv: impl FnOnce() -> Option<UvPoint>) -> Relief {
        let a = self.amplitude;
        let (height, gradient) = match &self.kind {
            Kind::Sine { wavelength } => {
                let w = TAU / wavelength;
                let (sx, cx) = sin_cos(w * p.x);
                let (sy, cy) = sin_cos(w * p.y);
                let (sz, cz) = sin_cos(w * p.z);
                (
                    a * (sx + sy + sz) / 3.0,
                    DVec3::new(cx, cy, cz) * (a * w / 3.0),
                )
            }
            Kind::Noise { waves, .. } => {
                let mut h = 0.0;
                let mut g = DVec3::ZERO;
                for &(k, phase) in waves.iter() {
                    let (s, c) = sin_cos(k.dot(p) + phase);
                    h += s;
                    g += c * k;
                }
                let m = a / NOISE_WAVES as f64;
                (m * h, m * g)
            }
            Kind::Image { image } => {
                let Some(at) = uv() else {
                    return Relief::FLAT;
                };
                let (value, slope) = image.sample(at.uv);
                (
                    a * (2.0 * value - 1.0),
                    (2.0 * a) * (slope.x * at.grad_u + slope.y * at.grad_v),
                )
            }
        };
        if height.is_finite() && gradient.is_finite() {
            Relief {
                height,
                gradient,
                amplitude: a,
            }
        } else {
            Relief::FLAT
        }
    }
}

/// `(sin x, cos x)` to within 1e-15 for `|x|` up to 1.6 million, then with the rounding
/// of the reduction by π/2 growing with `|x|` (about `|x| · 1e-16`, far below what a
/// height of a fraction of a millimetre can show), `(0, 1)` beyond 10⁹ or for a
/// non-finite `x`: a
/// quarter-turn reduction and Taylor polynomials to the 15th and 16th power on ±π/4,
/// several times cheaper than the library's `sin` and `cos` (a texture needs three of
/// each per tick).
#[inline]
fn sin_cos(x: f64) -> (f64, f64) {
    // π/2 in two parts: the first to 33 bits, so that `q * HI` is exact for `q` below
    // 2²⁰ (|x| below 1.6 million), the second what it leaves out.
    const HI: f64 = 1.570_796_326_734_125_6;
    const LO: f64 = 6.077_100_506_506_192e-11;
    if x.is_nan() || x.abs() > 1e9 {
        return (0.0, 1.0);
    }
    let q = (x * std::f64::consts::FRAC_2_PI).round();
    let r = (x - q * HI) - q * LO;
    let r2 = r * r;
    // sin r = r (1 − r²/3! + r⁴/5! − ...), cos r = 1 − r²/2! + r⁴/4! − ...
    let s = r
        * (1.0
            + r2 * (-1.0 / 6.0
                + r2 * (1.0 / 120.0
                    + r2 * (-1.0 / 5040.0
                        + r2 * (1.0 / 362_880.0
                            + r2 * (-1.0 / 39_916_800.0
                                + r2 * (1.0 / 6_227_020_800.0
                                    + r2 * (-1.0 / 1_307_674_368_000.0))))))));
    let c = 1.0
        + r2 * (-0.5
            + r2 * (1.0 / 24.0
                + r2 * (-1.0 / 720.0
                    + r2 * (1.0 / 40_320.0
                        + r2 * (-1.0 / 3_628_800.0
                            + r2 * (1.0 / 479_001_600.0
                                + r2 * (-1.0 / 87_178_291_200.0
                                    + r2 * (1.0 / 20_922_789_888_000.0))))))));
    // The quadrant by bit masks rather than a branch (the hand crosses quadrants at
    // random): odd quadrants swap sine and cosine, the sine's sign flips in quadrants 2
    // and 3, the cosine's in 1 and 2.
    let k = (q as i64) as u64;
    let swap = (k & 1).wrapping_neg();
    let (sb, cb) = (s.to_bits(), c.to_bits());
    let a = (sb & !swap) | (cb & swap);
    let b = (cb & !swap) | (sb & swap);
    (
        f64::from_bits(a ^ ((k & 2) << 62)),
        f64::from_bits(b ^ ((k.wrapping_add(1) & 2) << 62)),
    )
}

/// The amplitude, when it and the wavelength are in their domains and the bumps no
/// steeper than a slope of 1.
fn checked(amplitude: f64, wavelength: f64) -> Result<f64, ParamError> {
    let amplitude = Param::TextureAmplitude.check(amplitude)?;
    let wavelength = Param::TextureWavelength.check(wavelength)?;
    if amplitude * TAU > wavelength {
        return Err(ParamError::TooSteep {
            amplitude,
            wavelength,
        });
    }
    Ok(amplitude)
}

impl FromStr for Texture {
    type Err = SpecError;

    /// `sine:A:L` or `noise:A:L` (metres), or `image:PNG:A` (a height image's file and the
    /// amplitude in metres; the path may hold colons, the amplitude is after the last).
    fn from_str(text: &str) -> Result<Texture, SpecError> {
        let spec = Spec::split(text);
        let make = match spec.kind {
            "sine" => Texture::sine,
            "noise" => Texture::noise,
            "image" => return image_spec(&spec),
            _ => return Err(spec.unknown(KINDS)),
        };
        let [a, l] = spec.numbers("`KIND:AMPLITUDE:WAVELENGTH` (metres)")?;
        make(a, l).map_err(|e| spec.param(e))
    }
}

/// `image:PNG:A`: the image read, and the amplitude.
fn image_spec(spec: &Spec<'_>) -> Result<Texture, SpecError> {
    let form = "`image:PNG:AMPLITUDE` (a PNG file, metres)";
    let Some((amplitude, path)) = spec.values.split_last() else {
        return Err(spec.form(form));
    };
    if path.is_empty() || path.iter().all(|p| p.is_empty()) {
        return Err(spec.form(form));
    }
    let a = number(spec.text, amplitude)?;
    let a = Param::TextureAmplitude
        .check(a)
        .map_err(|e| spec.param(e))?;
    let image = HeightImage::read(Path::new(&path.join(":"))).map_err(|e| match e {
        SpecError::HeightImage { image, reason } => SpecError::Image {
            spec: spec.text.to_owned(),
            path: image,
            reason,
        },
        other => other,
    })?;
    Texture::image(Arc::new(image), a).map_err(|e| spec.param(e))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The gradient is the height's: central differences agree.
    #[test]
    fn the_gradient_is_the_heights() {
        for t in [Texture::sine(2e-4, 2e-3), Texture::noise(1e-4, 1e-3)] {
            let t = t.unwrap();
            for p in [
                DVec3::new(0.01, 0.02, -0.03),
                DVec3::new(-0.1234, 0.0007, 0.05),
            ] {
                let r = t.relief(p, || None);
                assert!(r.height.abs() <= t.amplitude());
                let e = 1e-8;
                for axis in [DVec3::X, DVec3::Y, DVec3::Z] {
                    let numeric = (t.relief(p + e * axis, || None).height
                        - t.relief(p - e * axis, || None).height)
                        / (2.0 * e);
                    assert!(
                        (numeric - r.gradient.dot(axis)).abs() < 1e-5,
                        "{numeric} vs {}",
                        r.gradient.dot(axis)
                    );
                }
            }
        }
    }

    #[test]
    fn sin_cos_is_the_librarys() {
        let mut worst = 0.0_f64;
        for i in -200_000..200_000 {
            let x = f64::from(i) * 0.001_234_567 + 1e-7 * f64::from(i % 7);
            let (s, c) = sin_cos(x);
            worst = worst.max((s - x.sin()).abs()).max((c - x.cos()).abs());
        }
        assert!(worst < 1e-15, "{worst}");
        // Beyond 1.6 million the reduction's rounding grows with |x|.
        for x in [123_456.789, 1e6 + 0.3, -1e8 - 0.7] {
            let (s, c) = sin_cos(x);
            let bound = if x.abs() < 1.6e6 {
                1e-15
            } else {
                1e-16 * x.abs()
            };
            let error = (s - x.sin()).abs().max((c - x.cos()).abs());
            assert!(error < bound, "{x}: {error}");
        }
        assert_eq!(sin_cos(f64::NAN), (0.0, 1.0));
        assert_eq!(sin_cos(1e300), (0.0, 1.0));
    }

    #[test]
    fn specifications_are_read_and_checked() {
        assert_eq!(
            "sine:0.0002:0.002".parse::<Texture>(),
            Texture::sine(0.0002, 0.002).map_err(|_| unreachable!())
        );
        let unknown = "bumps:1:2".parse::<Texture>().unwrap_err().to_string();
        assert!(unknown.contains("unknown kind `bumps`"), "{unknown}");
        let short = "sine:0.001".parse::<Texture>().unwrap_err().to_string();
        assert!(short.contains("expected"), "{short}");
        let negative = "noise:-0.001:0.01"
            .parse::<Texture>()
            .unwrap_err()
            .to_string();
        assert!(negative.contains("texture amplitude must be"), "{negative}");
        let nan = "sine:0.001:nan".parse::<Texture>().unwrap_err().to_string();
        assert!(nan.contains("texture wavelength must be"), "{nan}");
        let word = "sine:x:1".parse::<Texture>().unwrap_err().to_string();
        assert!(word.contains("`x` is not a number"), "{word}");
        let steep = "sine:0.001:0.001"
            .parse::<Texture>()
            .unwrap_err()
            .to_string();
        assert!(steep.contains("steep"), "{steep}");
    }
}
