//! The procedural shapes are closed, consistently oriented manifolds with the documented
//! sizes, counts, volumes and areas, and they come out the same on every run.
//!
//! The checks (in `shapes/checks.rs`) are written from scratch, independent of the
//! library's own validation.

use std::f64::consts::PI;

use haphe::DVec3;
use haphe::mesh::Mesh;
use haphe::mesh::shapes::{
    Catalog, MAX_BLOB_AMPLITUDE_FRACTION, blob, concave_corner, cuboid, geodesic_blob,
    geodesic_sphere, sphere, thin_plate, torus,
};
use proptest::prelude::*;

#[path = "shapes/checks.rs"]
mod checks;

#[path = "shapes/strategies.rs"]
mod strategies;

use checks::{
    area, assert_closed_manifold, assert_relative, assert_star_shaped_between, ball_volume,
    check_closed_manifold, extent, signed_volume,
};
use strategies::generator;

// ---------------------------------------------------------------------------------------
// Spheres
// ---------------------------------------------------------------------------------------

#[test]
fn subdivided_spheres_are_closed_spheres_with_the_expected_counts() {
    for radius in [0.1, 1.0, 0.003] {
        for subdivisions in 0..=5u32 {
            let context = format!("sphere({radius}, {subdivisions})");
            let mesh = sphere(radius, subdivisions);
            let faces = 20 * 4usize.pow(subdivisions);
            let topology = assert_closed_manifold(&mesh, &context);
            assert_eq!(topology.faces, faces, "{context}");
            assert_eq!(topology.vertices, faces / 2 + 2, "{context}");
            assert_eq!(topology.euler_characteristic(), 2, "{context}");
            for p in &mesh.vertices {
                assert_relative(p.length(), radius, 1e-15, &context);
            }
            let (volume, surface) = assert_star_shaped_between(&mesh, radius, &context);
            // The inscribed polyhedron converges to the sphere as 1/frequency².
            let frequency = f64::from(1u32 << subdivisions);
            let tolerance = 1.0 / (frequency * frequency);
            assert_relative(volume, ball_volume(radius), tolerance, &context);
            assert_relative(surface, 4.0 * PI * radius * radius, tolerance, &context);
        }
    }
}

#[test]
fn geodesic_spheres_allow_every_frequency() {
    for frequency in 1..=13u32 {
        let context = format!("geodesic_sphere(0.1, {frequency})");
        let mesh = geodesic_sphere(0.1, frequency);
        let topology = assert_closed_manifold(&mesh, &context);
        let faces = 20 * (frequency * frequency) as usize;
        assert_eq!(topology.faces, faces, "{context}");
        assert_eq!(topology.vertices, faces / 2 + 2, "{context}");
        assert_eq!(topology.euler_characteristic(), 2, "{context}");
        let (volume, _) = assert_star_shaped_between(&mesh, 0.1, &context);
        let f = f64::from(frequency);
        assert_relative(volume, ball_volume(0.1), 1.0 / (f * f), &context);
    }
}

#[test]
fn sphere_is_the_geodesic_sphere_of_frequency_two_to_the_subdivisions() {
    for subdivisions in 0..=4 {
        assert_eq!(
            sphere(0.05, subdivisions),
            geodesic_sphere(0.05, 1 << subdivisions)
        );
    }
}

#[test]
fn sphere_vertices_are_spread_evenly() {
    // Frequency 16: the longest edge is within a factor 1.5 of the shortest.
    let mesh = geodesic_sphere(1.0, 16);
    let lengths: Vec<f64> = mesh
        .triangles
        .iter()
        .flat_map(|&[a, b, c]| [(a, b), (b, c), (c, a)])
        .map(|(a, b)| (mesh.vertices[a as usize] - mesh.vertices[b as usize]).length())
        .collect();
    let longest = lengths.iter().copied().fold(0.0, f64::max);
    let shortest = lengths.iter().copied().fold(f64::INFINITY, f64::min);
    assert!(
        longest / shortest < 1.5,
        "edge ratio {}",
        longest / shortest
    );
}

// ---------------------------------------------------------------------------------------
// Torus
// ---------------------------------------------------------------------------------------

/// The exact volume of the polyhedral torus: each ring segment is the tube's regular
/// polygon swept linearly between two ring angles, of volume `sin(2π/M)·A·R`.
fn polyhedral_torus_volume(major: f64, minor: f64, ring: u32, tube: u32) -> f64 {
    let (ring, tube) = (f64::from(ring), f64::from(tube));
    let polygon_area = tube / 2.0 * minor * minor * (2.0 * PI / tube).sin();
    ring * (2.0 * PI / ring).sin() * polygon_area * major
}

