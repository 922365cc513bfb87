//! `--plot DIR`: one PNG per query kind, cost against triangle count on log-log axes, one
//! line per method and mesh family (solid: p50, dashed: p99).
//!
//! The text is drawn with DejaVu Sans embedded in the binary (the `dejavu` crate), so
//! plotting needs no system fonts.

use std::error::Error;
use std::path::{Path, PathBuf};

use anyhow::{Context as _, anyhow};
use plotters::prelude::*;

use super::json::Record;
use super::methods::{Method, Query};

/// Times below this (ns) are drawn at it: a log axis has no zero, and the clock cannot
/// resolve less.
const SMALLEST_NS: f64 = 0.5;

/// Writes `DIR/<query>.png` for every query kind with records; returns the paths.
///
/// # Errors
/// When the folder cannot be created or a plot cannot be drawn or written.
pub fn write(dir: &Path, records: &[Record]) -> anyhow::Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    plotters::style::register_font("sans-serif", FontStyle::Normal, dejavu::sans::regular())
        .map_err(|_| anyhow!("the embedded DejaVu Sans font is unreadable"))?;
    let mut written = Vec::new();
    for query in Query::ALL {
        let rows: Vec<&Record> = records.iter().filter(|r| r.query == query).collect();
        if rows.is_empty() {
            continue;
        }
        let path = dir.join(format!("{}.png", query.name()));
        crate::output::write_png(&path, SIZE, |pixels| draw(pixels, query, &rows))?;
        written.push(path);
    }
    Ok(written)
}

/// The colour of a method's lines.
fn colour(method: Method) -> RGBColor {
    match method {
        Method::Haphe => RGBColor(31, 119, 180),
        Method::Parry => RGBColor(214, 39, 40),
        Method::BruteForce => RGBColor(110, 110, 110),
    }
}

/// The marker of the `family`-th family, a polygon in pixels around `centre`: a disc, a
/// triangle, a diamond, then squares.
fn marker(family: usize, (cx, cy): (i32, i32)) -> Vec<(i32, i32)> {
    let offsets: Vec<(i32, i32)> = match family {
        0 => (0..12)
            .map(|k| {
                let a = f64::from(k) * std::f64::consts::TAU / 12.0;
                (
                    (4.5 * a.cos()).round() as i32,
                    (4.5 * a.sin()).round() as i32,
                )
            })
            .collect(),
        1 => vec![(0, -6), (5, 4), (-5, 4)],
        2 => vec![(0, -6), (5, 0), (0, 6), (-5, 0)],
        _ => vec![(-4, -4), (4, -4), (4, 4), (-4, 4)],
    };
    offsets.into_iter().map(|(x, y)| (cx + x, cy + y)).collect()
}

/// A plot's size in pixels.
const SIZE: (u32, u32) = (1000, 650);

fn draw(pixels: &mut [u8], query: Query, rows: &[&Record]) -> Result<(), Box<dyn Error>> {
    let at_least = |v: f64| {
        if v.is_finite() {
            v.max(SMALLEST_NS)
        } else {
            SMALLEST_NS
        }
    };
    let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, 0.0f64, f64::INFINITY, 0.0f64);
    for r in rows {
        x0 = x0.min(r.triangles as f64);
        x1 = x1.max(r.triangles as f64);
        y0 = y0.min(at_least(r.p50_ns));
        y1 = y1.max(at_least(r.p99_ns));
    }
    let mut families: Vec<&str> = Vec::new();
    for r in rows {
        if !families.contains(&r.family.as_str()) {
            families.push(&r.family);
        }
    }

    let root = BitMapBackend::with_buffer(pixels, SIZE).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(
            format!("{}: cost against triangle count", query.name()),
            ("sans-serif", 24),
        )
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(80)
        .build_cartesian_2d(
            (x0 / 1.5..x1 * 1.5).log_scale(),
            (y0 / 2.0..y1 * 2.0).log_scale(),
        )?;
    chart
        .configure_mesh()
        .x_desc("triangles")
        .y_desc(match query {
            Query::Build | Query::Decode | Query::Zones => "ns (solid: median, dashed: slowest)",
            _ => "ns per query (solid: p50, dashed: p99)",
        })
        .x_label_formatter(&|x| format!("{x:.0}"))
        .y_label_formatter(&|y| format!("{y:.0}"))
        .draw()?;

    for method in [Method::Haphe, Method::Parry, Method::BruteForce] {
        for (f, family) in families.iter().enumerate() {
            let mut points: Vec<(f64, f64, f64)> = rows
                .iter()
                .filter(|r| r.method == method && r.family == *family)
                .map(|r| (r.triangles as f64, at_least(r.p50_ns), at_least(r.p99_ns)))
                .collect();
            if points.is_empty() {
                continue;
            }
            points.sort_by(|a, b| a.0.total_cmp(&b.0));
            let c = colour(method);
            chart
                .draw_series(LineSeries::new(
                    points.iter().map(|&(x, p50, _)| (x, p50)),
                    c.stroke_width(2),
                ))?
                .label(format!("{} · {family}", method.name()))
                .legend(move |(x, y)| {
                    EmptyElement::at((x, y))
                        + PathElement::new(vec![(0, 0), (20, 0)], c.stroke_width(2))
                        + Polygon::new(marker(f, (10, 0)), c.filled())
                });
            chart.draw_series(DashedLineSeries::new(
                points.iter().map(|&(x, _, p99)| (x, p99)),
                6,
                4,
                c.stroke_width(1),
            ))?;
            chart.draw_series(points.iter().map(|&(x, p50, _)| {
                EmptyElement::at((x, p50)) + Polygon::new(marker(f, (0, 0)), c.filled())
            }))?;
        }
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperLeft)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font(("sans-serif", 15))
        .draw()?;
    root.present()?;
    Ok(())
}
