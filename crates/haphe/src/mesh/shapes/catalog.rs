//! [`Catalog`]: the generator families at a typical haptic size, sized by a triangle budget.

use std::fmt;
use std::str::FromStr;

use glam::DVec3;

use crate::mesh::Mesh;

use super::{
    MAX_CONCAVE_CORNER_DIVISIONS, MAX_CUBOID_DIVISIONS, MAX_SPHERE_FREQUENCY, MAX_TORUS_SEGMENTS,
    MIN_TORUS_SEGMENTS, concave_corner, cuboid, geodesic_blob, geodesic_sphere, thin_plate, torus,
};

/// Sphere and blob radius, metres.
const SPHERE_RADIUS_M: f64 = 0.1;
/// Torus ring and tube radii, metres.
const TORUS_MAJOR_RADIUS_M: f64 = 0.07;
const TORUS_MINOR_RADIUS_M: f64 = 0.03;
/// Box half extents, metres.
const BOX_HALF_EXTENTS_M: DVec3 = DVec3::new(0.1, 0.075, 0.05);
/// Thin plate width (x), depth (y) and thickness (z), metres.
const PLATE_WIDTH_M: f64 = 0.2;
const PLATE_DEPTH_M: f64 = 0.2;
const PLATE_THICKNESS_M: f64 = 0.0001;
/// Concave-corner cube edge, metres.
const CONCAVE_CORNER_SIZE_M: f64 = 0.2;
/// Blob noise amplitude, metres, and seed.
const BLOB_AMPLITUDE_M: f64 = 0.02;
const BLOB_SEED: u64 = 0x005E_ED0F_B10B;

/// A procedural solid at a typical haptic size (about 0.2 m across, centred on the origin
/// of its object frame), for benchmarks, the command-line tool and the demo.
///
/// Names, as [`Display`](fmt::Display) writes them and [`FromStr`] reads them: `sphere`,
/// `torus`, `box`, `thin-plate`, `concave-corner`, `blob`.
///
/// # Examples
/// ```
/// use haphe::mesh::shapes::Catalog;
/// let shape: Catalog = "concave-corner".parse().expect("a known name");
/// let mesh = shape.with_triangles(10_000);
/// assert_eq!(mesh.triangles.len(), shape.closest_triangle_count(10_000));
/// assert_eq!(mesh.triangles.len(), 9408); // 48·14²
/// assert_eq!(shape.to_string(), "concave-corner");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Catalog {
    /// A [`geodesic_sphere`] of radius 0.1 m: `20·f²` triangles.
    Sphere,
    /// A [`torus`] around the z axis, ring radius 0.07 m and tube radius 0.03 m (0.2 m
    /// across, 0.06 m tall): `2·M·m` triangles, with about 7/3 as many segments around the
    /// ring as around the tube so that cells are roughly square.
    Torus,
    /// A [`cuboid`] of 0.2 × 0.15 × 0.1 m (x, y, z): `4·(dx·dy + dy·dz + dz·dx)`
    /// triangles, with divisions in proportion to the sides so that cells are roughly
    /// square.
    Box,
    /// A [`thin_plate`] of 0.2 × 0.2 m (x, y), 0.1 mm thick (z): `4·n² + 8·n` triangles.
    ThinPlate,
    /// A [`concave_corner`] block: a 0.2 m cube with the octant `x, y, z > 0` removed, its
    /// concave corner at the origin: `48·d²` triangles.
    ConcaveCorner,
    /// A [`geodesic_blob`] of radius 0.1 m, noise amplitude 0.02 m and seed `0x5EED0FB10B`:
    /// `20·f²` triangles.
    Blob,
}

/// The most triangles a built-in shape may be asked for in a front end (a binary STL of
/// 500 MB); [`Catalog::check_triangles`].
pub const MAX_SHAPE_TRIANGLES: usize = 10_000_000;

impl Catalog {
    /// Every shape, in the order of the enum.
    pub const ALL: [Catalog; 6] = [
        Catalog::Sphere,
        Catalog::Torus,
        Catalog::Box,
        Catalog::ThinPlate,
        Catalog::ConcaveCorner,
        Catalog::Blob,
    ];

