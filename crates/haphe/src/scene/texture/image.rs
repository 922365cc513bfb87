//! Height images: a grey image whose value (0 to 1) is a height over the surface, read
//! through the shape's texture coordinates.
//!
//! Conventions, for reading and for sampling:
//! - pixel values are heights from 0 (black) to 1 (white); colour is turned into luminance
//!   (Rec. 709 weights `0.2126 R + 0.7152 G + 0.0722 B` on the stored values, no gamma
//!   decoding); alpha is ignored;
//! - texture coordinate `(u, v)` covers the image once over `[0, 1]²` and repeats outside
//!   it (wrap-around addressing); `u` runs along a row, left to right, and `v` up the
//!   image: `v = 0` is the bottom row's edge, `v = 1` the top row's (the convention of OBJ
//!   and of haphe's texture coordinates, glTF's being turned over on reading);
//! - pixel `(x, y)`, with `y` counted from the top row as in the file, has its centre at
//!   `u = (x + ½) / width`, `v = 1 − (y + ½) / height`; between centres the value is
//!   interpolated bilinearly.

use std::path::Path;

use glam::DVec2;
use image::codecs::png::PngDecoder;
use image::{DynamicImage, ImageDecoder, Limits};

use crate::scene::SpecError;

/// The most pixels a height image may have along either side.
pub(crate) const MAX_HEIGHT_IMAGE_SIDE: u32 = 16_384;

/// The most pixels a height image may have: 2^26 (8192 × 8192), 256 MB of heights. A
/// height map finer than that is finer than a hand can feel over any object a servo loop
/// renders.
pub(crate) const MAX_HEIGHT_IMAGE_PIXELS: u64 = 1 << 26;

/// The bytes a PNG file starts with.
const PNG_SIGNATURE: &[u8] = b"\x89PNG\r\n\x1a\n";

/// Rec. 709 luminance weights of red, green and blue.
const LUMA: [f32; 3] = [0.2126, 0.7152, 0.0722];

/// A grey height image: `width × height` values from 0 to 1, row after row from the top
/// row, as in the file. See the module for how texture coordinates address it.
///
/// Invariants: `width` and `height` are at least 1, at most 16 384, their product at most
/// 2^26 (8192 × 8192: 256 MB of heights; a height map finer than that is finer than a
/// hand feels over any object a servo loop renders); there are `width × height` values,
/// each in `[0, 1]`.
///
/// ```
/// use haphe::scene::HeightImage;
/// // Two pixels: black on the left, white on the right.
/// let image = HeightImage::from_values(2, 1, vec![0.0, 1.0])?;
/// assert_eq!((image.width(), image.height()), (2, 1));
/// assert!(HeightImage::from_values(2, 2, vec![0.0; 3]).is_err());
/// # Ok::<(), haphe::scene::SpecError>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct HeightImage {
    width: u32,
    height: u32,
    values: Box<[f32]>,
}

impl HeightImage {
    /// Reads the PNG file at `path` (8- or 16-bit grey, grey with alpha, RGB or RGBA).
    ///
    /// # Errors
    /// [`SpecError::HeightImage`] naming the file and why: it cannot be read (missing, a
    /// directory, no permission), or as [`HeightImage::from_png`].
    pub fn read(path: &Path) -> Result<HeightImage, SpecError> {
        let name = path.display().to_string();
        let bytes = std::fs::read(path).map_err(|e| SpecError::HeightImage {
            image: name.clone(),
            reason: format!("cannot read the file: {e}"),
        })?;
        HeightImage::from_png(&name, &bytes)
    }