/// The exact area of the polyhedral torus: every cell is a planar isosceles trapezoid.
fn polyhedral_torus_area(major: f64, minor: f64, ring: u32, tube: u32) -> f64 {
    let half_step = PI / f64::from(ring);
    let point = |j: u32| {
        let angle = 2.0 * PI * f64::from(j) / f64::from(tube);
        (major + minor * angle.cos(), minor * angle.sin())
    };
    let ring_cells: f64 = (0..tube)
        .map(|j| {
            let ((rho0, z0), (rho1, z1)) = (point(j), point(j + 1));
            let parallel_mean = (rho0 + rho1) * half_step.sin();
            let height = ((z1 - z0).powi(2) + ((rho1 - rho0) * half_step.cos()).powi(2)).sqrt();
            parallel_mean * height
        })
        .sum();
    f64::from(ring) * ring_cells
}

#[test]
fn tori_are_closed_with_euler_characteristic_zero_and_exact_volume() {
    for (major, minor) in [(0.07, 0.03), (1.0, 0.999), (0.5, 0.01)] {
        for (ring, tube) in [(3, 3), (3, 7), (8, 3), (24, 12), (64, 48), (5, 200)] {
            let context = format!("torus({major}, {minor}, {ring}, {tube})");
            let mesh = torus(major, minor, ring, tube);
            let topology = assert_closed_manifold(&mesh, &context);
            assert_eq!(topology.faces, 2 * (ring * tube) as usize, "{context}");
            assert_eq!(topology.vertices, (ring * tube) as usize, "{context}");
            assert_eq!(topology.euler_characteristic(), 0, "{context}");
            let volume = signed_volume(&mesh);
            assert_relative(
                volume,
                polyhedral_torus_volume(major, minor, ring, tube),
                1e-12,
                &context,
            );
            assert_relative(
                area(&mesh),
                polyhedral_torus_area(major, minor, ring, tube),
                1e-12,
                &context,
            );
        }
    }
}

#[test]
fn fine_tori_approach_the_analytic_volume_and_area() {
    let (major, minor) = (0.07, 0.03);
    let mesh = torus(major, minor, 280, 120);
    assert_closed_manifold(&mesh, "fine torus");
    assert_relative(
        signed_volume(&mesh),
        2.0 * PI * PI * major * minor * minor,
        1e-3,
        "volume",
    );
    assert_relative(area(&mesh), 4.0 * PI * PI * major * minor, 1e-3, "area");
}

// ---------------------------------------------------------------------------------------
// Boxes
// ---------------------------------------------------------------------------------------

#[test]
fn cuboids_are_closed_with_exact_volume_and_area() {
    let half_extents = [
        DVec3::new(0.1, 0.075, 0.05),
        DVec3::splat(1.0),
        DVec3::new(3.0, 0.001, 0.2),
    ];
    let divisions = [[1, 1, 1], [2, 2, 2], [3, 1, 7], [1, 5, 2], [16, 12, 8]];
    for h in half_extents {
        for d in divisions {
            let context = format!("cuboid({h}, {d:?})");
            let mesh = cuboid(h, d);
            let topology = assert_closed_manifold(&mesh, &context);
            let [dx, dy, dz] = d.map(|n| n as usize);
            let faces = 4 * (dx * dy + dy * dz + dz * dx);
            assert_eq!(topology.faces, faces, "{context}");
            assert_eq!(topology.vertices, faces / 2 + 2, "{context}");
            assert_eq!(topology.euler_characteristic(), 2, "{context}");
            assert_eq!(mesh.bounds(), Some((-h, h)), "{context}");
            assert_relative(signed_volume(&mesh), 8.0 * h.x * h.y * h.z, 1e-12, &context);
            let expected_area = 8.0 * (h.x * h.y + h.y * h.z + h.z * h.x);
            assert_relative(area(&mesh), expected_area, 1e-12, &context);
        }
    }
}

#[test]
fn thin_plates_are_closed_with_exact_volume() {
    for (width, depth, thickness) in [(0.2, 0.2, 0.0001), (0.3, 0.1, 1e-5), (1.0, 2.0, 0.01)] {
        for divisions in [1, 2, 5, 40] {
            let context = format!("thin_plate({width}, {depth}, {thickness}, {divisions})");
            let mesh = thin_plate(width, depth, thickness, divisions);
            let topology = assert_closed_manifold(&mesh, &context);
            let n = divisions as usize;
            assert_eq!(topology.faces, 4 * n * n + 8 * n, "{context}");
            assert_eq!(topology.euler_characteristic(), 2, "{context}");
            assert_relative(extent(&mesh).z, thickness, 1e-9, &context);
            assert_relative(
                signed_volume(&mesh),
                width * depth * thickness,
                1e-9,
                &context,
            );
            let expected_area = 2.0 * (width * depth + width * thickness + depth * thickness);
            assert_relative(area(&mesh), expected_area, 1e-12, &context);
        }
    }
}

