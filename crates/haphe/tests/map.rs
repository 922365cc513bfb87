//! The voxel map against independent references: a dense map built the plain way, the
//! generalised winding number, brute-force clearance, exact overlap; determinism, the
//! memory budget, and saving and loading (including damaged and crafted files).

use std::sync::OnceLock;

use haphe::DVec3;
use haphe::map::{
    CellSizeRule, CellState, FORMAT_VERSION, Grid, MAX_CLEARANCE, MAX_SOURCE_NAME_BYTES, MapBytes,
    MapError, MapFileError, MapOptions, OVERLAP_TOLERANCE_REL, Provenance, VoxelMap, decode,
    decode_in_place, encode, overlap_triangle_box,
};
use haphe::mesh::shapes::{self, Catalog};
use haphe::mesh::{Mesh, Surface, SurfaceOptions, TriId};
use proptest::prelude::*;

#[path = "map/reference.rs"]
mod reference;

mod support;

/// Saving and loading, damaged and crafted files.
#[path = "map/file.rs"]
mod file;

/// Lookups with any index or point.
#[path = "map/lookup.rs"]
mod lookup;

/// Segments walked through the grid find the triangles they meet.
#[path = "map/walk.rs"]
mod walk;

/// Maps of the shared real meshes.
#[path = "map/models.rs"]
mod models;

/// Clearance and reach of the free cells.
#[path = "map/clearance.rs"]
mod clearance;

use reference::{Dense, dense_reference, distance_to_surface, winding_number};

fn surface(mesh: Mesh) -> Surface {
    Surface::new(mesh, &SurfaceOptions::default()).expect("a usable test mesh")
}

fn build(surface: &Surface, options: &MapOptions) -> VoxelMap {
    VoxelMap::build(surface, options).expect("the map builds")
}

/// Small closed solids of every procedural family, a few hundred to a thousand triangles.
fn solids() -> Vec<(&'static str, Surface)> {
    vec![
        ("sphere", surface(shapes::sphere(0.1, 3))),
        ("torus", surface(shapes::torus(0.07, 0.03, 24, 12))),
        ("concave_corner", surface(shapes::concave_corner(0.2, 4))),
        (
            "thin_plate",
            surface(shapes::thin_plate(0.2, 0.2, 1e-4, 12)),
        ),
        ("blob", surface(shapes::blob(0.1, 3, 0.02, 7))),
        (
            "box",
            surface(shapes::cuboid(DVec3::new(0.1, 0.05, 0.03), [12, 6, 4])),
        ),
        ("hollow sphere", hollow_sphere()),
        ("nested spheres", nested_spheres()),
    ]
}

/// The triangles of `a` and `b` together (`b` turned inside out when `invert_b`).
fn union(a: Mesh, b: Mesh, invert_b: bool) -> Mesh {
    let offset = a.vertices.len() as u32;
    let mut mesh = a;
    mesh.vertices.extend(b.vertices);
    mesh.triangles
        .extend(b.triangles.into_iter().map(|[p, q, r]| {
            let [p, q, r] = [p, q, r].map(|v| v + offset);
            if invert_b { [p, r, q] } else { [p, q, r] }
        }));
    mesh
}

/// A ball with a spherical cavity: a solid whose cavity is enclosed free space that the
/// flood fill from the padding cannot reach, yet outside the material.
fn hollow_sphere() -> Surface {
    let s = surface(union(shapes::sphere(0.1, 3), shapes::sphere(0.05, 3), true));
    assert!(s.is_solid(), "a cavity is part of a valid solid");
    s
}

/// A ball inside a ball, both outward: the inner one encloses space of winding number 2.
fn nested_spheres() -> Surface {
    surface(union(
        shapes::sphere(0.1, 3),
        shapes::sphere(0.05, 2),
        false,
    ))
}

/// A sphere with its top cap removed: open, so no inside.
fn open_sphere() -> Surface {
    let mut mesh = shapes::sphere(0.1, 3);
    let vertices = mesh.vertices.clone();
    mesh.triangles
        .retain(|t| t.iter().map(|&v| vertices[v as usize].z).sum::<f64>() < 0.2);
    let s = surface(mesh);
    assert!(!s.is_solid());
    s
}

