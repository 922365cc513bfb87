//! The run's PNG: the force (its components and its length) and the penetration over
//! time, and the path seen from the side (x–z plane): the objects' section by the plane
//! of the path, the proxy, and the device point drawn over it.
//!
//! Text is drawn with DejaVu Sans embedded in the binary, so plotting needs no system fonts.

use std::error::Error;
use std::path::Path;

use anyhow::anyhow;
use plotters::prelude::*;

use haphe::DVec3;
use haphe::scene::SceneObject;

use super::summary::PlotPoint;

/// The device point: orange, over the proxy.
pub const HIP: RGBColor = RGBColor(255, 127, 14);
pub const PROXY: RGBColor = RGBColor(31, 119, 180);
/// The force's length.
pub const FORCE: RGBColor = RGBColor(214, 39, 40);
/// The force's x, y and z components.
pub const FORCE_XYZ: [RGBColor; 3] = [
    RGBColor(148, 103, 189),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];
const DEPTH: RGBColor = RGBColor(44, 160, 44);
/// The objects' section in the side view.
pub const SECTION: RGBColor = RGBColor(64, 64, 64);

/// Draws `points` to `path` (PNG) under `title`, with the section of `objects` (as placed
/// at the start) in the side view.
pub fn write(
    path: &Path,
    title: &str,
    points: &[PlotPoint],
    objects: &[SceneObject],
) -> anyhow::Result<()> {
    plotters::style::register_font("sans-serif", FontStyle::Normal, dejavu::sans::regular())
        .map_err(|_| anyhow!("the embedded DejaVu Sans font is unreadable"))?;
    let y = if points.is_empty() {
        0.0
    } else {
        points.iter().map(|p| p.hip.y).sum::<f64>() / points.len() as f64
    };
    let section = section(objects, y);
    crate::output::write_png(path, SIZE, |pixels| draw(pixels, title, points, &section))
}

/// The section of `objects` by the plane `y = y` (world): one segment (x, z), metres, per
/// triangle that crosses it.
pub fn section(objects: &[SceneObject], y: f64) -> Vec<[(f64, f64); 2]> {
    let mut segments = Vec::new();
    for o in objects {
        let surface = o.shape.surface();
        let v = surface.vertices();
        for t in surface.triangles() {
            let p = t.map(|i| o.pose.to_world(v[i as usize]));
            let mut ends = [(0.0, 0.0); 2];
            let mut n = 0;
            for (a, b) in [(p[0], p[1]), (p[1], p[2]), (p[2], p[0])] {
                let (da, db) = (a.y - y, b.y - y);
                if (da < 0.0) != (db < 0.0) && n < 2 {
                    let c: DVec3 = a + (b - a) * (da / (da - db));
                    ends[n] = (c.x, c.z);
                    n += 1;
                }
            }
            if n == 2 {
                segments.push(ends);
            }
        }
    }
    segments
}

/// Tick labels with as many decimals as a fifth of `span` needs, so that labels stay
/// short on scenes of millimetres.
fn decimals(span: f64) -> usize {
    let step = (span / 5.0).abs();
    if !step.is_finite() || step <= 0.0 || step >= 1.0 {
        0
    } else {
        (-step.log10().floor()).clamp(0.0, 6.0) as usize
    }
}

fn range(values: impl Iterator<Item = f64>, pad: f64) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values.filter(|v| v.is_finite()) {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    let span = (hi - lo).max(1e-9);
    (lo - pad * span, hi + pad * span)
}

/// The picture's size in pixels.
const SIZE: (u32, u32) = (1200, 950);

fn draw(
    pixels: &mut [u8],
    title: &str,
    points: &[PlotPoint],
    section: &[[(f64, f64); 2]],
) -> Result<(), Box<dyn Error>> {
    let root = BitMapBackend::with_buffer(pixels, SIZE).into_drawing_area();
    root.fill(&WHITE)?;
    let root = root.titled(title, ("sans-serif", 22))?;
    let (top, bottom) = root.split_vertically(420);
    let (force_area, depth_area) = top.split_horizontally(600);
    let t_end = points.last().map_or(1.0, |p| p.t).max(1e-6);
    draw_force(&force_area, points, t_end)?;
    draw_depth(&depth_area, points, t_end)?;
    draw_side(&bottom, points, section)?;
    root.present()?;
    Ok(())
}

/// A part of the picture.
type Area<'a> = DrawingArea<BitMapBackend<'a>, plotters::coord::Shift>;

