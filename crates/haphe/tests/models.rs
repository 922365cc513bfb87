//! Every real model's validation report, pinned.
//!
//! The expected counts were computed independently of haphe: by
//! `tools/crosscheck_models.py`, which reads the files with trimesh (another parser) and
//! counts with numpy/scipy (another implementation of the same definitions: exact welding,
//! edges used once are boundary and three or more times non-manifold, components joined
//! through edges, fans around each vertex, Euler characteristic per closed component,
//! signed volume). Only the verdict (`usable_as`) follows from those counts by haphe's
//! documented rule.

mod support;

use haphe::mesh::{MeshReport, ReadOptions, Surface, SurfaceOptions, Usability, read_mesh};

/// The independently computed report of one model.
struct Pin {
    file: &'static str,
    triangles: usize,
    vertices: usize,
    edges: usize,
    components: usize,
    boundary_edges: usize,
    nonmanifold_edges: usize,
    nonmanifold_vertices: usize,
    orientation_conflicts: usize,
    duplicate_faces: usize,
    degenerate_triangles: usize,
    /// Sum over closed, oriented components without non-manifold vertices (cow.obj's one
    /// component has a non-manifold vertex, so it has none: its V − E + F is 1).
    genus: Option<u32>,
    /// m² (in file units, read as metres).
    area: f64,
    /// m³, for closed and oriented meshes.
    volume: Option<f64>,
}