#[test]
fn concave_corner_blocks_are_closed_with_seven_eighths_of_the_cube() {
    for size in [0.2, 1.0, 0.01] {
        for divisions in [1, 2, 3, 7] {
            let context = format!("concave_corner({size}, {divisions})");
            let mesh = concave_corner(size, divisions);
            let topology = assert_closed_manifold(&mesh, &context);
            let d = divisions as usize;
            assert_eq!(topology.faces, 48 * d * d, "{context}");
            assert_eq!(topology.vertices, 24 * d * d + 2, "{context}");
            assert_eq!(topology.euler_characteristic(), 2, "{context}");
            assert_relative(
                signed_volume(&mesh),
                7.0 / 8.0 * size.powi(3),
                1e-12,
                &context,
            );
            assert_relative(area(&mesh), 6.0 * size * size, 1e-12, &context);
            assert_eq!(
                mesh.bounds(),
                Some((DVec3::splat(-size / 2.0), DVec3::splat(size / 2.0))),
                "{context}"
            );
        }
    }
}

#[test]
fn concave_corner_has_its_concave_corner_at_the_origin() {
    let mesh = concave_corner(0.2, 3);
    // No vertex lies inside the removed octant, and the origin is a vertex.
    assert!(mesh.vertices.contains(&DVec3::ZERO));
    assert!(!mesh.vertices.iter().any(|p| p.min_element() > 0.0));
    // The three inner faces face into the removed octant.
    let inner_normals: Vec<DVec3> = (0..mesh.triangles.len())
        .filter_map(|t| {
            let [a, b, c] = mesh.corners(t);
            let centroid = (a + b + c) / 3.0;
            let normal = (b - a).cross(c - a).normalize();
            let on_inner_face = centroid.min_element() > 0.0 - 1e-12
                && centroid
                    .to_array()
                    .iter()
                    .filter(|&&x| x.abs() < 1e-12)
                    .count()
                    == 1;
            on_inner_face.then_some(normal)
        })
        .collect();
    assert_eq!(inner_normals.len(), 3 * 2 * 9);
    for normal in inner_normals {
        assert!(
            normal == DVec3::X || normal == DVec3::Y || normal == DVec3::Z,
            "{normal}"
        );
    }
}

// ---------------------------------------------------------------------------------------
// Blobs
// ---------------------------------------------------------------------------------------

#[test]
fn blobs_are_closed_star_shaped_and_within_their_amplitude() {
    for seed in [0, 1, 42, u64::MAX] {
        for (radius, amplitude) in [(0.1, 0.02), (1.0, 0.5), (0.1, 0.0)] {
            for subdivisions in [0, 2, 4] {
                let context = format!("blob({radius}, {subdivisions}, {amplitude}, {seed})");
                let mesh = blob(radius, subdivisions, amplitude, seed);
                let topology = assert_closed_manifold(&mesh, &context);
                assert_eq!(topology.faces, 20 * 4usize.pow(subdivisions), "{context}");
                assert_eq!(topology.euler_characteristic(), 2, "{context}");
                for p in &mesh.vertices {
                    let distance = p.length();
                    assert!(
                        (distance - radius).abs() <= amplitude * (1.0 + 1e-12) + 1e-15,
                        "{context}: vertex at {distance}"
                    );
                }
                assert_star_shaped_between(&mesh, radius + amplitude, &context);
            }
        }
    }
}

#[test]
fn blobs_are_lumpy_and_depend_on_the_seed() {
    let mesh = blob(0.1, 4, 0.02, 3);
    let distances: Vec<f64> = mesh.vertices.iter().map(|p| p.length()).collect();
    let spread = distances.iter().copied().fold(0.0, f64::max)
        - distances.iter().copied().fold(f64::INFINITY, f64::min);
    assert!(spread > 0.01, "too smooth: radial spread {spread}");
    assert_eq!(mesh, blob(0.1, 4, 0.02, 3));
    assert_ne!(mesh, blob(0.1, 4, 0.02, 4));
}

