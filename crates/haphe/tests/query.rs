//! The accelerated queries against their brute-force oracles (small samples; `haphe verify`
//! runs the same checks at any size): segment crossing on random and adversarial segments
//! with zero leaks, inside/outside against winding numbers and parry, the surface walk.

mod support;

use haphe::DVec3;
use haphe::map::{MapOptions, VoxelMap};
use haphe::mesh::shapes::{self, Catalog};
use haphe::mesh::{Mesh, ReadOptions, Surface, SurfaceOptions, TriId, read_mesh, relative_height};
use haphe::verify::{SegmentKind, check_crossings, check_inside, check_walk, points};
use parry3d_f64::query::PointQuery;
use parry3d_f64::shape::{TriMesh, TriMeshFlags};

fn object(mesh: Mesh) -> (Surface, VoxelMap) {
    let surface = Surface::new(mesh, &SurfaceOptions::default()).expect("valid surface");
    let map = VoxelMap::build(&surface, &MapOptions::default()).expect("map");
    (surface, map)
}

/// Runs every check with `n` samples and asserts zero failures.
fn assert_verified(name: &str, surface: &Surface, map: &VoxelMap, n: usize) {
    for kind in SegmentKind::ALL {
        let c = check_crossings(surface, map, kind, n, 7);
        assert_eq!(c.mismatches, 0, "{name} {kind:?}: {c:?}");
        assert_eq!(c.leaks, 0, "{name} {kind:?}: {c:?}");
    }
    let i = check_inside(surface, map, n, 11);
    assert_eq!(i.mismatches, 0, "{name}: {i:?}");
    let size = surface.report().bounds_max[0] - surface.report().bounds_min[0];
    let w = check_walk(
        surface,
        n / 50 + 1,
        50,
        (0.05e-3 * size / 0.2, 0.5e-3 * size / 0.2),
        13,
    );
    assert_eq!(w.not_local_minimum, 0, "{name}: {w:?}");
    assert_eq!(w.not_nearest, 0, "{name}: {w:?}");
}

#[test]
fn procedural_shapes_agree_with_brute_force() {
    for shape in Catalog::ALL {
        let (surface, map) = object(shape.with_triangles(3_000));
        assert_verified(&shape.to_string(), &surface, &map, 300);
    }
}

#[test]
fn convex_shapes_walk_to_the_nearest_point() {
    for (name, mesh) in [
        ("sphere", shapes::sphere(0.1, 3)),
        (
            "box",
            shapes::cuboid(DVec3::new(0.1, 0.06, 0.03), [5, 4, 3]),
        ),
    ] {
        let (surface, _) = object(mesh);
        let w = check_walk(&surface, 20, 100, (0.05e-3, 0.5e-3), 5);
        assert!(w.convex, "{name} is convex");
        assert!(w.outside_walks > 500, "{name}: {w:?}");
        assert_eq!(
            (w.not_local_minimum, w.not_nearest),
            (0, 0),
            "{name}: {w:?}"
        );
    }
}

#[test]
fn inside_agrees_with_parry_on_solids() {
    for shape in Catalog::ALL {
        let (surface, map) = object(shape.with_triangles(2_000));
        let parry = TriMesh::with_flags(
            surface.vertices().to_vec(),
            surface.triangles().to_vec(),
            TriMeshFlags::ORIENTED,
        )
        .expect("parry accepts a closed manifold");
        for p in points(&surface, 500, 3) {
            let (side, _) = haphe::query::classify_point(&surface, &map, p);
            assert_eq!(
                side == haphe::query::Side::Inside,
                parry.contains_local_point(p),
                "{shape} at {p}"
            );
        }
    }
}

#[test]
fn real_models_agree_with_brute_force() {
    for (name, path) in support::model_files() {
        let bytes = std::fs::read(&path).expect("readable");
        let mesh = read_mesh(&name, &bytes, &ReadOptions::default()).expect("loads");
        // Brute force is O(n) per sample: fewer samples on bigger meshes.
        let n = (2_000_000 / mesh.triangles.len()).clamp(20, 300);
        let (surface, map) = object(mesh);
        assert_verified(&name, &surface, &map, n);
    }
}