#[rustfmt::skip]
const PINS: &[Pin] = &[
    Pin { file: "20mm-xyz-cube.stl", triangles: 260, vertices: 132, edges: 390, components: 1, boundary_edges: 0, nonmanifold_edges: 0, nonmanifold_vertices: 0, orientation_conflicts: 0, duplicate_faces: 0, degenerate_triangles: 0, genus: Some(0), area: 2499.0248765768843, volume: Some(7938.6818763348165) },
    Pin { file: "box.STL", triangles: 8954, vertices: 4455, edges: 13431, components: 10, boundary_edges: 0, nonmanifold_edges: 0, nonmanifold_vertices: 0, orientation_conflicts: 0, duplicate_faces: 0, degenerate_triangles: 0, genus: Some(21), area: 293.7966812335881, volume: Some(16.084489098307877) },
    Pin { file: "bunny.ply", triangles: 16301, vertices: 8146, edges: 24363, components: 1, boundary_edges: 123, nonmanifold_edges: 150, nonmanifold_vertices: 224, orientation_conflicts: 0, duplicate_faces: 87, degenerate_triangles: 0, genus: None, area: 0.05655603189002554, volume: None },
    Pin { file: "cow.obj", triangles: 5804, vertices: 2903, edges: 8706, components: 1, boundary_edges: 0, nonmanifold_edges: 0, nonmanifold_vertices: 1, orientation_conflicts: 0, duplicate_faces: 0, degenerate_triangles: 0, genus: None, area: 108.84536412297015, volume: Some(53.56744584247946) },
    Pin { file: "cylinder.stl", triangles: 416, vertices: 210, edges: 624, components: 1, boundary_edges: 0, nonmanifold_edges: 0, nonmanifold_vertices: 0, orientation_conflicts: 0, duplicate_faces: 0, degenerate_triangles: 0, genus: Some(0), area: 56.51839500127704, volume: Some(25.092387531871278) },
    Pin { file: "fandisk.obj", triangles: 12946, vertices: 6475, edges: 19419, components: 1, boundary_edges: 0, nonmanifold_edges: 0, nonmanifold_vertices: 0, orientation_conflicts: 0, duplicate_faces: 0, degenerate_triangles: 0, genus: Some(0), area: 60.669109234919674, volume: Some(20.24337488283946) },
    Pin { file: "featuretype.STL", triangles: 3476, vertices: 2010, edges: 5502, components: 1, boundary_edges: 576, nonmanifold_edges: 0, nonmanifold_vertices: 0, orientation_conflicts: 0, duplicate_faces: 0, degenerate_triangles: 0, genus: None, area: 53.82738611818216, volume: None },
    Pin { file: "fuze.ply", triangles: 1000, vertices: 502, edges: 1500, components: 1, boundary_edges: 0, nonmanifold_edges: 0, nonmanifold_vertices: 0, orientation_conflicts: 0, duplicate_faces: 0, degenerate_triangles: 0, genus: Some(0), area: 0.04472226022256357, volume: Some(0.0006066887624291841) },
    Pin { file: "fuze_ascii.ply", triangles: 1000, vertices: 502, edges: 1500, components: 1, boundary_edges: 0, nonmanifold_edges: 0, nonmanifold_vertices: 0, orientation_conflicts: 0, duplicate_faces: 0, degenerate_triangles: 0, genus: Some(0), area: 0.04472226022256357, volume: Some(0.0006066887624291841) },
    Pin { file: "nefertiti.obj", triangles: 99938, vertices: 49971, edges: 149907, components: 1, boundary_edges: 0, nonmanifold_edges: 0, nonmanifold_vertices: 0, orientation_conflicts: 0, duplicate_faces: 0, degenerate_triangles: 0, genus: Some(0), area: 363182.1114864782, volume: Some(11553383.52383343) },
    Pin { file: "octagonal_pocket.stl", triangles: 3262, vertices: 1658, edges: 4920, components: 5, boundary_edges: 54, nonmanifold_edges: 0, nonmanifold_vertices: 3, orientation_conflicts: 0, duplicate_faces: 0, degenerate_triangles: 0, genus: None, area: 0.07482245333956647, volume: None },
    Pin { file: "plate_holes.STL", triangles: 1252, vertices: 618, edges: 1878, components: 1, boundary_edges: 0, nonmanifold_edges: 0, nonmanifold_vertices: 0, orientation_conflicts: 0, duplicate_faces: 0, degenerate_triangles: 0, genus: Some(5), area: 133343.4118898397, volume: Some(767362.1125896011) },
    Pin { file: "rocker-arm.obj", triangles: 20088, vertices: 10044, edges: 30132, components: 1, boundary_edges: 0, nonmanifold_edges: 0, nonmanifold_vertices: 0, orientation_conflicts: 0, duplicate_faces: 0, degenerate_triangles: 0, genus: Some(1), area: 1.2965518606981843, volume: Some(0.04251362358052909) },
    Pin { file: "sphere.ply", triangles: 1280, vertices: 642, edges: 1920, components: 1, boundary_edges: 0, nonmanifold_edges: 0, nonmanifold_vertices: 0, orientation_conflicts: 0, duplicate_faces: 0, degenerate_triangles: 0, genus: Some(0), area: 12.506491330684753, volume: Some(4.1527401125257954) },
    Pin { file: "spot.obj", triangles: 5856, vertices: 2930, edges: 8784, components: 1, boundary_edges: 0, nonmanifold_edges: 0, nonmanifold_vertices: 0, orientation_conflicts: 0, duplicate_faces: 0, degenerate_triangles: 0, genus: Some(0), area: 5.709518785165158, volume: Some(0.7182587880998647) },
    Pin { file: "stanford-bunny.obj", triangles: 69451, vertices: 34834, edges: 104288, components: 1, boundary_edges: 223, nonmanifold_edges: 0, nonmanifold_vertices: 0, orientation_conflicts: 0, duplicate_faces: 0, degenerate_triangles: 0, genus: None, area: 0.0571287860608643, volume: None },
    Pin { file: "suzanne.obj", triangles: 968, vertices: 505, edges: 1472, components: 3, boundary_edges: 42, nonmanifold_edges: 1, nonmanifold_vertices: 4, orientation_conflicts: 0, duplicate_faces: 1, degenerate_triangles: 0, genus: None, area: 12.468539112387251, volume: None },
    Pin { file: "teapot.obj", triangles: 6320, vertices: 3241, edges: 9560, components: 4, boundary_edges: 160, nonmanifold_edges: 0, nonmanifold_vertices: 1, orientation_conflicts: 0, duplicate_faces: 0, degenerate_triangles: 0, genus: None, area: 52.6607934255059, volume: None },
    Pin { file: "tet.ply", triangles: 4, vertices: 4, edges: 6, components: 1, boundary_edges: 0, nonmanifold_edges: 0, nonmanifold_vertices: 0, orientation_conflicts: 0, duplicate_faces: 0, degenerate_triangles: 0, genus: Some(0), area: 8.94427190999916, volume: Some(1.3333333333333333) },
    Pin { file: "torus.STL", triangles: 8700, vertices: 4350, edges: 13050, components: 1, boundary_edges: 0, nonmanifold_edges: 0, nonmanifold_vertices: 0, orientation_conflicts: 0, duplicate_faces: 0, degenerate_triangles: 0, genus: Some(1), area: 19.7155093091624, volume: Some(4.9175473223140225) },
    Pin { file: "unit_sphere.STL", triangles: 1280, vertices: 642, edges: 1920, components: 1, boundary_edges: 0, nonmanifold_edges: 0, nonmanifold_vertices: 0, orientation_conflicts: 0, duplicate_faces: 0, degenerate_triangles: 0, genus: Some(0), area: 12.506492595767828, volume: Some(4.1527407490072425) },
];