/// One triangle in the plane z = 0.5 (a flat, open surface: one axis of zero extent).
fn single_triangle() -> Surface {
    surface(Mesh {
        vertices: vec![
            DVec3::new(0.0, 0.0, 0.5),
            DVec3::new(0.3, 0.05, 0.5),
            DVec3::new(0.1, 0.2, 0.5),
        ],
        triangles: vec![[0, 1, 2]],
    })
}

/// Compares every cell of `map` with the dense reference, and a few indices outside the
/// grid. Clearance is exact in bricks that hold a surface cell or touch one (26
/// neighbours) and, elsewhere, the smallest exact clearance of the brick (the documented
/// lower bound).
/// The cells of `grid` within `margin` cells of the bounding box of the triangle with
/// `corners` (which lies in the grid).
fn cells_around(grid: &Grid, corners: [DVec3; 3], margin: u32) -> impl Iterator<Item = [u32; 3]> {
    let lo = grid
        .cell_of(corners[0].min(corners[1]).min(corners[2]))
        .expect("in grid");
    let hi = grid
        .cell_of(corners[0].max(corners[1]).max(corners[2]))
        .expect("in grid");
    let span = move |a: usize| lo[a].saturating_sub(margin)..=hi[a] + margin;
    span(2).flat_map(move |z| span(1).flat_map(move |y| span(0).map(move |x| [x, y, z])))
}

fn assert_matches_dense(name: &str, surface: &Surface, map: &VoxelMap) {
    let dense: Dense = dense_reference(surface, map.grid(), surface.is_solid());
    let brick = |c: [u32; 3]| c.map(|v| v / 8);
    let mut surface_bricks = std::collections::HashSet::new();
    let mut brick_min = std::collections::HashMap::new();
    for c in dense.cells() {
        let i = dense.index(c);
        if dense.states[i] == CellState::Surface {
            surface_bricks.insert(brick(c));
        }
        let min = brick_min.entry(brick(c)).or_insert(u8::MAX);
        *min = (*min).min(dense.clearance[i]);
    }
    let exact = |b: [u32; 3]| {
        (-1i64..=1).any(|dz| {
            (-1i64..=1).any(|dy| {
                (-1i64..=1).any(|dx| {
                    let n = [
                        i64::from(b[0]) + dx,
                        i64::from(b[1]) + dy,
                        i64::from(b[2]) + dz,
                    ];
                    n.iter().all(|&v| v >= 0) && surface_bricks.contains(&n.map(|v| v as u32))
                })
            })
        })
    };
    for c in dense.cells() {
        let i = dense.index(c);
        assert_eq!(map.state(c), dense.states[i], "{name}: state of {c:?}");
        // The same triangles, each once (a list is ordered along its cell's slab).
        let mut listed = map.triangles_in(c).to_vec();
        listed.sort_unstable();
        assert_eq!(listed, dense.triangles[i], "{name}: triangles of {c:?}");
        let expected = match dense.states[i] {
            CellState::Surface => 0,
            _ if exact(brick(c)) => dense.clearance[i],
            _ => brick_min[&brick(c)],
        };
        assert_eq!(map.clearance(c), expected, "{name}: clearance of {c:?}");
        // The reach: the clearance below the cap; beyond it never more than the exact
        // distance, and short of it by less than two bricks.
        let (reach, distance) = (map.reach(c), dense.distance[i]);
        if expected < MAX_CLEARANCE {
            assert_eq!(reach, u32::from(expected), "{name}: reach of {c:?}");
        } else {
            assert!(
                reach >= u32::from(MAX_CLEARANCE)
                    && reach <= distance
                    && reach + 14 >= distance.min(1 << 20),
                "{name}: reach {reach} of {c:?} at distance {distance}"
            );
        }
    }
    let [dx, dy, dz] = dense.dims;
    for c in [
        [dx, 0, 0],
        [0, dy, 0],
        [0, 0, dz],
        [u32::MAX; 3],
        [dx - 1, dy - 1, dz],
    ] {
        assert_eq!(
            map.state(c),
            CellState::Outside,
            "{name}: {c:?} outside the grid"
        );
        assert_eq!(map.clearance(c), 0);
        assert_eq!(map.reach(c), 0);
        assert!(map.triangles_in(c).is_empty());
    }
    let stats = map.stats();
    let count = |s: CellState| dense.states.iter().filter(|&&x| x == s).count() as u64;
    assert_eq!(stats.surface_cells, count(CellState::Surface), "{name}");
    assert_eq!(stats.inside_cells, count(CellState::Inside), "{name}");
    assert_eq!(stats.outside_cells, count(CellState::Outside), "{name}");
    assert_eq!(
        stats.triangle_refs,
        dense.triangles.iter().map(Vec::len).sum::<usize>() as u64,
        "{name}"
    );
}

