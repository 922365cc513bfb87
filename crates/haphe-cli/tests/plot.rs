//! The simulate plot, read back from its PNG: the side view outlines the object's section
//! (pixels of the section's colour across the panel), and the force panel draws the
//! three components beside the length (each in its colour).

mod common;

use common::{ok, s, scratch};

/// The colours of the plot (crates/haphe-cli/src/session/plot.rs).
const SECTION: [u8; 3] = [64, 64, 64];
const FORCE_XYZ: [[u8; 3]; 3] = [[148, 103, 189], [188, 189, 34], [23, 190, 207]];
const HIP: [u8; 3] = [255, 127, 14];

/// The PNG at `path`: width, height and RGB rows.
fn read_png(path: &std::path::Path) -> (usize, usize, Vec<u8>) {
    let decoder = png::Decoder::new(std::io::BufReader::new(
        std::fs::File::open(path).expect("the plot"),
    ));
    let mut reader = decoder.read_info().expect("a PNG");
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).expect("a frame");
    let channels = info.color_type.samples();
    let (w, h) = (info.width as usize, info.height as usize);
    let rgb = buf[..w * h * channels]
        .chunks(channels)
        .flat_map(|p| [p[0], p[1], p[2]])
        .collect();
    (w, h, rgb)
}

/// The columns, within the rows `rows` and columns `columns`, holding a pixel of `colour`.
fn columns_with(
    (w, _, rgb): &(usize, usize, Vec<u8>),
    rows: std::ops::Range<usize>,
    columns: std::ops::Range<usize>,
    colour: [u8; 3],
) -> usize {
    columns
        .filter(|&x| {
            rows.clone()
                .any(|y| rgb[3 * (y * w + x)..3 * (y * w + x) + 3] == colour)
        })
        .count()
}

#[test]
fn the_side_view_outlines_the_section_and_the_force_has_its_components() {
    let dir = scratch("plot");
    let png = dir.join("slide.png");
    ok(&[
        "simulate",
        "--shape",
        "sphere",
        "--triangles",
        "2000",
        "--path",
        "slide",
        "--seconds",
        "3",
        "--plot",
        s(&png),
    ]);
    let image = read_png(&png);
    let (w, h) = (image.0, image.1);
    // The panels: the side view is the lower part (below 450 px), the force the upper left.
    let section = columns_with(&image, 450..h, 0..w, SECTION);
    // Guards against a stray pixel: the slide runs over the top of the sphere, whose
    // section spans most of the side view's width.
    assert!(
        section > w / 3,
        "the section shows in {section} columns of {w}"
    );
    for colour in FORCE_XYZ {
        let columns = columns_with(&image, 0..450, 0..w / 2, colour);
        assert!(columns > 50, "{colour:?} in {columns} columns");
    }
    let hip = columns_with(&image, 450..h, 0..w, HIP);
    assert!(hip > w / 3, "the device point shows in {hip} columns");
}
