//! Stage 1 benches: read (binary STL, OBJ), weld, validate (report) and build the topology
//! (`Surface::new`) of a procedural blob of about 10 000 triangles.
//!
//! `cargo bench -p haphe --bench mesh`; `cargo test --benches` runs each once.

use std::fmt::Write as _;
use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use haphe::mesh::shapes::Catalog;
use haphe::mesh::{
    Format, Mesh, MeshReport, ReadOptions, Surface, SurfaceOptions, Weld, read_unwelded, weld,
};

/// Triangles of the benchmark mesh: large enough to leave the caches' sweet spot, small
/// enough that `cargo test --benches` stays quick.
const TRIANGLES: usize = 10_000;

/// Binary STL bytes of `mesh`: every triangle with its own three corners, as files have them.
fn binary_stl(mesh: &Mesh) -> Vec<u8> {
    let mut bytes = vec![0u8; 80];
    bytes.extend_from_slice(&(mesh.triangles.len() as u32).to_le_bytes());
    for t in 0..mesh.triangles.len() {
        let corners = mesh.corners(t);
        let normal = (corners[1] - corners[0])
            .cross(corners[2] - corners[0])
            .normalize_or_zero();
        for p in std::iter::once(normal).chain(corners) {
            for x in p.to_array() {
                bytes.extend_from_slice(&(x as f32).to_le_bytes());
            }
        }
        bytes.extend_from_slice(&[0, 0]);
    }
    bytes
}

/// OBJ text of `mesh`, shared vertices, full `f64` precision.
fn obj(mesh: &Mesh) -> String {
    let mut text = String::new();
    for p in &mesh.vertices {
        let _ = writeln!(text, "v {} {} {}", p.x, p.y, p.z);
    }
    for [a, b, c] in &mesh.triangles {
        let _ = writeln!(text, "f {} {} {}", a + 1, b + 1, c + 1);
    }
    text
}

fn mesh_stage(c: &mut Criterion) {
    let mesh = Catalog::Blob.with_triangles(TRIANGLES);
    let stl = binary_stl(&mesh);
    let obj = obj(&mesh);
    let stl_options = ReadOptions {
        format: Some(Format::Stl),
        ..ReadOptions::default()
    };
    let obj_options = ReadOptions {
        format: Some(Format::Obj),
        ..ReadOptions::default()
    };
    let unwelded = read_unwelded("blob.stl", &stl, &stl_options).expect("the STL reads");

    let mut group = c.benchmark_group("mesh");
    group.bench_function("read_stl_binary", |b| {
        b.iter(|| read_unwelded("blob.stl", black_box(&stl), &stl_options))
    });
    group.bench_function("read_obj", |b| {
        b.iter(|| read_unwelded("blob.obj", black_box(obj.as_bytes()), &obj_options))
    });
    group.bench_function("weld_exact", |b| {
        b.iter(|| weld(black_box(&unwelded), Weld::Exact))
    });
    group.bench_function("report", |b| b.iter(|| MeshReport::of(black_box(&mesh))));
    group.bench_function("surface_new", |b| {
        b.iter_batched(
            || mesh.clone(),
            |m| Surface::new(m, &SurfaceOptions::default()),
            criterion::BatchSize::LargeInput,
        )
    });
    group.finish();
}

criterion_group!(benches, mesh_stage);
criterion_main!(benches);