    /// Triangle budgets above this are clamped to it by [`Catalog::with_triangles`]: about
    /// 1.6 GB of mesh.
    pub const MAX_TRIANGLES: usize = 1 << 26;

    /// The name of the shape, as used on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Catalog::Sphere => "sphere",
            Catalog::Torus => "torus",
            Catalog::Box => "box",
            Catalog::ThinPlate => "thin-plate",
            Catalog::ConcaveCorner => "concave-corner",
            Catalog::Blob => "blob",
        }
    }

    /// The shape at the resolution whose triangle count is closest to `target` (ties go
    /// to the rounder cells, then to the fewer triangles). For the torus and the box, whose
    /// resolution has several parameters, only resolutions with roughly square cells are
    /// considered (segment or division ratios within a factor of about two of the
    /// proportional ones), which still leaves the count within a fraction of a percent of
    /// any target above a few thousand. `target` is clamped to [`Catalog::MAX_TRIANGLES`];
    /// below the coarsest mesh of the family (12 to 48 triangles) the coarsest is returned.
    ///
    /// Deterministic: the same shape and target give the same mesh.
    ///
    /// # Performance
    /// Linear in the triangle count; about 4 million triangles take a fraction of a second
    /// in a release build.
    pub fn with_triangles(self, target: usize) -> Mesh {
        self.with_triangles_unchecked(target)
    }

    /// Checks a triangle count asked of a built-in shape: at least 1 and at most
    /// [`MAX_SHAPE_TRIANGLES`] (front ends call this before building, so a typing mistake
    /// is an error instead of minutes and gigabytes).
    ///
    /// # Errors
    /// A sentence naming the count and the limit.
    pub fn check_triangles(target: usize) -> Result<usize, String> {
        if (1..=MAX_SHAPE_TRIANGLES).contains(&target) {
            Ok(target)
        } else {
            Err(format!(
                "a built-in shape has from 1 to {MAX_SHAPE_TRIANGLES} triangles, not {target}"
            ))
        }
    }

    fn with_triangles_unchecked(self, target: usize) -> Mesh {
        match self.resolution_for(target) {
            Resolution::Sphere { frequency } => geodesic_sphere(SPHERE_RADIUS_M, frequency),
            Resolution::Torus { ring, tube } => {
                torus(TORUS_MAJOR_RADIUS_M, TORUS_MINOR_RADIUS_M, ring, tube)
            }
            Resolution::Box { divisions } => cuboid(BOX_HALF_EXTENTS_M, divisions),
            Resolution::ThinPlate { divisions } => {
                thin_plate(PLATE_WIDTH_M, PLATE_DEPTH_M, PLATE_THICKNESS_M, divisions)
            }
            Resolution::ConcaveCorner { divisions } => {
                concave_corner(CONCAVE_CORNER_SIZE_M, divisions)
            }
            Resolution::Blob { frequency } => {
                geodesic_blob(SPHERE_RADIUS_M, frequency, BLOB_AMPLITUDE_M, BLOB_SEED)
            }
        }
    }

    /// The number of triangles [`Catalog::with_triangles`] gives for `target`, without
    /// building the mesh.
    pub fn closest_triangle_count(self, target: usize) -> usize {
        self.resolution_for(target).triangle_count()
    }

    fn resolution_for(self, target: usize) -> Resolution {
        let target = target.min(Catalog::MAX_TRIANGLES);
        match self {
            Catalog::Sphere => Resolution::Sphere {
                frequency: sphere_frequency_for(target),
            },
            Catalog::Blob => Resolution::Blob {
                frequency: sphere_frequency_for(target),
            },
            Catalog::Torus => torus_resolution_for(target),
            Catalog::Box => box_resolution_for(target),
            Catalog::ThinPlate => {
                // 4n² + 8n = target  ⇔  n = √(1 + target/4) − 1
                let estimate = (1.0 + target as f64 / 4.0).sqrt() - 1.0;
                let divisions = closest_single(
                    target,
                    estimate,
                    MAX_CUBOID_DIVISIONS,
                    Resolution::plate_triangles,
                );
                Resolution::ThinPlate { divisions }
            }
            Catalog::ConcaveCorner => {
                let estimate = (target as f64 / 48.0).sqrt();
                let divisions =
                    closest_single(target, estimate, MAX_CONCAVE_CORNER_DIVISIONS, |d| {
                        48 * d as usize * d as usize
                    });
                Resolution::ConcaveCorner { divisions }
            }
        }
    }
}