#[test]
fn sparse_map_equals_the_dense_reference() {
    let mut cases = solids();
    cases.push(("open sphere", open_sphere()));
    cases.push(("single triangle", single_triangle()));
    for (name, surface) in &cases {
        let automatic = build(surface, &MapOptions::default());
        assert_matches_dense(name, surface, &automatic);
        // Coarser and finer cells than the automatic size; the finest has bricks far from
        // the surface (uniform, with clearance lower bounds) and dims that are not a
        // multiple of the brick size.
        let h = automatic.grid().cell_size();
        for factor in [2.7, 0.37] {
            let options = MapOptions {
                cell_size_m: Some(h * factor),
                ..MapOptions::default()
            };
            let map = build(surface, &options);
            assert_eq!(map.cell_size_rule(), CellSizeRule::Given);
            assert_matches_dense(&format!("{name} ×{factor}"), surface, &map);
        }
    }
}

#[test]
fn every_triangle_is_listed_where_it_overlaps_and_nowhere_else() {
    for (name, surface) in solids() {
        let map = build(&surface, &MapOptions::default());
        let grid = map.grid();
        let h = grid.cell_size();
        let mut pairs = 0usize;
        for t in 0..surface.triangle_count() {
            let corners = surface.corners(TriId(t as u32));
            // Every cell within two of the triangle's bounding box.
            for c in cells_around(grid, corners, 2) {
                let listed = map.triangles_in(c).contains(&(t as u32));
                pairs += usize::from(listed);
                assert_eq!(
                    listed,
                    grid.overlaps_cell(corners, c),
                    "{name}: triangle {t} in cell {c:?}"
                );
                // Conservative against the plain kernel on the cell's closed box, and
                // never farther than the tolerance (twice, for rounding).
                let (min, max) = grid.cell_bounds(c);
                let centre = 0.5 * (min + max);
                let exact = overlap_triangle_box(corners, centre, 0.5 * (max - min));
                let slack = DVec3::splat((0.5 + 2.0 * OVERLAP_TOLERANCE_REL) * h);
                let loose = overlap_triangle_box(corners, centre, slack);
                assert!(!exact || listed, "{name}: {t} missed in {c:?}");
                assert!(!listed || loose, "{name}: {t} listed far from {c:?}");
            }
        }
        assert_eq!(
            pairs as u64,
            map.stats().triangle_refs,
            "{name}: no stray pairs"
        );
    }
}

#[test]
fn points_on_a_triangle_find_it_in_their_cell() {
    for (name, surface) in solids() {
        let map = build(&surface, &MapOptions::default());
        let grid = map.grid();
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut unit = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        for t in 0..surface.triangle_count() {
            let [a, b, c] = surface.corners(TriId(t as u32));
            let (u, v) = (unit(), unit());
            let (u, v) = if u + v > 1.0 {
                (1.0 - u, 1.0 - v)
            } else {
                (u, v)
            };
            for p in [a, b, c, 0.5 * (a + b), a + u * (b - a) + v * (c - a)] {
                let cell = grid.cell_of(p).expect("the surface is inside the grid");
                assert!(
                    map.triangles_in(cell).contains(&(t as u32)),
                    "{name}: triangle {t} not listed in the cell of its point {p}"
                );
            }
        }
    }
}