/// Segments in a face's plane that `haphe verify` caught on the shared models (file units,
/// as `haphe verify` reads them): on the 20 mm cube a segment in the plane of a letter's
/// slanted wall, from outside to inside, found no crossing at all (fast and brute force
/// alike); on the cylinder the brute force reported a spurious hit on the face the segment
/// lies in, at a parameter far from that face, which the map walk did not find.
#[test]
fn in_face_plane_segments_leaked_or_mismatched_on_real_models() {
    let dir = support::meshes();
    let cases = [
        (
            "20mm-xyz-cube.stl",
            [-27.365356134556585, 3.6291185883881947, -17.800416795684125],
            [-29.006564376655447, 4.234349018985464, -18.77002064878383],
        ),
        (
            "cylinder.stl",
            [-0.7558967512048365, 0.6574683954123448, 1.0254928311390505],
            [-0.8205702903299557, 0.5702662515936672, 1.513563645110198],
        ),
        (
            "cylinder.stl",
            [0.7513037075884241, 0.6636613957556381, 5.1790648272541215],
            [0.8034119925317789, 0.5934015302952957, 5.671353642834729],
        ),
    ];
    for (name, p0, p1) in cases {
        let bytes = std::fs::read(dir.join("models").join(name)).expect("readable");
        let mesh = read_mesh(name, &bytes, &ReadOptions::default()).expect("loads");
        let (surface, map) = object(mesh);
        let (p0, p1) = (DVec3::from_array(p0), DVec3::from_array(p1));
        let oracle = haphe::verify::WindingOracle::new(&surface);
        let change = oracle.winding(p1) - oracle.winding(p0);
        let all = haphe::query::all_crossings_brute_force(&surface, p0, p1);
        let signed: i64 = all.iter().map(|c| if c.entering { 1 } else { -1 }).sum();
        assert_eq!(signed, change, "{name}: {all:?}");
        let fast = haphe::query::first_crossing(&surface, &map, p0, p1);
        let brute = haphe::query::first_crossing_brute_force(&surface, p0, p1);
        assert_eq!(fast, brute, "{name}");
        assert_eq!(fast, all.first().copied(), "{name}");
        if change != 0 {
            assert!(fast.is_some(), "{name}: a leak");
        }
    }
}

#[test]
fn in_face_plane_segments_on_procedural_shapes_agree_with_brute_force() {
    // More in-plane segments than the general check, on the shapes with flat faces.
    for shape in [Catalog::Box, Catalog::ThinPlate, Catalog::ConcaveCorner] {
        let (surface, map) = object(shape.with_triangles(2_000));
        let c = check_crossings(&surface, &map, SegmentKind::InFacePlane, 5_000, 17);
        assert_eq!((c.mismatches, c.leaks), (0, 0), "{shape}: {c:?}");
    }
}

#[test]
fn the_binned_winding_oracle_equals_the_generalised_winding_number() {
    // The verification oracle (ray parity over binned triangles) against the plain
    // generalised winding number over every triangle, on points all around each shape
    // and far away; points near the surface, where the solid angles round, are skipped.
    for shape in Catalog::ALL {
        let (surface, _) = object(shape.with_triangles(3_000));
        let oracle = haphe::verify::WindingOracle::new(&surface);
        let mut far = points(&surface, 200, 23);
        for p in &mut far {
            *p *= 50.0;
        }
        for p in points(&surface, 2_000, 19).into_iter().chain(far) {
            if haphe::verify::distance_to_surface(&surface, p) < 1e-6 {
                continue;
            }
            let plain = haphe::mesh::winding_number(&surface, p).round() as i64;
            assert_eq!(oracle.winding(p), plain, "{shape} at {p}");
        }
    }
}