impl fmt::Display for Catalog {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Catalog {
    type Err = ParseShapeError;

    /// Reads a shape name (`sphere`, `torus`, `box`, `thin-plate`, `concave-corner`,
    /// `blob`), exactly as [`Catalog::name`] writes it.
    fn from_str(name: &str) -> Result<Catalog, ParseShapeError> {
        Catalog::ALL
            .into_iter()
            .find(|shape| shape.name() == name)
            .ok_or_else(|| ParseShapeError {
                name: name.to_owned(),
            })
    }
}

/// A shape name that [`Catalog::from_str`] does not know.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error(
    "unknown shape '{name}' (expected one of: sphere, torus, box, thin-plate, concave-corner, blob){}",
    crate::names::did_you_mean(name, &Catalog::ALL.map(Catalog::name))
)]
pub struct ParseShapeError {
    /// The name as given.
    pub name: String,
}

/// The resolution parameters of one shape family.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Resolution {
    Sphere { frequency: u32 },
    Torus { ring: u32, tube: u32 },
    Box { divisions: [u32; 3] },
    ThinPlate { divisions: u32 },
    ConcaveCorner { divisions: u32 },
    Blob { frequency: u32 },
}

impl Resolution {
    fn triangle_count(self) -> usize {
        match self {
            Resolution::Sphere { frequency } | Resolution::Blob { frequency } => {
                20 * frequency as usize * frequency as usize
            }
            Resolution::Torus { ring, tube } => 2 * ring as usize * tube as usize,
            Resolution::Box { divisions } => box_triangles(divisions),
            Resolution::ThinPlate { divisions } => Resolution::plate_triangles(divisions),
            Resolution::ConcaveCorner { divisions } => 48 * divisions as usize * divisions as usize,
        }
    }

    fn plate_triangles(divisions: u32) -> usize {
        box_triangles([divisions, divisions, 1])
    }
}

fn box_triangles([dx, dy, dz]: [u32; 3]) -> usize {
    let [dx, dy, dz] = [dx as usize, dy as usize, dz as usize];
    4 * (dx * dy + dy * dz + dz * dx)
}

/// The best resolution offered so far: the triangle count nearest the target, then the
/// smallest cell shape error (0 for square cells), then the fewest triangles, then the
/// first offered, so ties resolve the same way every time.
struct Closest<R> {
    target: usize,
    best: R,
    key: (usize, f64, usize),
}

impl<R: Copy> Closest<R> {
    fn new(target: usize, first: R, count: usize, shape_error: f64) -> Closest<R> {
        Closest {
            target,
            best: first,
            key: (count.abs_diff(target), shape_error, count),
        }
    }

    fn offer(&mut self, candidate: R, count: usize, shape_error: f64) {
        let key = (count.abs_diff(self.target), shape_error, count);
        if key.partial_cmp(&self.key) == Some(std::cmp::Ordering::Less) {
            self.best = candidate;
            self.key = key;
        }
    }
}

/// The value in `1..=max`, near the real `estimate`, whose `count` is closest to `target`
/// (the smaller on a tie). `count` must grow with the value.
fn closest_single(target: usize, estimate: f64, max: u32, count: impl Fn(u32) -> usize) -> u32 {
    let centre = estimate.clamp(1.0, f64::from(max)) as u32;
    let mut closest = Closest::new(target, 1, count(1), 0.0);
    for value in centre.saturating_sub(1).max(1)..=centre.saturating_add(2).min(max) {
        closest.offer(value, count(value), 0.0);
    }
    closest.best
}

fn sphere_frequency_for(target: usize) -> u32 {
    let estimate = (target as f64 / 20.0).sqrt();
    closest_single(target, estimate, MAX_SPHERE_FREQUENCY, |f| {
        20 * f as usize * f as usize
    })
}