/// Non-surface cells against the generalised winding number at their centre. The cells
/// farther than a cell diagonal from the surface are the reference check; the nearer ones
/// (at least half a cell from it, since no triangle meets them) are checked too, which
/// holds for these shapes (no pocket of outside space closed off by surface cells).
#[test]
fn flood_fill_agrees_with_the_winding_number() {
    for (name, surface) in solids() {
        let map = build(&surface, &MapOptions::default());
        let grid = map.grid();
        let diagonal = 3f64.sqrt() * grid.cell_size();
        let [dx, dy, dz] = grid.dims();
        let (mut far, mut inside) = (0, 0);
        for z in 0..dz {
            for y in 0..dy {
                for x in 0..dx {
                    let c = [x, y, z];
                    let state = map.state(c);
                    if state == CellState::Surface {
                        continue;
                    }
                    let p = grid.cell_centre(c);
                    let w = winding_number(&surface, p);
                    let expected = if w.abs() > 0.5 {
                        CellState::Inside
                    } else {
                        CellState::Outside
                    };
                    let is_far = distance_to_surface(&surface, p) > diagonal;
                    assert_eq!(
                        state, expected,
                        "{name}: cell {c:?} (far: {is_far}), winding number {w}"
                    );
                    if is_far {
                        assert!(
                            (w - w.round()).abs() < 1e-6,
                            "{name}: {w} is not a whole number"
                        );
                        far += 1;
                        inside += usize::from(state == CellState::Inside);
                    }
                }
            }
        }
        // The plate is thinner than a cell: no cell is inside, few are far from it.
        if name != "thin_plate" {
            assert!(
                far > 100 && inside > 0,
                "{name}: {far} far cells, {inside} inside"
            );
        }
    }
}

#[test]
fn a_cavity_is_outside_and_nested_solids_are_inside() {
    let hollow = hollow_sphere();
    let map = build(&hollow, &MapOptions::default());
    let grid = map.grid();
    let state = |p: DVec3| map.state(grid.cell_of(p).expect("in the grid"));
    assert_eq!(
        state(DVec3::ZERO),
        CellState::Outside,
        "the cavity's centre"
    );
    assert_eq!(
        state(DVec3::new(0.075, 0.0, 0.0)),
        CellState::Inside,
        "in the shell"
    );
    assert_eq!(
        state(DVec3::new(0.0, -0.075, 0.0)),
        CellState::Inside,
        "in the shell"
    );

    let nested = nested_spheres();
    let map = build(&nested, &MapOptions::default());
    let grid = map.grid();
    assert_eq!(
        map.state(grid.cell_of(DVec3::ZERO).expect("in grid")),
        CellState::Inside
    );
}

#[test]
fn open_meshes_have_no_inside_cells() {
    for surface in [open_sphere(), single_triangle()] {
        let map = build(&surface, &MapOptions::default());
        assert!(!map.is_solid());
        assert_eq!(map.stats().inside_cells, 0);
        let [dx, dy, dz] = map.grid().dims();
        for z in 0..dz {
            for y in 0..dy {
                for x in 0..dx {
                    assert_ne!(map.state([x, y, z]), CellState::Inside);
                }
            }
        }
    }
}

#[test]
fn padding_is_outside_and_points_beyond_the_grid_belong_to_no_cell() {
    for (name, surface) in solids() {
        let map = build(&surface, &MapOptions::default());
        let grid = map.grid();
        let [dx, dy, dz] = grid.dims();
        for z in 0..dz {
            for y in 0..dy {
                for x in 0..dx {
                    let on_border =
                        x == 0 || y == 0 || z == 0 || x + 1 == dx || y + 1 == dy || z + 1 == dz;
                    if on_border {
                        assert_eq!(map.state([x, y, z]), CellState::Outside, "{name}");
                        assert!(map.clearance([x, y, z]) >= 1, "{name}");
                    }
                }
            }
        }
        let (min, max) = (grid.origin(), grid.max_corner());
        assert!(grid.cell_of(min - DVec3::splat(1e-9)).is_none());
        assert!(grid.cell_of(max).is_none());
        let bounds = surface.report();
        let (lo, hi) = (
            DVec3::from(bounds.bounds_min),
            DVec3::from(bounds.bounds_max),
        );
        assert!(
            (lo - min).min_element() > grid.cell_size(),
            "{name}: a full padding cell below"
        );
        assert!(
            (max - hi).min_element() > grid.cell_size(),
            "{name}: a full padding cell above"
        );
    }
}

