//! A refreshed map equals, array for array, the map a build makes of the deformed surface
//! on the same grid: on every procedural shape and two real models, under deformations
//! from none to every vertex, one after another.

use glam::DVec3;

use super::super::build::build_on_grid;
use super::super::{MapOptions, VoxelMap};
use crate::mesh::shapes::Catalog;
use crate::mesh::{ReadOptions, Surface, SurfaceOptions, read_mesh};
use crate::rng::SplitMix64;

/// Asserts that `a` (refreshed) and `b` (built) are equal, naming the first field that
/// differs and where.
fn assert_same(a: &VoxelMap, b: &VoxelMap, context: &str) {
    fn first<T: PartialEq + std::fmt::Debug>(name: &str, a: &[T], b: &[T], context: &str) {
        if a == b {
            return;
        }
        let at = a.iter().zip(b).position(|(x, y)| x != y);
        match at {
            Some(i) => panic!(
                "{context}: {name} differ at {i} of {}/{}: {:?} ≠ {:?}",
                a.len(),
                b.len(),
                a[i],
                b[i]
            ),
            None => panic!("{context}: {name} lengths {} ≠ {}", a.len(), b.len()),
        }
    }
    assert_eq!(a.grid, b.grid, "{context}: grid");
    assert_eq!(a.brick_dims, b.brick_dims, "{context}: brick_dims");
    first("surface_bits", &a.surface_bits, &b.surface_bits, context);
    first(
        "surface_before",
        &a.surface_before,
        &b.surface_before,
        context,
    );
    first("surface_first", &a.surface_first, &b.surface_first, context);
    first(
        "triangle_start",
        &a.triangle_start,
        &b.triangle_start,
        context,
    );
    first("inside_bits", &a.inside_bits, &b.inside_bits, context);
    first(
        "overlap_bricks",
        &a.overlap_bricks,
        &b.overlap_bricks,
        context,
    );
    first("overlap_bits", &a.overlap_bits, &b.overlap_bits, context);
    first("bricks", &a.bricks, &b.bricks, context);
    first("clearances", &a.clearances, &b.clearances, context);
    first("free_bricks", &a.free_bricks, &b.free_bricks, context);
    first("slabs", &a.slabs, &b.slabs, context);
    first("brick_slabs", &a.brick_slabs, &b.brick_slabs, context);
    first("region_slabs", &a.region_slabs, &b.region_slabs, context);
    first("triangle_refs", &a.triangle_refs, &b.triangle_refs, context);
    assert_eq!(a.free_regions, b.free_regions, "{context}: free_regions");
    assert_eq!(
        a.triangle_count, b.triangle_count,
        "{context}: triangle_count"
    );
    assert_eq!(a.solid, b.solid, "{context}: solid");
    assert_eq!(
        a.cell_size_rule, b.cell_size_rule,
        "{context}: cell_size_rule"
    );
    assert!(a.provenance.is_none(), "{context}: provenance");
    assert_eq!(a, b, "{context}");
}

/// A surface with its map, deformed step by step, each refreshed map checked against a
/// build on its grid.
struct Shape {
    name: String,
    surface: Surface,
    map: VoxelMap,
    /// Whether a refresh so far left the grid (a rebuild on a grown grid).
    grew: bool,
    /// Overlap cells seen in a refreshed map.
    overlaps: usize,
}

impl Shape {
    fn new(name: &str, surface: Surface) -> Shape {
        let map = VoxelMap::build(&surface, &MapOptions::default()).expect("a map");
        Shape {
            name: name.to_string(),
            surface,
            map,
            grew: false,
            overlaps: 0,
        }
    }

    fn h(&self) -> f64 {
        self.map.grid().cell_size()
    }

    fn centre(&self) -> DVec3 {
        let (lo, hi) = self.surface.bounds();
        0.5 * (lo + hi)
    }

    /// Moves the vertices to `vertices`, refreshes the map and compares it with a build.
    fn deform(&mut self, what: &str, vertices: Vec<DVec3>) {
        let (surface, moved) = self.surface.deformed(vertices);
        let map = self
            .map
            .refreshed(&self.surface, &surface, &moved)
            .expect("a refreshed map");
        self.grew |= map.grid != self.map.grid;
        let built = build_on_grid(&surface, map.grid, map.cell_size_rule, &|_| {}).expect("built");
        assert_same(&map, &built, &format!("{}, {what}", self.name));
        if map.grid == self.map.grid {
            // The local refresh, also where most triangles moved (`refreshed` builds).
            let local = self
                .map
                .refreshed_here(&self.surface, &surface, &moved)
                .expect("a refreshed map");
            assert_same(&local, &built, &format!("{}, {what}, local", self.name));
        }
        self.overlaps += map.overlap_bricks.len();
        self.surface = surface;
        self.map = map;
    }

    fn vertices(&self) -> Vec<DVec3> {
        self.surface.vertices().to_vec()
    }

    /// The usual sequence: no move, shrinking (which leaves room in the grid), one
    /// vertex, a dent, 1 % and 30 % jittered, breathing in and out, all jittered.
    fn run_all(&mut self, random: &mut SplitMix64) {
        self.deform("no move", self.vertices());
        self.deform("shrunk (×0.8)", self.scaled(0.8));
        let mut v = self.vertices();
        let i = random.index(v.len());
        v[i] += DVec3::new(0.3, -0.2, 0.25) * self.h();
        self.deform("one vertex", v);
        self.dent(random, 0.15);
        self.jitter(random, 0.01, 0.4);
        self.jitter(random, 0.3, 0.3);
        self.deform("breathing in (×0.85)", self.scaled(0.85));
        self.deform("breathing out (×1.15)", self.scaled(1.15));
        // Back where it was, as a refresh of a refresh of ...
        self.jitter(random, 1.0, 0.2);
    }

