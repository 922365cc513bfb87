//! The run's PNG: force and penetration over time, and the path seen from the side
//! (x–z plane), device point and proxy.
//!
//! Text is drawn with DejaVu Sans embedded in the binary, so plotting needs no system fonts.

use std::error::Error;
use std::path::Path;

use anyhow::anyhow;
use plotters::prelude::*;

use super::summary::PlotPoint;

const HIP: RGBColor = RGBColor(150, 150, 150);
const PROXY: RGBColor = RGBColor(31, 119, 180);
const FORCE: RGBColor = RGBColor(214, 39, 40);
const DEPTH: RGBColor = RGBColor(44, 160, 44);

/// Draws `points` to `path` (PNG) under `title`.
pub fn write(path: &Path, title: &str, points: &[PlotPoint]) -> anyhow::Result<()> {
    plotters::style::register_font("sans-serif", FontStyle::Normal, dejavu::sans::regular())
        .map_err(|_| anyhow!("the embedded DejaVu Sans font is unreadable"))?;
    crate::output::write_png(path, SIZE, |pixels| draw(pixels, title, points))
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

fn draw(pixels: &mut [u8], title: &str, points: &[PlotPoint]) -> Result<(), Box<dyn Error>> {
    let root = BitMapBackend::with_buffer(pixels, SIZE).into_drawing_area();
    root.fill(&WHITE)?;
    let root = root.titled(title, ("sans-serif", 22))?;
    let (top, bottom) = root.split_vertically(420);
    let (force_area, depth_area) = top.split_horizontally(600);
    let t_end = points.last().map_or(1.0, |p| p.t).max(1e-6);

    let f_max = points.iter().map(|p| p.force).fold(0.0, f64::max).max(0.1) * 1.1;
    let mut chart = ChartBuilder::on(&force_area)
        .caption("force on the hand", ("sans-serif", 18))
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(55)
        .build_cartesian_2d(0.0..t_end, 0.0..f_max)?;
    chart
        .configure_mesh()
        .x_desc("time (s)")
        .y_desc("|force| (N)")
        .draw()?;
    chart.draw_series(LineSeries::new(
        points.iter().map(|p| (p.t, p.force)),
        FORCE.stroke_width(1),
    ))?;

    let d_max = points
        .iter()
        .map(|p| p.penetration * 1e3)
        .fold(0.0, f64::max)
        .max(0.1)
        * 1.1;
    let mut chart = ChartBuilder::on(&depth_area)
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
    let mut chart = ChartBuilder::on(&bottom)
        .caption(
            "the path seen from the side (grey: device point, blue: proxy, red dots: contact)",
            ("sans-serif", 18),
        )
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(55)
        .build_cartesian_2d(cx - half_x..cx + half_x, cz - half_z..cz + half_z)?;
    chart
        .configure_mesh()
        .x_desc("x (mm, world)")
        .y_desc("z (mm, world)")
        .draw()?;
    chart.draw_series(LineSeries::new(
        points.iter().map(|p| (p.hip.x * 1e3, p.hip.z * 1e3)),
        HIP.stroke_width(1),
    ))?;
    chart.draw_series(LineSeries::new(
        points.iter().map(|p| (p.proxy.x * 1e3, p.proxy.z * 1e3)),
        PROXY.stroke_width(2),
    ))?;
    let step = (points.len() / 2000).max(1);
    chart.draw_series(
        points
            .iter()
            .step_by(step)
            .filter(|p| p.contact)
            .map(|p| Circle::new((p.proxy.x * 1e3, p.proxy.z * 1e3), 2, FORCE.filled())),
    )?;
    root.present()?;
    Ok(())
}