/// The force on the hand over time: its components and its length.
fn draw_force(area: &Area<'_>, points: &[PlotPoint], t_end: f64) -> Result<(), Box<dyn Error>> {
    let f_max = points
        .iter()
        .map(|p| p.force.length())
        .fold(0.0, f64::max)
        .max(0.1)
        * 1.1;
    let mut chart = ChartBuilder::on(area)
        .caption("force on the hand", ("sans-serif", 18))
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(55)
        .build_cartesian_2d(0.0..t_end, -f_max..f_max)?;
    chart
        .configure_mesh()
        .x_desc("time (s)")
        .y_desc("force (N, world)")
        .draw()?;
    for (k, (name, colour)) in ["x", "y", "z"].into_iter().zip(FORCE_XYZ).enumerate() {
        chart
            .draw_series(LineSeries::new(
                points.iter().map(|p| (p.t, p.force[k])),
                colour.stroke_width(1),
            ))?
            .label(format!("F{name}"))
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 16, y)], colour));
    }
    chart
        .draw_series(LineSeries::new(
            points.iter().map(|p| (p.t, p.force.length())),
            FORCE.stroke_width(2),
        ))?
        .label("|F|")
        .legend(|(x, y)| PathElement::new([(x, y), (x + 16, y)], FORCE));
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .position(SeriesLabelPosition::UpperRight)
        .label_font(("sans-serif", 13))
        .draw()?;

    Ok(())
}

/// The penetration over time.
fn draw_depth(area: &Area<'_>, points: &[PlotPoint], t_end: f64) -> Result<(), Box<dyn Error>> {
    let d_max = points
        .iter()
        .map(|p| p.penetration * 1e3)
        .fold(0.0, f64::max)
        .max(0.1)
        * 1.1;
    let mut chart = ChartBuilder::on(area)
        .caption(
            "penetration (device point behind the proxy)",
            ("sans-serif", 18),
        )
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(55)
        .build_cartesian_2d(0.0..t_end, 0.0..d_max)?;
    chart
        .configure_mesh()
        .x_desc("time (s)")
        .y_desc("penetration (mm)")
        .draw()?;
    chart.draw_series(LineSeries::new(
        points.iter().map(|p| (p.t, p.penetration * 1e3)),
        DEPTH.stroke_width(1),
    ))?;

    Ok(())
}

/// The path seen from the side, with the objects' section.
fn draw_side(
    area: &Area<'_>,
    points: &[PlotPoint],
    section: &[[(f64, f64); 2]],
) -> Result<(), Box<dyn Error>> {
    // Side view, millimetres, equal scale on both axes.
    let (x0, x1) = range(
        points.iter().flat_map(|p| [p.hip.x * 1e3, p.proxy.x * 1e3]),
        0.05,
    );
    let (z0, z1) = range(
        points.iter().flat_map(|p| [p.hip.z * 1e3, p.proxy.z * 1e3]),
        0.05,
    );
    // Keep 1 mm in x as wide as 1 mm in z (plot area about 1130 x 440 pixels).
    let aspect = 1130.0 / 440.0;
    let (cx, cz) = (0.5 * (x0 + x1), 0.5 * (z0 + z1));
    let half_z = (0.5 * (z1 - z0)).max(0.5 * (x1 - x0) / aspect);
    let half_x = half_z * aspect;
    let (x_digits, z_digits) = (decimals(2.0 * half_x), decimals(2.0 * half_z));
    let mut chart = ChartBuilder::on(area)
        .caption(
            "the path seen from the side (dark grey: the objects' section, blue: proxy, orange: device point, red dots: contact)",
            ("sans-serif", 18),
        )
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(75)
        .build_cartesian_2d(cx - half_x..cx + half_x, cz - half_z..cz + half_z)?;
    chart
        .configure_mesh()
        .x_desc("x (mm, world)")
        .y_desc("z (mm, world)")
        .x_label_formatter(&|v| format!("{v:.x_digits$}"))
        .y_label_formatter(&|v| format!("{v:.z_digits$}"))
        .draw()?;
    let inside = |(x, z): (f64, f64)| {
        (cx - half_x..=cx + half_x).contains(&x) && (cz - half_z..=cz + half_z).contains(&z)
    };
    // The proxy first, the device point over it: where they coincide (free motion) the
    // device point shows.
    chart.draw_series(LineSeries::new(
        points.iter().map(|p| (p.proxy.x * 1e3, p.proxy.z * 1e3)),
        PROXY.stroke_width(3),
    ))?;
    chart.draw_series(LineSeries::new(
        points.iter().map(|p| (p.hip.x * 1e3, p.hip.z * 1e3)),
        HIP.stroke_width(1),
    ))?;
    let step = (points.len() / 2000).max(1);
    chart.draw_series(
        points
            .iter()
            .step_by(step)
            .filter(|p| p.contact)
            .map(|p| Circle::new((p.proxy.x * 1e3, p.proxy.z * 1e3), 2, FORCE.filled())),
    )?;
    // The section last: the contact dots lie on it and must not hide it.
    chart.draw_series(
        section
            .iter()
            .map(|[a, b]| [(a.0 * 1e3, a.1 * 1e3), (b.0 * 1e3, b.1 * 1e3)])
            .filter(|[a, b]| inside(*a) || inside(*b))
            .map(|ends| PathElement::new(ends, SECTION.stroke_width(2))),
    )?;
    Ok(())
}