    /// The vertices scaled by `s` about the centre.
    fn scaled(&self, s: f64) -> Vec<DVec3> {
        let c = self.centre();
        self.vertices().iter().map(|&p| c + (p - c) * s).collect()
    }

    /// Vertices within `radius` (a fraction of the extent) of a random vertex pushed
    /// toward the centre by 30 % of the radius, less toward the rim.
    fn dent(&mut self, random: &mut SplitMix64, radius: f64) {
        let (lo, hi) = self.surface.bounds();
        let r = radius * (hi - lo).max_element();
        let mut v = self.vertices();
        let at = v[random.index(v.len())];
        let c = self.centre();
        for p in &mut v {
            let d = p.distance(at);
            if d < r {
                *p += (c - *p).normalize_or_zero() * 0.3 * r * (1.0 - d / r);
            }
        }
        self.deform("a dent", v);
    }

    /// A fraction `share` of the vertices moved by up to `amount` cells along each axis.
    fn jitter(&mut self, random: &mut SplitMix64, share: f64, amount: f64) {
        let h = self.h();
        let mut v = self.vertices();
        for p in &mut v {
            if random.next_unit() < share {
                *p += DVec3::new(
                    random.range(-amount, amount),
                    random.range(-amount, amount),
                    random.range(-amount, amount),
                ) * h;
            }
        }
        self.deform(&format!("{share} jittered"), v);
    }
}

fn surface_of(shape: Catalog, triangles: usize) -> Surface {
    Surface::new(shape.with_triangles(triangles), &SurfaceOptions::default()).expect("a surface")
}

/// Every procedural shape, at two sizes, under the usual sequence of deformations.
#[test]
fn refreshed_maps_equal_builds_on_every_shape() {
    let mut random = SplitMix64::new(0xDEF0);
    for shape in Catalog::ALL {
        for triangles in [2_000, 20_000] {
            let mut s = Shape::new(
                &format!("{shape:?} {triangles}"),
                surface_of(shape, triangles),
            );
            s.run_all(&mut random);
            // The plate, 0.1 mm thick, leaves its grid at the first jitter; the
            // refreshes after are made on the grown grid.
            assert_eq!(s.grew, shape == Catalog::ThinPlate, "{}", s.name);
        }
    }
}

/// The small real models, under the usual sequence.
#[test]
fn refreshed_maps_equal_builds_on_real_models() {
    let mut random = SplitMix64::new(0x5907);
    for file in ["spot.obj", "20mm-xyz-cube.stl", "fuze.ply"] {
        let path = format!("{}/../../meshes/models/{file}", env!("CARGO_MANIFEST_DIR"));
        let bytes = std::fs::read(&path).expect("the model");
        let mesh = read_mesh(file, &bytes, &ReadOptions::default()).expect("a mesh");
        let surface = Surface::new(mesh, &SurfaceOptions::default()).expect("a surface");
        let mut s = Shape::new(file, surface);
        s.run_all(&mut random);
    }
}

/// A fold: the top of a shape pushed down through its bottom, so that the surface
/// passes through itself (cells of winding number −1 or 2), and back. The shape first
/// shrinks, to leave room in its grid.
#[test]
fn a_fold_through_itself_equals_a_build() {
    for shape in [Catalog::Sphere, Catalog::Blob, Catalog::Torus] {
        let mut s = Shape::new(&format!("{shape:?} fold"), surface_of(shape, 5_000));
        s.deform("shrunk (×0.8)", s.scaled(0.8));
        let (lo, hi) = s.surface.bounds();
        let height = hi.z - lo.z;
        let original = s.vertices();
        for depth in [0.5, 0.95, 0.9] {
            let v = original
                .iter()
                .map(|&p| {
                    if p.z > hi.z - 0.1 * height {
                        p - DVec3::Z * depth * height
                    } else {
                        p
                    }
                })
                .collect();
            s.deform(&format!("fold {depth}"), v);
        }
        s.deform("unfolded", original);
        assert!(!s.grew, "{}: left the grid", s.name);
        if shape == Catalog::Sphere {
            assert!(s.overlaps > 0, "{}: no overlap cells", s.name);
        }
    }
}

/// A thin plate bent back and forth (on a grid grown by a first large bend), so that
/// cells switch between surface and outside and bricks between uniform and detailed.
#[test]
fn a_bent_plate_equals_a_build() {
    let mut s = Shape::new("plate", surface_of(Catalog::ThinPlate, 8_000));
    let original = s.vertices();
    let (lo, hi) = s.surface.bounds();
    let width = hi.x - lo.x;
    let bend = |amplitude: f64| -> Vec<DVec3> {
        original
            .iter()
            .map(|&p| {
                let x = (p.x - lo.x) / width;
                p + DVec3::Z * amplitude * width * (x * x - 0.5 * x)
            })
            .collect()
    };
    s.deform("large bend (grown grid)", bend(0.4));
    assert!(s.grew, "the first bend leaves the grid");
    s.grew = false;
    for amplitude in [0.3, 0.1, 0.0, -0.05, 0.2, 0.38] {
        s.deform(&format!("bend {amplitude}"), bend(amplitude));
    }
    assert!(!s.grew, "the bends stay in the grown grid");
}

/// Breathing out past the grid takes the grown grid, and equals a build on it.
#[test]
fn leaving_the_grid_rebuilds_on_a_grown_grid() {
    let mut s = Shape::new("sphere", surface_of(Catalog::Sphere, 2_000));
    s.deform("×1.15", s.scaled(1.15));
    assert!(s.grew);
}