    /// Decodes the bytes of a PNG file named `name` (the name is used in errors).
    ///
    /// # Errors
    /// [`SpecError::HeightImage`] naming `name` and why: not a PNG file (no PNG
    /// signature), a PNG that cannot be decoded (truncated, corrupt), no pixels, more
    /// than 16 384 pixels along a side or 2^26 in all (refused from the header, before the
    /// pixels are decoded).
    pub fn from_png(name: &str, bytes: &[u8]) -> Result<HeightImage, SpecError> {
        let refuse = |reason: String| SpecError::HeightImage {
            image: name.to_owned(),
            reason,
        };
        if !bytes.starts_with(PNG_SIGNATURE) {
            return Err(refuse(
                "not a PNG file (it does not start with the PNG signature); height images \
                 are read from PNG"
                    .to_owned(),
            ));
        }
        let invalid = |e: image::ImageError| refuse(format!("not a valid PNG file: {e}"));
        let mut limits = Limits::default();
        limits.max_image_width = Some(MAX_HEIGHT_IMAGE_SIDE);
        limits.max_image_height = Some(MAX_HEIGHT_IMAGE_SIDE);
        // The header is read under the default limits, the pixels under ours.
        let mut decoder = PngDecoder::new(std::io::Cursor::new(bytes)).map_err(invalid)?;
        let (width, height) = decoder.dimensions();
        check_size(width, height).map_err(refuse)?;
        // A decoded pixel holds at most 8 bytes (RGBA, 16 bits a channel).
        limits.max_alloc = Some(9 * MAX_HEIGHT_IMAGE_PIXELS);
        decoder.set_limits(limits).map_err(invalid)?;
        let image = DynamicImage::from_decoder(decoder).map_err(invalid)?;
        HeightImage::from_values(width, height, grey(&image)).map_err(|e| match e {
            SpecError::HeightImage { reason, .. } => refuse(reason),
            other => other,
        })
    }

    /// A height image from values given row after row, from the top row, each from 0 to
    /// 1.
    ///
    /// # Errors
    /// [`SpecError::HeightImage`] (named "height image values"): no pixels, a side over
    /// 16 384 or more than 2^26 pixels, another
    /// number of values than `width × height`, or a value that is not a number from 0 to
    /// 1 (naming its pixel).
    pub fn from_values(
        width: u32,
        height: u32,
        values: Vec<f32>,
    ) -> Result<HeightImage, SpecError> {
        let refuse = |reason: String| SpecError::HeightImage {
            image: "height image values".to_owned(),
            reason,
        };
        check_size(width, height).map_err(refuse)?;
        let pixels = u64::from(width) * u64::from(height);
        if values.len() as u64 != pixels {
            return Err(refuse(format!(
                "{} values for {width} × {height} = {pixels} pixels",
                values.len()
            )));
        }
        if let Some(i) = values.iter().position(|v| !(0.0..=1.0).contains(v)) {
            let w = width as usize;
            return Err(refuse(format!(
                "pixel ({}, {}) (column, row from the top) is {}, not a height from 0 to 1",
                i % w,
                i / w,
                values[i]
            )));
        }
        Ok(HeightImage {
            width,
            height,
            values: values.into_boxed_slice(),
        })
    }

    /// Pixels along a row.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Rows.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The values, row after row from the top row, each from 0 to 1.
    pub fn values(&self) -> &[f32] {
        &self.values
    }

    /// The value at texture coordinate `uv` (bilinear between pixel centres, repeating
    /// outside `[0, 1]²`; see the module) and its exact gradient `(∂/∂u, ∂/∂v)` (per unit
    /// of texture coordinate) of that bilinear interpolant. `(0, 0)` for a non-finite
    /// `uv`.
    ///
    /// # Real-time
    /// No allocation, no panic; four values read.
    pub(crate) fn sample(&self, uv: DVec2) -> (f64, DVec2) {
        if !uv.is_finite() {
            return (0.0, DVec2::ZERO);
        }
        let (w, h) = (f64::from(self.width), f64::from(self.height));
        // Continuous pixel coordinates: column x and row y counted from the bottom, pixel
        // centres at whole numbers. Wrapped into [0, 1] first, so that a large u keeps its
        // fraction and the products stay small.
        let x = uv.x.rem_euclid(1.0) * w - 0.5;
        let y = uv.y.rem_euclid(1.0) * h - 0.5;
        let (x0, y0) = (x.floor(), y.floor());
        let (fx, fy) = (x - x0, y - y0);
        let column = |c: f64| (c.rem_euclid(w) as usize).min(self.width as usize - 1);
        let row_from_bottom = |r: f64| (r.rem_euclid(h) as usize).min(self.height as usize - 1);
        let (c0, c1) = (column(x0), column(x0 + 1.0));
        let (r0, r1) = (row_from_bottom(y0), row_from_bottom(y0 + 1.0));
        let at = |c: usize, r: usize| {
            let row_from_top = self.height as usize - 1 - r;
            let index = row_from_top * self.width as usize + c;
            f64::from(self.values.get(index).copied().unwrap_or(0.0))
        };
        let (v00, v10, v01, v11) = (at(c0, r0), at(c1, r0), at(c0, r1), at(c1, r1));
        let bottom = v00 + fx * (v10 - v00);
        let top = v01 + fx * (v11 - v01);
        let value = bottom + fy * (top - bottom);
        // d/dx and d/dy of the bilinear form, times dx/du = width and dy/dv = height.
        let d_dx = (1.0 - fy) * (v10 - v00) + fy * (v11 - v01);
        let d_dy = top - bottom;
        (value, DVec2::new(d_dx * w, d_dy * h))
    }

