//! Writes the Rust library's answers to inside and first-crossing queries on a mesh, for
//! the C API's check (`crates/haphe-c/check/answers.c`, run by `.ci/run`): the C program
//! asks `haphe_shape_inside` and `haphe_shape_first_crossing` the same questions and
//! requires the same answers, bit for bit.
//!
//! ```sh
//! cargo run -p haphe-c --example c_answers -- meshes/models/spot.obj > answers.txt
//! ```
//!
//! The shape is built as `haphe_shape_from_file(path, 1.0, …)` builds it (exact weld,
//! metres, default surface and map options). The points: a jittered grid over the mesh's
//! bounding box grown by a tenth, and points a hair (1e-6 of the box's diagonal) in front
//! of and behind every 7th triangle's centroid. The segments: between random points of
//! the grown box, through every 11th vertex, and through the midpoint of an edge of every
//! 13th triangle (the watertight cases: a segment through an edge or a corner meets one
//! triangle). Numbers are written in Rust's shortest round-trip form, which `strtod`
//! reads back to the same `double`.

use std::fmt::Write as _;

use haphe_lib::DVec3;
use haphe_lib::map::MapOptions;
use haphe_lib::mesh::{
    ReadOptions, Surface, SurfaceOptions, TriId, Units, VertId, Weld, read_mesh_with_stats,
};
use haphe_lib::query::{Side, classify_point, first_crossing};
use haphe_lib::scene::Shape;

/// A small deterministic generator (SplitMix64), so the file is the same on every run.
struct Draw(u64);

impl Draw {
    fn unit(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }

    fn point_in(&mut self, lo: DVec3, hi: DVec3) -> DVec3 {
        DVec3::new(self.unit(), self.unit(), self.unit()) * (hi - lo) + lo
    }
}

fn v(p: DVec3) -> String {
    format!("{:?} {:?} {:?}", p.x, p.y, p.z)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = std::env::args()
        .nth(1)
        .ok_or("usage: c_answers MESH (writes the answers to standard output)")?;
    let bytes = std::fs::read(&path).map_err(|e| format!("cannot read {path}: {e}"))?;
    let options = ReadOptions {
        units: Units::Factor(1.0),
        weld: Weld::Exact,
        format: None,
    };
    let mesh = read_mesh_with_stats(&path, &bytes, &options)?.mesh;
    let surface = Surface::new(mesh, &SurfaceOptions::default())?;
    let shape = Shape::build(surface, &MapOptions::default())?;
    let (surface, map) = (shape.surface(), shape.map());
    let (lo, hi) = surface.bounds();
    let grow = (hi - lo) * 0.1;
    let (lo, hi) = (lo - grow, hi + grow);
    let hair = 1e-6 * (hi - lo).length();
    let mut draw = Draw(0x5EED);

    let mut points = Vec::new();
    let n = 12;
    for i in 0..n {
        for j in 0..n {
            for k in 0..n {
                let cell = DVec3::new(i as f64, j as f64, k as f64);
                let jitter = DVec3::new(draw.unit(), draw.unit(), draw.unit());
                points.push(lo + (cell + jitter) / n as f64 * (hi - lo));
            }
        }
    }
    for t in (0..surface.triangle_count()).step_by(7) {
        let t = TriId(t as u32);
        let [a, b, c] = surface.corners(t);
        let centroid = (a + b + c) / 3.0;
        let normal = surface.frame(t).normal;
        points.push(centroid + hair * normal);
        points.push(centroid - hair * normal);
    }

    let mut segments = Vec::new();
    for _ in 0..2000 {
        segments.push((draw.point_in(lo, hi), draw.point_in(lo, hi)));
    }
    let through = |draw: &mut Draw, p: DVec3| {
        let dir = (draw.point_in(lo, hi) - p).normalize_or_zero();
        (
            p - 0.3 * (hi - lo).length() * dir,
            p + 0.3 * (hi - lo).length() * dir,
        )
    };
    for i in (0..surface.vertex_count()).step_by(11) {
        let p = surface.vertex(VertId(i as u32));
        segments.push(through(&mut draw, p));
    }
    for t in (0..surface.triangle_count()).step_by(13) {
        let [a, b, _] = surface.corners(TriId(t as u32));
        segments.push(through(&mut draw, 0.5 * (a + b)));
    }

    let mut out = String::new();
    writeln!(out, "haphe-c-answers 1")?;
    let inside: Vec<bool> = points
        .iter()
        .map(|&p| classify_point(surface, map, p).0 == Side::Inside)
        .collect();
    writeln!(
        out,
        "inside {} {}",
        points.len(),
        inside.iter().filter(|&&i| i).count()
    )?;
    for (p, i) in points.iter().zip(&inside) {
        writeln!(out, "{} {}", v(*p), u8::from(*i))?;
    }
    let hits: Vec<_> = segments
        .iter()
        .map(|&(a, b)| first_crossing(surface, map, a, b))
        .collect();
    writeln!(
        out,
        "crossing {} {}",
        segments.len(),
        hits.iter().filter(|h| h.is_some()).count()
    )?;
    for ((a, b), h) in segments.iter().zip(&hits) {
        match h {
            Some(c) => writeln!(
                out,
                "{} {} {:?} {} {} {} {}",
                v(*a),
                v(*b),
                c.t,
                surface.source_triangle(c.triangle),
                u8::from(c.entering),
                v(c.point),
                v(c.face_normal)
            )?,
            None => writeln!(out, "{} {} none", v(*a), v(*b))?,
        }
    }
    print!("{out}");
    Ok(())
}