#[test]
fn blob_amplitude_is_clamped_below_the_radius() {
    let mesh = geodesic_blob(0.1, 12, 5.0, 9);
    let nearest = mesh
        .vertices
        .iter()
        .map(|p| p.length())
        .fold(f64::INFINITY, f64::min);
    assert!(nearest >= 0.1 * (1.0 - MAX_BLOB_AMPLITUDE_FRACTION) * (1.0 - 1e-12));
    assert_closed_manifold(&mesh, "blob with clamped amplitude");
    assert_star_shaped_between(
        &mesh,
        0.1 * (1.0 + MAX_BLOB_AMPLITUDE_FRACTION),
        "clamped blob",
    );
}

#[test]
fn blob_without_noise_is_the_sphere() {
    assert_eq!(blob(0.1, 3, 0.0, 5), sphere(0.1, 3));
    assert_eq!(
        blob(0.1, 3, -0.01, 5),
        sphere(0.1, 3),
        "negative amplitude clamps to 0"
    );
}

// ---------------------------------------------------------------------------------------
// Arguments out of range
// ---------------------------------------------------------------------------------------

#[test]
fn invalid_sizes_give_an_empty_mesh() {
    let bad = [0.0, -0.1, f64::NAN, f64::INFINITY, f64::NEG_INFINITY];
    for x in bad {
        assert_eq!(sphere(x, 2), Mesh::default(), "sphere radius {x}");
        assert_eq!(
            geodesic_sphere(x, 3),
            Mesh::default(),
            "geodesic radius {x}"
        );
        assert_eq!(torus(x, 0.03, 8, 8), Mesh::default(), "torus major {x}");
        assert_eq!(torus(0.07, x, 8, 8), Mesh::default(), "torus minor {x}");
        assert_eq!(
            cuboid(DVec3::new(0.1, x, 0.1), [2; 3]),
            Mesh::default(),
            "cuboid {x}"
        );
        assert_eq!(
            thin_plate(0.2, 0.2, x, 4),
            Mesh::default(),
            "plate thickness {x}"
        );
        assert_eq!(
            thin_plate(x, 0.2, 0.001, 4),
            Mesh::default(),
            "plate width {x}"
        );
        assert_eq!(concave_corner(x, 2), Mesh::default(), "concave corner {x}");
        assert_eq!(blob(x, 2, 0.01, 1), Mesh::default(), "blob radius {x}");
    }
    for amplitude in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        assert_eq!(
            blob(0.1, 2, amplitude, 1),
            Mesh::default(),
            "amplitude {amplitude}"
        );
    }
    // A tube as thick as the ring would cross itself on the axis.
    assert_eq!(torus(0.05, 0.05, 8, 8), Mesh::default());
    assert_eq!(torus(0.03, 0.07, 8, 8), Mesh::default());
    // Sizes that overflow once doubled or added.
    assert_eq!(cuboid(DVec3::splat(f64::MAX), [1; 3]), Mesh::default());
    assert_eq!(torus(f64::MAX, f64::MAX / 2.0, 8, 8), Mesh::default());
}

#[test]
fn resolutions_below_the_coarsest_are_clamped_up() {
    assert_eq!(geodesic_sphere(0.1, 0), geodesic_sphere(0.1, 1));
    assert_eq!(
        geodesic_blob(0.1, 0, 0.01, 2),
        geodesic_blob(0.1, 1, 0.01, 2)
    );
    assert_eq!(torus(0.07, 0.03, 0, 1), torus(0.07, 0.03, 3, 3));
    assert_eq!(cuboid(DVec3::ONE, [0, 0, 0]), cuboid(DVec3::ONE, [1, 1, 1]));
    assert_eq!(
        thin_plate(0.2, 0.2, 0.001, 0),
        thin_plate(0.2, 0.2, 0.001, 1)
    );
    assert_eq!(concave_corner(0.2, 0), concave_corner(0.2, 1));
    assert_closed_manifold(&torus(0.07, 0.03, 0, 0), "coarsest torus");
}

// ---------------------------------------------------------------------------------------
// Catalog: names, sizes, triangle budgets, determinism
// ---------------------------------------------------------------------------------------

#[test]
fn shape_names_round_trip() {
    let names: Vec<String> = Catalog::ALL.iter().map(Catalog::to_string).collect();
    assert_eq!(
        names,
        [
            "sphere",
            "torus",
            "box",
            "thin-plate",
            "concave-corner",
            "blob"
        ]
    );
    for shape in Catalog::ALL {
        assert_eq!(shape.to_string().parse::<Catalog>(), Ok(shape));
    }
    let error = "cube".parse::<Catalog>().expect_err("not a shape name");
    assert_eq!(error.name, "cube");
    assert!(error.to_string().contains("thin-plate"), "{error}");
    assert!(
        "Sphere".parse::<Catalog>().is_err(),
        "names are case-sensitive"
    );
}