/// A closed box of side 0.1 m whose top face is cut along its diagonal into slivers that
/// grow geometrically from a relative height of about 2e-8 (just above degenerate) at one
/// corner: where the frames behind the crossing prefilter are least accurate.
fn box_with_sliver_top() -> Mesh {
    let s = 0.1;
    let mut vertices = vec![
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(s, 0.0, 0.0),
        DVec3::new(s, s, 0.0),
        DVec3::new(0.0, s, 0.0),
        DVec3::new(0.0, 0.0, s),
        DVec3::new(s, 0.0, s),
        DVec3::new(s, s, s),
        DVec3::new(0.0, s, s),
    ];
    let mut triangles: Vec<[u32; 3]> = vec![
        [0, 1, 2],
        [0, 2, 3],
        [0, 1, 5],
        [0, 5, 4],
        [1, 2, 6],
        [1, 6, 5],
        [2, 3, 7],
        [2, 7, 6],
        [3, 0, 4],
        [3, 4, 7],
    ];
    // The top diagonal from corner 4 to corner 6, cut at 1 - 1e-8·2^k of its length.
    let (a, c) = (vertices[4], vertices[6]);
    let mut diagonal = vec![4u32];
    for k in (1..27).rev() {
        let f = 1.0 - 1e-8 * 2f64.powi(k);
        vertices.push(a + f * (c - a));
        diagonal.push(vertices.len() as u32 - 1);
    }
    diagonal.push(6);
    for pair in diagonal.windows(2) {
        triangles.push([pair[0], 5, pair[1]]);
        triangles.push([pair[0], pair[1], 7]);
    }
    // Every face outward (the box is convex).
    let centre = DVec3::splat(s / 2.0);
    for t in &mut triangles {
        let [p, q, r] = t.map(|v| vertices[v as usize]);
        if (q - p).cross(r - p).dot((p + q + r) / 3.0 - centre) < 0.0 {
            t.swap(1, 2);
        }
    }
    Mesh {
        vertices,
        triangles,
    }
}

#[test]
fn slivers_down_to_a_relative_height_of_2e_8_agree_with_brute_force() {
    let (surface, map) = object(box_with_sliver_top());
    assert!(surface.is_solid());
    let thinnest = (0..surface.triangle_count())
        .map(|t| {
            let [a, b, c] = surface.corners(TriId(t as u32));
            relative_height(a, b, c)
        })
        .fold(f64::INFINITY, f64::min);
    assert!(thinnest < 1e-7 && thinnest > 1e-9, "{thinnest}");
    for kind in SegmentKind::ALL {
        let c = check_crossings(&surface, &map, kind, 4_000, 23);
        assert_eq!((c.mismatches, c.leaks), (0, 0), "{kind:?}: {c:?}");
    }
}

