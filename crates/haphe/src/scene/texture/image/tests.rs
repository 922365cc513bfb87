use image::codecs::png::PngEncoder;
use image::{ExtendedColorType, ImageEncoder};

use super::*;

/// A PNG file of `width × height` pixels of `color` from the raw `bytes` (big-endian
/// 16-bit samples, as PNG stores them).
fn png(width: u32, height: u32, color: ExtendedColorType, bytes: &[u8]) -> Vec<u8> {
    let mut out = Vec::new();
    PngEncoder::new(&mut out)
        .write_image(bytes, width, height, color)
        .expect("a PNG of the test");
    out
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

#[test]
fn a_ramps_gradient_is_its_slope_along_u_and_up_v() {
    // Along a row: 0, 1/7, ..., 1 over 8 pixels: d/du = (1/7 per pixel) × 8 pixels.
    let row: Vec<f32> = (0..8).map(|i| i as f32 / 7.0).collect();
    let image = HeightImage::from_values(8, 1, row.clone()).unwrap();
    for u in [0.1, 0.3, 0.45, 0.8, 0.93] {
        let (value, gradient) = image.sample(DVec2::new(u, 0.37));
        // Between the centres of pixels 0 and 7 the ramp is the line through them.
        let expected = (u * 8.0 - 0.5) / 7.0;
        assert!(close(value, expected, 1e-6), "u {u}: {value} vs {expected}");
        assert!(close(gradient.x, 8.0 / 7.0, 1e-6), "u {u}: {gradient}");
        assert!(close(gradient.y, 0.0, 1e-12), "u {u}: {gradient}");
    }
    // Up the image: rows from the top 1, 2/3, 1/3, 0, so brighter as v grows.
    let column: Vec<f32> = (0..4).map(|r| (3 - r) as f32 / 3.0).collect();
    let image = HeightImage::from_values(1, 4, column).unwrap();
    for v in [0.2, 0.5, 0.7] {
        let (value, gradient) = image.sample(DVec2::new(0.6, v));
        assert!(close(value, (v * 4.0 - 0.5) / 3.0, 1e-6), "v {v}: {value}");
        assert!(close(gradient.y, 4.0 / 3.0, 1e-6), "v {v}: {gradient}");
        assert!(close(gradient.x, 0.0, 1e-12), "v {v}: {gradient}");
    }
}

/// A 5 × 4 image of values from a fixed formula, no two alike.
fn uneven() -> HeightImage {
    let values = (0..20)
        .map(|i| ((i * 7 % 20) as f32 + 0.5) / 20.0)
        .collect();
    HeightImage::from_values(5, 4, values).unwrap()
}

#[test]
fn the_gradient_is_that_of_the_bilinear_value() {
    let image = uneven();
    let e = 1e-7;
    for uv in [
        DVec2::new(0.13, 0.71),
        DVec2::new(0.52, 0.06),
        DVec2::new(0.97, 0.48),
        DVec2::new(-3.31, 12.22),
    ] {
        let (_, gradient) = image.sample(uv);
        let du =
            (image.sample(uv + DVec2::X * e).0 - image.sample(uv - DVec2::X * e).0) / (2.0 * e);
        let dv =
            (image.sample(uv + DVec2::Y * e).0 - image.sample(uv - DVec2::Y * e).0) / (2.0 * e);
        assert!(close(du, gradient.x, 1e-5), "{uv}: {du} vs {gradient}");
        assert!(close(dv, gradient.y, 1e-5), "{uv}: {dv} vs {gradient}");
    }
}

#[test]
fn texture_coordinates_wrap_around() {
    let image = uneven();
    for uv in [DVec2::new(0.13, 0.71), DVec2::new(0.97, 0.02)] {
        let here = image.sample(uv);
        for shift in [
            DVec2::new(1.0, 0.0),
            DVec2::new(-2.0, 3.0),
            DVec2::new(5.0, -7.0),
        ] {
            let there = image.sample(uv + shift);
            assert!(close(here.0, there.0, 1e-12), "{uv} + {shift}");
            assert!((here.1 - there.1).length() < 1e-9, "{uv} + {shift}");
        }
    }
    // On the left edge (u = 0), half-way between the first and the last column's
    // centres; on the bottom edge (v = 0), between the bottom and the top row.
    let values = image.values();
    let (first, last) = (values[15], values[19]); // bottom row: the last in the file
    let (value, _) = image.sample(DVec2::new(0.0, 0.5 / 4.0));
    assert!(close(value, f64::from(first + last) / 2.0, 1e-6), "{value}");
    let (bottom, top) = (values[15 + 2], values[2]);
    let (value, _) = image.sample(DVec2::new(2.5 / 5.0, 0.0));
    assert!(close(value, f64::from(bottom + top) / 2.0, 1e-6), "{value}");
}

#[test]
fn a_bright_pixel_peaks_at_the_texture_coordinate_of_its_centre() {
    // Pixel (3, 1), column 3 and row 1 from the top, of a 5 × 4 black image.
    let mut values = vec![0.0; 20];
    values[5 + 3] = 1.0;
    let image = HeightImage::from_values(5, 4, values).unwrap();
    let centre = DVec2::new((3.0 + 0.5) / 5.0, 1.0 - (1.0 + 0.5) / 4.0);
    assert_eq!(image.sample(centre).0, 1.0);
    // On a grid finer than the pixels that holds the centre (0.7 = 56/80, 0.625 =
    // 50/80), the peak is there.
    let n = 80;
    let mut best = (f64::NEG_INFINITY, DVec2::ZERO);
    for i in 0..n {
        for j in 0..n {
            let uv = DVec2::new(i as f64 / n as f64, j as f64 / n as f64);
            let (value, _) = image.sample(uv);
            if value > best.0 {
                best = (value, uv);
            }
        }
    }
    assert!((best.1 - centre).length() < 1e-12, "{best:?} vs {centre}");
}

#[test]
fn non_finite_coordinates_give_zero() {
    let image = uneven();
    for uv in [
        DVec2::new(f64::NAN, 0.5),
        DVec2::new(0.5, f64::INFINITY),
        DVec2::new(f64::NEG_INFINITY, f64::NAN),
    ] {
        assert_eq!(image.sample(uv), (0.0, DVec2::ZERO), "{uv}");
    }
    // Huge but finite coordinates stay in the image.
    for uv in [DVec2::new(1e300, -1e300), DVec2::new(-1e-300, 1e17)] {
        let (value, gradient) = image.sample(uv);
        assert!((0.0..=1.0).contains(&value) && gradient.is_finite(), "{uv}");
    }
}

#[test]
fn png_grey_and_colour_are_read_as_heights() {
    // 2 × 1 pixels each: grey 51 (0.2) and 255.
    let l8 =
        HeightImage::from_png("l8.png", &png(2, 1, ExtendedColorType::L8, &[51, 255])).unwrap();
    assert_eq!(l8.values(), &[0.2, 1.0]);
    let l16 = png(2, 1, ExtendedColorType::L16, &[0x33, 0x33, 0, 0]);
    let l16 = HeightImage::from_png("l16.png", &l16).unwrap();
    assert_eq!(l16.values(), &[0x3333 as f32 / 65535.0, 0.0]);
    // Pure red and white; alpha ignored.
    let rgb = png(2, 1, ExtendedColorType::Rgb8, &[255, 0, 0, 255, 255, 255]);
    let rgb = HeightImage::from_png("rgb.png", &rgb).unwrap();
    assert!(
        close(f64::from(rgb.values()[0]), 0.2126, 1e-6),
        "{:?}",
        rgb.values()
    );
    assert!(
        close(f64::from(rgb.values()[1]), 1.0, 1e-6),
        "{:?}",
        rgb.values()
    );
    let rgba = png(
        1,
        2,
        ExtendedColorType::Rgba8,
        &[0, 255, 0, 0, 0, 0, 255, 255],
    );
    let rgba = HeightImage::from_png("rgba.png", &rgba).unwrap();
    assert_eq!((rgba.width(), rgba.height()), (1, 2));
    assert!(
        close(f64::from(rgba.values()[0]), 0.7152, 1e-6),
        "{:?}",
        rgba.values()
    );
    assert!(
        close(f64::from(rgba.values()[1]), 0.0722, 1e-6),
        "{:?}",
        rgba.values()
    );
}

/// The CRC-32 of PNG chunks (ISO 3309), bit by bit.
fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &b in bytes {
        crc ^= u32::from(b);
        for _ in 0..8 {
            crc = if crc & 1 == 1 {
                (crc >> 1) ^ 0xEDB8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

/// `file` with the width and height of its IHDR chunk replaced (and its CRC redone).
fn resized(file: &[u8], width: u32, height: u32) -> Vec<u8> {
    let mut out = file.to_vec();
    // Signature (8), length (4), "IHDR" (4), then width and height.
    out[16..20].copy_from_slice(&width.to_be_bytes());
    out[20..24].copy_from_slice(&height.to_be_bytes());
    let crc = crc32(&out[12..29]);
    out[29..33].copy_from_slice(&crc.to_be_bytes());
    out
}

#[test]
fn bad_files_are_refused_naming_the_file_and_why() {
    let message = |r: Result<HeightImage, SpecError>| r.unwrap_err().to_string();
    let text = message(HeightImage::from_png(
        "bumps.jpg",
        b"\xFF\xD8\xFF\xE0 not png",
    ));
    assert!(text.starts_with("bumps.jpg: not a PNG file"), "{text}");
    let file = png(2, 2, ExtendedColorType::L8, &[0, 1, 2, 3]);
    let text = message(HeightImage::from_png("cut.png", &file[..file.len() - 20]));
    assert!(text.starts_with("cut.png: not a valid PNG file"), "{text}");
    let text = message(HeightImage::from_png(
        "wide.png",
        &resized(&file, 20_000, 2),
    ));
    assert!(
        text.contains("wide.png: 20000 × 2 pixels: a side is over the 16384"),
        "{text}"
    );
    let text = message(HeightImage::from_png(
        "big.png",
        &resized(&file, 16_384, 16_384),
    ));
    assert!(
        text.contains("big.png: 16384 × 16384 = 268435456 pixels, more than"),
        "{text}"
    );
    let path = std::env::temp_dir().join("haphe-no-such-height-image.png");
    let text = message(HeightImage::read(&path));
    assert!(
        text.starts_with(&format!("{}: cannot read the file", path.display())),
        "{text}"
    );
    // The header's size is checked before the pixels: a zero width is refused by the
    // decoder or by us, never decoded.
    let text = message(HeightImage::from_png("empty.png", &resized(&file, 0, 2)));
    assert!(text.starts_with("empty.png: "), "{text}");
}

#[test]
fn values_are_checked() {
    let message = |r: Result<HeightImage, SpecError>| r.unwrap_err().to_string();
    assert_eq!(
        message(HeightImage::from_values(0, 3, vec![])),
        "height image values: the image has no pixels (0 × 3)"
    );
    assert_eq!(
        message(HeightImage::from_values(2, 2, vec![0.0; 5])),
        "height image values: 5 values for 2 × 2 = 4 pixels"
    );
    let mut values = vec![0.5; 6];
    values[4] = f32::NAN;
    assert_eq!(
        message(HeightImage::from_values(3, 2, values.clone())),
        "height image values: pixel (1, 1) (column, row from the top) is NaN, not a height \
         from 0 to 1"
    );
    values[4] = 1.5;
    assert!(HeightImage::from_values(3, 2, values).is_err());
    let image = HeightImage::from_values(3, 2, vec![0.25; 6]).unwrap();
    assert_eq!(image.heap_bytes(), 6 * 4);
}