/// Solids under haphe's rule: closed, manifold, oriented, not inside out, no duplicates.
/// None of the closed models has an inside-out component (box.STL's three small parts
/// inside a larger one have positive volume: nested solids).
fn expected_usability(p: &Pin) -> Usability {
    let closed = p.boundary_edges == 0 && p.nonmanifold_edges == 0;
    if closed
        && p.nonmanifold_vertices == 0
        && p.orientation_conflicts == 0
        && p.duplicate_faces == 0
    {
        Usability::Solid
    } else {
        Usability::Surface
    }
}

/// The names of the files in `models/` of the meshes the tests read, sorted.
fn models_on_disk() -> Vec<String> {
    let mut on_disk: Vec<String> = std::fs::read_dir(support::meshes().join("models"))
        .expect("models folder")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    on_disk.sort();
    on_disk
}

/// Every model present (the repository's own, or the whole shared collection) against its
/// pin.
#[test]
fn every_model_report_matches_the_independent_counts() {
    let models = support::meshes().join("models");
    let on_disk = models_on_disk();
    for file in &on_disk {
        assert!(PINS.iter().any(|p| p.file == file), "{file} is not pinned");
    }
    for p in PINS.iter().filter(|p| on_disk.iter().any(|f| f == p.file)) {
        let bytes = std::fs::read(models.join(p.file)).expect("readable");
        let mesh =
            read_mesh(p.file, &bytes, &ReadOptions::default()).unwrap_or_else(|e| panic!("{e}"));
        let r = MeshReport::of(&mesh);
        let got = (
            r.triangles,
            r.vertices,
            r.edges,
            r.components,
            r.boundary_edges,
            r.nonmanifold_edges,
            r.nonmanifold_vertices,
            r.orientation_conflicts,
            r.duplicate_faces,
            r.degenerate_triangles,
        );
        let want = (
            p.triangles,
            p.vertices,
            p.edges,
            p.components,
            p.boundary_edges,
            p.nonmanifold_edges,
            p.nonmanifold_vertices,
            p.orientation_conflicts,
            p.duplicate_faces,
            p.degenerate_triangles,
        );
        assert_eq!(got, want, "{}: counts", p.file);
        assert_eq!(
            r.closed,
            p.boundary_edges == 0 && p.nonmanifold_edges == 0,
            "{}",
            p.file
        );
        assert_eq!(r.genus, p.genus, "{}: genus", p.file);
        assert!(
            (r.area - p.area).abs() <= 1e-12 * p.area,
            "{}: area {} vs {}",
            p.file,
            r.area,
            p.area
        );
        match (r.volume, p.volume) {
            (Some(a), Some(b)) => assert!(
                (a - b).abs() <= 1e-11 * b.abs(),
                "{}: volume {a} vs {b}",
                p.file
            ),
            (a, b) => assert_eq!(a, b, "{}: volume", p.file),
        }
        assert_eq!(r.usable_as, expected_usability(p), "{}: verdict", p.file);
        assert_eq!(r.inverted_components, 0, "{}", p.file);
        // Every model becomes a surface; solids stay solids.
        let surface = Surface::new(mesh, &SurfaceOptions::default())
            .unwrap_or_else(|e| panic!("{}: {e}", p.file));
        assert_eq!(surface.is_solid(), r.usable_as == Usability::Solid);
    }
}

/// Every pinned model is in the shared collection, and only those: a model added there
/// gets its pin.
#[test]
#[cfg_attr(not(shared_meshes), ignore = "needs ../shared/meshes")]
fn every_shared_model_is_pinned() {
    let mut pinned: Vec<String> = PINS.iter().map(|p| p.file.to_owned()).collect();
    pinned.sort();
    assert_eq!(
        models_on_disk(),
        pinned,
        "every model is pinned, and only those"
    );
}

#[test]
fn units_scale_the_report() {
    let bytes =
        std::fs::read(support::meshes().join("models/20mm-xyz-cube.stl")).expect("readable");
    let options = ReadOptions {
        units: "mm".parse().expect("a unit"),
        ..Default::default()
    };
    let r = MeshReport::of(&read_mesh("20mm-xyz-cube.stl", &bytes, &options).expect("loads"));
    let size: Vec<f64> = (0..3).map(|i| r.bounds_max[i] - r.bounds_min[i]).collect();
    for s in size {
        assert!(
            (s - 0.020).abs() < 1e-6,
            "a 20 mm cube is 0.02 m across: {s}"
        );
    }
    let volume = r.volume.expect("closed");
    assert!(
        (volume - 7_938.681_876_334_816e-9).abs() < 1e-15,
        "{volume}"
    );
}