/// Segments around the ring and the tube: as close to the target as possible, with about
/// `R/r` times as many around the ring as around the tube (square cells at the tube's
/// centre line), within a factor of two of that ratio.
fn torus_resolution_for(target: usize) -> Resolution {
    let ideal_ratio = TORUS_MAJOR_RADIUS_M / TORUS_MINOR_RADIUS_M;
    let count = |ring: u32, tube: u32| 2 * ring as usize * tube as usize;
    let shape_error =
        |ring: u32, tube: u32| (f64::from(ring) / f64::from(tube) / ideal_ratio).ln().abs();
    let (min, max) = (MIN_TORUS_SEGMENTS, MAX_TORUS_SEGMENTS);
    let tube_estimate = (target as f64 / (2.0 * ideal_ratio)).sqrt();
    let tube_low = (tube_estimate / 2f64.sqrt())
        .floor()
        .clamp(f64::from(min), f64::from(max)) as u32;
    let tube_high = (tube_estimate * 2f64.sqrt())
        .ceil()
        .clamp(f64::from(min), f64::from(max)) as u32;

    let mut closest = Closest::new(target, (min, min), count(min, min), shape_error(min, min));
    for tube in tube_low..=tube_high {
        let ring_estimate = target as f64 / (2.0 * f64::from(tube));
        let ring_floor = ring_estimate.floor().clamp(f64::from(min), f64::from(max)) as u32;
        for ring in [ring_floor, ring_floor.saturating_add(1).min(max)] {
            closest.offer((ring, tube), count(ring, tube), shape_error(ring, tube));
        }
    }
    let (ring, tube) = closest.best;
    Resolution::Torus { ring, tube }
}

/// Divisions along x, y, z: as close to the target as possible, with cells near square
/// (each division within two of the proportional value).
fn box_resolution_for(target: usize) -> Resolution {
    let sides = 2.0 * BOX_HALF_EXTENTS_M;
    // With d = s·sides, the count is 4·s²·(xy + yz + zx).
    let pair_sum = sides.x * sides.y + sides.y * sides.z + sides.z * sides.x;
    let scale = (target as f64 / (4.0 * pair_sum)).sqrt();
    let shape_error = |divisions: [u32; 3]| {
        let cell = sides / DVec3::from_array(divisions.map(f64::from));
        (cell.max_element() / cell.min_element()).ln()
    };
    let around = |axis: usize| {
        let centre = (scale * sides[axis])
            .round()
            .clamp(1.0, f64::from(MAX_CUBOID_DIVISIONS)) as u32;
        centre.saturating_sub(2).max(1)..=centre.saturating_add(2).min(MAX_CUBOID_DIVISIONS)
    };
    let first = [1, 1, 1];
    let mut closest = Closest::new(target, first, box_triangles(first), shape_error(first));
    for dx in around(0) {
        for dy in around(1) {
            for dz in around(2) {
                let divisions = [dx, dy, dz];
                closest.offer(divisions, box_triangles(divisions), shape_error(divisions));
            }
        }
    }
    Resolution::Box {
        divisions: closest.best,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn predicted_counts_match_the_meshes() {
        for shape in Catalog::ALL {
            for target in [0, 1, 13, 50, 100, 777, 2_000, 12_345] {
                assert_eq!(
                    shape.with_triangles(target).triangles.len(),
                    shape.closest_triangle_count(target),
                    "{shape} at {target}"
                );
            }
        }
    }

    #[test]
    fn single_parameter_choice_is_the_closest_of_all() {
        for target in [0, 5, 20, 79, 80, 81, 1_000, 54_321, 4_000_000] {
            let chosen = sphere_frequency_for(target);
            let best = (1..=2_000u32)
                .map(|f| 20 * (f as usize).pow(2))
                .map(|count| count.abs_diff(target))
                .min()
                .unwrap_or(usize::MAX);
            assert_eq!(
                (20 * (chosen as usize).pow(2)).abs_diff(target),
                best,
                "target {target}"
            );
        }
    }

    #[test]
    fn huge_targets_are_clamped() {
        for shape in Catalog::ALL {
            let count = shape.closest_triangle_count(usize::MAX);
            assert!(
                count <= Catalog::MAX_TRIANGLES * 11 / 10,
                "{shape}: {count}"
            );
        }
    }
}