    /// Bytes of memory the image holds.
    pub fn heap_bytes(&self) -> usize {
        size_of_val(&*self.values)
    }
}

/// Checks an image's size against the limits; the reason when it is refused.
fn check_size(width: u32, height: u32) -> Result<(), String> {
    if width == 0 || height == 0 {
        return Err(format!("the image has no pixels ({width} × {height})"));
    }
    if width > MAX_HEIGHT_IMAGE_SIDE || height > MAX_HEIGHT_IMAGE_SIDE {
        return Err(format!(
            "{width} × {height} pixels: a side is over the {MAX_HEIGHT_IMAGE_SIDE} pixels a \
             height image may have"
        ));
    }
    let pixels = u64::from(width) * u64::from(height);
    if pixels > MAX_HEIGHT_IMAGE_PIXELS {
        return Err(format!(
            "{width} × {height} = {pixels} pixels, more than the {MAX_HEIGHT_IMAGE_PIXELS} a \
             height image may have"
        ));
    }
    Ok(())
}

/// The grey values (0 to 1) of a decoded image, row after row from the top: grey as it is,
/// colour as its luminance, alpha ignored.
fn grey(image: &DynamicImage) -> Vec<f32> {
    fn of<T: Copy>(raw: &[T], channels: usize, scale: f32, to_f32: impl Fn(T) -> f32) -> Vec<f32> {
        raw.chunks_exact(channels)
            .map(|p| {
                let l = if channels >= 3 {
                    LUMA[0] * to_f32(p[0]) + LUMA[1] * to_f32(p[1]) + LUMA[2] * to_f32(p[2])
                } else {
                    to_f32(p[0])
                };
                (l / scale).clamp(0.0, 1.0)
            })
            .collect()
    }
    match image {
        DynamicImage::ImageLuma8(b) => of(b.as_raw(), 1, 255.0, f32::from),
        DynamicImage::ImageLumaA8(b) => of(b.as_raw(), 2, 255.0, f32::from),
        DynamicImage::ImageRgb8(b) => of(b.as_raw(), 3, 255.0, f32::from),
        DynamicImage::ImageRgba8(b) => of(b.as_raw(), 4, 255.0, f32::from),
        DynamicImage::ImageLuma16(b) => of(b.as_raw(), 1, 65535.0, f32::from),
        DynamicImage::ImageLumaA16(b) => of(b.as_raw(), 2, 65535.0, f32::from),
        DynamicImage::ImageRgb16(b) => of(b.as_raw(), 3, 65535.0, f32::from),
        DynamicImage::ImageRgba16(b) => of(b.as_raw(), 4, 65535.0, f32::from),
        DynamicImage::ImageRgb32F(b) => of(b.as_raw(), 3, 1.0, |x| x),
        DynamicImage::ImageRgba32F(b) => of(b.as_raw(), 4, 1.0, |x| x),
        other => other.to_luma32f().into_raw(),
    }
}

#[cfg(test)]
mod tests;