/// Long segments across free space, which [`first_crossing`](haphe::query::first_crossing)
/// crosses by skipping the cubes of cells its clearances vouch for: the same triangle and
/// the same parameter, bit for bit, as the brute force. On meshes whose grids hold large
/// clearances (inside and around a sphere and blobs): random segments across the grown
/// bounding box and far beyond it, segments between points deep in free space (inside or
/// outside, several cells from any surface cell), segments grazing the surface (in a
/// triangle's plane through a point of it, and a hair above and below that plane), and,
/// for entering crossings only, the same segments again.
#[test]
fn long_segments_across_free_space_agree_with_brute_force() {
    use haphe::map::MAX_CLEARANCE;
    use haphe::query::{
        first_crossing, first_crossing_brute_force, first_crossing_brute_force_where,
        first_crossing_where,
    };
    use haphe::rng::SplitMix64;
    use haphe::verify::{bounds, segments};
    use rayon::prelude::*;

    let mut far_segments = 0;
    for (name, mesh, n) in [
        ("sphere-20k", Catalog::Sphere.with_triangles(20_000), 1_500),
        ("blob-50k", Catalog::Blob.with_triangles(50_000), 1_500),
        ("blob-200k", Catalog::Blob.with_triangles(200_000), 600),
    ] {
        let (surface, map) = object(mesh);
        let grid = map.grid();
        let (lo, hi, size) = bounds(&surface);
        let mut random = SplitMix64::new(0xDDA);
        // Points deep in free space: their cell is at least 6 cells from any surface cell.
        let mut free = Vec::new();
        while free.len() < 2 * n {
            let p = random.point_in(lo - 0.2 * size, hi + 0.2 * size);
            if grid.cell_of(p).is_some_and(|c| map.clearance(c) >= 6) {
                free.push(p);
            }
        }
        let mut cases: Vec<(DVec3, DVec3)> = free.chunks(2).map(|p| (p[0], p[1])).collect();
        cases.extend(segments(&surface, SegmentKind::Random, n, 3));
        cases.extend(segments(&surface, SegmentKind::Long, n / 4, 5));
        for _ in 0..n {
            let t = TriId(random.index(surface.triangle_count()) as u32);
            let [a, b, c] = surface.corners(t);
            let frame = surface.frame(t);
            let q = (a + b + c) / 3.0;
            let along = frame.normal.cross(random.unit_vector()).normalize_or(b - a);
            let lift = [0.0, 1e-9, -1e-9][random.index(3)] * size;
            let p = q + lift * frame.normal;
            cases.push((p - size * along, p + size * along));
        }
        // Most segments cross cells from which the walk skips several cells at once, and
        // the grid has some from which it skips the most.
        let vouched = cases
            .iter()
            .filter(|&&(p0, p1)| grid.walk(p0, p1).any(|s| map.clearance(s.cell) >= 4))
            .count();
        assert!(
            vouched * 2 > cases.len(),
            "{name}: {vouched} of {}",
            cases.len()
        );
        assert!(
            free.iter().any(|&p| grid
                .cell_of(p)
                .is_some_and(|c| map.clearance(c) == MAX_CLEARANCE)),
            "{name}"
        );
        // Bricks whose reach exceeds the clearance cap (skipped whole), counted over all.
        far_segments += cases
            .iter()
            .filter(|&&(p0, p1)| {
                grid.walk(p0, p1)
                    .any(|s| map.reach(s.cell) > u32::from(MAX_CLEARANCE))
            })
            .count();
        let bad: Vec<String> = cases
            .par_iter()
            .filter_map(|&(p0, p1)| {
                let fast = first_crossing(&surface, &map, p0, p1);
                let brute = first_crossing_brute_force(&surface, p0, p1);
                let entering = |hit: &haphe::query::SegmentHit| hit.entering;
                let fast_in = first_crossing_where(&surface, &map, p0, p1, entering);
                let brute_in = first_crossing_brute_force_where(&surface, p0, p1, entering);
                let same = |a: Option<haphe::query::Crossing>,
                            b: Option<haphe::query::Crossing>| {
                    a.map(|c| (c.triangle, c.t.to_bits())) == b.map(|c| (c.triangle, c.t.to_bits()))
                };
                (!same(fast, brute) || !same(fast_in, brute_in)).then(|| {
                    format!(
                        "{p0} → {p1}: {fast:?} / {brute:?}; entering {fast_in:?} / {brute_in:?}"
                    )
                })
            })
            .collect();
        assert!(
            bad.is_empty(),
            "{name}: {} of {} differ: {:?}",
            bad.len(),
            cases.len(),
            &bad[..bad.len().min(3)]
        );
    }
    assert!(
        far_segments > 1_000,
        "{far_segments} segments skip whole bricks"
    );
}

#[test]
fn the_spatial_order_changes_no_answer() {
    // A blob with its faces shuffled, as a mesh from a tool that reorders them comes: the
    // surface in spatial order and the one in the file's order give the same crossings
    // (the same face of the file, the same parameter and point) and the same sides.
    let mut mesh = Catalog::Blob.with_triangles(5_000);
    shapes::shuffle_faces(&mut mesh, 3);
    let (sorted, sorted_map) = object(mesh.clone());
    let options = SurfaceOptions {
        spatial_order: false,
        ..SurfaceOptions::default()
    };
    let plain = Surface::new(mesh, &options).expect("valid surface");
    let plain_map = VoxelMap::build(&plain, &MapOptions::default()).expect("map");
    assert!(
        plain
            .source_triangles()
            .iter()
            .enumerate()
            .all(|(t, &s)| s == t as u32)
    );
    assert_ne!(sorted.triangles(), plain.triangles());
    let mut hits = 0;
    for kind in SegmentKind::ALL {
        for (p0, p1) in haphe::verify::segments(&plain, kind, 300, 3) {
            let a = haphe::query::first_crossing(&sorted, &sorted_map, p0, p1);
            let b = haphe::query::first_crossing(&plain, &plain_map, p0, p1);
            assert_eq!(a.is_some(), b.is_some(), "{kind:?} {p0} {p1}");
            if let (Some(a), Some(b)) = (a, b) {
                assert_eq!(sorted.source_triangle(a.triangle), b.triangle.0);
                assert_eq!((a.t, a.point, a.entering), (b.t, b.point, b.entering));
                hits += 1;
            }
        }
    }
    assert!(hits > 300, "{hits}");
    for p in points(&plain, 2_000, 5) {
        assert_eq!(
            haphe::query::classify_point(&sorted, &sorted_map, p).0,
            haphe::query::classify_point(&plain, &plain_map, p).0,
            "{p}"
        );
    }
}