#[test]
fn builds_are_deterministic_across_runs_and_thread_counts() {
    let surface = surface(Catalog::Blob.with_triangles(20_000));
    let options = MapOptions::default();
    let reference = encode(&surface, &build(&surface, &options));
    assert_eq!(encode(&surface, &build(&surface, &options)), reference);
    for threads in [1, 3] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("a thread pool");
        let bytes = pool.install(|| encode(&surface, &build(&surface, &options)));
        assert!(bytes == reference, "{threads} threads give other bytes");
    }
}

#[test]
fn the_memory_budget_is_respected() {
    let surface = surface(Catalog::Sphere.with_triangles(20_000));
    let free = build(&surface, &MapOptions::default());
    let budget = free.heap_bytes() / 3;
    let options = MapOptions {
        memory_budget_bytes: budget,
        ..MapOptions::default()
    };
    let tight = build(&surface, &options);
    assert!(
        tight.heap_bytes() <= budget,
        "{} > {budget}",
        tight.heap_bytes()
    );
    assert!(tight.grid().cell_size() > free.grid().cell_size());
    let CellSizeRule::Automatic { enlargements, .. } = tight.cell_size_rule() else {
        panic!("automatic rule expected");
    };
    assert!(enlargements > 0);
    assert_matches_dense("tight budget", &surface, &tight);

    // Too small for any grid, or for a given cell size.
    let tiny = MapOptions {
        memory_budget_bytes: 10_000,
        ..MapOptions::default()
    };
    assert!(matches!(
        VoxelMap::build(&surface, &tiny),
        Err(MapError::OverBudget { .. })
    ));
    let given = MapOptions {
        cell_size_m: Some(free.grid().cell_size()),
        memory_budget_bytes: budget,
        ..MapOptions::default()
    };
    assert!(matches!(
        VoxelMap::build(&surface, &given),
        Err(MapError::OverBudget { .. })
    ));
}

#[test]
fn bad_options_are_refused() {
    let surface = surface(shapes::sphere(0.1, 1));
    for h in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let options = MapOptions {
            cell_size_m: Some(h),
            ..MapOptions::default()
        };
        assert!(matches!(
            VoxelMap::build(&surface, &options),
            Err(MapError::InvalidCellSize { .. })
        ));
    }
    for tau in [0.5, f64::NAN, -3.0] {
        let options = MapOptions {
            triangles_per_cell: tau,
            ..MapOptions::default()
        };
        assert!(matches!(
            VoxelMap::build(&surface, &options),
            Err(MapError::InvalidTrianglesPerCell { .. })
        ));
    }
    let options = MapOptions {
        cell_size_m: Some(1e-9),
        ..MapOptions::default()
    };
    assert!(matches!(
        VoxelMap::build(&surface, &options),
        Err(MapError::TooManyCells { .. })
    ));
}

#[test]
fn progress_rises_to_one() {
    let surface = surface(Catalog::Torus.with_triangles(30_000));
    let seen = std::sync::Mutex::new(Vec::new());
    let map = VoxelMap::build_with_progress(&surface, &MapOptions::default(), &|f| {
        seen.lock().expect("not poisoned").push(f);
    })
    .expect("builds");
    let seen = seen.into_inner().expect("not poisoned");
    assert!(seen.len() > 10, "{seen:?}");
    assert!(seen.windows(2).all(|w| w[0] <= w[1]), "{seen:?}");
    assert_eq!(seen.first(), Some(&0.0));
    assert_eq!(seen.last(), Some(&1.0));
    assert_eq!(map, build(&surface, &MapOptions::default()));
}
