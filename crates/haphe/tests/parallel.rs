//! The `parallel` feature changes where the work before a servo loop runs, never what it
//! gives. `results` lists everything that work produces on a few meshes (the reader's weld,
//! the mesh report, the surface and map as saved, the self-intersections, the clear zones,
//! a volume voxelised from a mesh and its iso-surface):
//!
//! - with the feature, one thread and four give the same, byte for byte;
//! - `HAPHE_PARALLEL_DIGEST=FILE` writes a digest of it to FILE. CI runs this test with and
//!   without the feature and compares the two files (`.ci/run`).

use std::hash::{DefaultHasher, Hasher};
use std::path::Path;

use haphe::map::{MapOptions, VoxelMap, encode};
use haphe::mesh::shapes::Catalog;
use haphe::mesh::{Mesh, MeshReport, ReadOptions, Surface, SurfaceOptions, read_mesh};
use haphe::query::self_intersections;
use haphe::scene::Shape;
use haphe::volume::{Chunks, Volume};

/// The meshes: procedural (the blob's noise is evaluated in parallel) and one read from a
/// file with duplicate vertices to weld.
fn meshes() -> Vec<(String, Mesh)> {
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../meshes/models/spot.obj");
    let bytes = std::fs::read(&file).expect("the in-tree mesh meshes/models/spot.obj");
    vec![
        ("blob".into(), Catalog::Blob.with_triangles(20_000)),
        (
            "thin-plate".into(),
            Catalog::ThinPlate.with_triangles(5_000),
        ),
        (
            "spot.obj".into(),
            read_mesh("spot.obj", &bytes, &ReadOptions::default()).expect("spot.obj reads"),
        ),
    ]
}

/// Everything the parallel steps produce from the meshes, as bytes.
fn results() -> Vec<u8> {
    let mut out = Vec::new();
    for (name, mesh) in meshes() {
        out.extend(format!("{name}\n{:?}\n", MeshReport::of(&mesh)).bytes());
        let surface = Surface::new(mesh, &SurfaceOptions::default()).expect("a surface");
        let map = VoxelMap::build(&surface, &MapOptions::default()).expect("a map");
        out.extend(encode(&surface, &map));
        out.extend(format!("{:?}\n", self_intersections(&surface, &map)).bytes());
        let shape = Shape::new(surface, map);
        out.extend(format!("clear zones {}\n", shape.prepare_clear_zones()).bytes());
        if name == "blob" {
            // Voxelised at 40 voxels across, and its iso-surface extracted in chunks.
            let volume = Volume::from_shape(&shape, shape.bound_radius() / 20.0)
                .expect("the blob voxelises");
            let mesh = Chunks::extract(&volume).mesh();
            out.extend(format!("{:?}\n{mesh:?}\n", volume.values()).bytes());
        }
    }
    out
}

fn digest(bytes: &[u8]) -> u64 {
    // SipHash with fixed keys: the same in both builds of one toolchain.
    let mut hasher = DefaultHasher::new();
    hasher.write(bytes);
    hasher.finish()
}

#[test]
fn results_do_not_depend_on_the_threads() {
    let all = results();
    let line = format!("{:016x} {} bytes\n", digest(&all), all.len());
    println!("parallel={}: {line}", cfg!(feature = "parallel"));
    if let Some(file) = std::env::var_os("HAPHE_PARALLEL_DIGEST") {
        std::fs::write(&file, &line).expect("write the digest");
    }
    #[cfg(feature = "parallel")]
    for threads in [1, 4] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("a thread pool");
        let again = pool.install(results);
        assert!(again == all, "{threads} thread(s): other results");
    }
}