#[test]
fn shapes_are_closed_manifolds_of_the_documented_size_at_every_budget() {
    for shape in Catalog::ALL {
        for target in [0, 20, 100, 1_000, 10_000, 100_000] {
            let context = format!("{shape} with {target} triangles");
            let mesh = shape.with_triangles(target);
            let topology = assert_closed_manifold(&mesh, &context);
            let expected_euler = if shape == Catalog::Torus { 0 } else { 2 };
            assert_eq!(topology.euler_characteristic(), expected_euler, "{context}");
            assert!(signed_volume(&mesh) > 0.0, "{context}");
            assert_eq!(mesh.triangles.len(), shape.closest_triangle_count(target));

            let size = extent(&mesh);
            let expected = match shape {
                Catalog::Box => DVec3::new(0.2, 0.15, 0.1),
                Catalog::ThinPlate => DVec3::new(0.2, 0.2, 0.0001),
                Catalog::ConcaveCorner => DVec3::splat(0.2),
                _ => DVec3::ZERO,
            };
            match shape {
                Catalog::Sphere | Catalog::Blob | Catalog::Torus => {
                    let across = size.x.max(size.y);
                    let (low, high) = if shape == Catalog::Blob {
                        (0.12, 0.24)
                    } else {
                        (0.15, 0.2)
                    };
                    assert!(
                        low <= across && across <= high * (1.0 + 1e-12),
                        "{context}: {across} m across"
                    );
                }
                _ => assert!(
                    (size - expected).abs().max_element() < 1e-15,
                    "{context}: extent {size}"
                ),
            }
        }
    }
}

#[test]
fn shapes_hit_their_triangle_budget() {
    for shape in Catalog::ALL {
        for target in [100, 1_000, 10_000, 100_000, 1_000_000, 4_000_000] {
            let count = shape.closest_triangle_count(target);
            let ratio = count as f64 / target as f64;
            let factor = match target {
                ..1_000 => 2.5,
                1_000..100_000 => 1.25,
                _ => 1.05,
            };
            assert!(
                1.0 / factor <= ratio && ratio <= factor,
                "{shape}: {count} triangles for a target of {target}"
            );
        }
        // Never more than the coarsest mesh for a tiny budget.
        assert!(shape.closest_triangle_count(0) <= 48, "{shape}");
        assert!(shape.closest_triangle_count(1) >= 12, "{shape}");
    }
}

#[test]
fn shapes_are_deterministic() {
    for shape in Catalog::ALL {
        let first = shape.with_triangles(20_000);
        let again = shape.with_triangles(20_000);
        assert!(first == again, "{shape} differs between runs");
    }
    // From another thread, whose rayon scheduling differs.
    let from_thread = std::thread::spawn(|| Catalog::Blob.with_triangles(20_000))
        .join()
        .expect("the thread finishes");
    assert_eq!(from_thread, Catalog::Blob.with_triangles(20_000));
}

/// Run with `cargo test --release -p haphe --test shapes -- --ignored`.
#[test]
#[ignore = "builds and checks about 24 million triangles; slow without --release"]
fn four_million_triangle_shapes_are_closed_manifolds() {
    for shape in Catalog::ALL {
        let mesh = shape.with_triangles(4_000_000);
        let topology = assert_closed_manifold(&mesh, &format!("{shape} at 4M"));
        assert!(
            (3_900_000..=4_100_000).contains(&topology.faces),
            "{shape}: {}",
            topology.faces
        );
        assert_eq!(
            mesh.vertices.capacity(),
            mesh.vertices.len(),
            "{shape}: vertex buffer"
        );
        assert_eq!(
            mesh.triangles.capacity(),
            mesh.triangles.len(),
            "{shape}: index buffer"
        );
    }
}

// ---------------------------------------------------------------------------------------
// Property test
// ---------------------------------------------------------------------------------------

proptest! {
    #[test]
    fn every_generated_mesh_is_a_closed_oriented_manifold(generator in generator()) {
        let mesh = generator.build();
        let topology = check_closed_manifold(&mesh);
        prop_assert!(topology.is_ok(), "{:?}: {:?}", generator, topology);
        if let Ok(topology) = topology {
            prop_assert_eq!(topology.euler_characteristic(), generator.euler_characteristic());
        }
        prop_assert!(signed_volume(&mesh) > 0.0, "{:?}: volume not positive", generator);
    }
}
