//! Building each library's structures for one mesh, timed and weighed: haphe's surface and
//! voxel map (and the decoding of their saved form), parry's `TriMesh` with pseudo-normals.
//!
//! Builds alternate between haphe and parry (which goes first alternates too), a few
//! times on small meshes and once on large ones; the structures of the last build are
//! kept for the queries. Memory is what the counting allocator ([`super::alloc`]) sees
//! the structure hold once built, its copy of the input arrays included; haphe's own
//! account ([`Surface::heap_bytes`] + [`VoxelMap::heap_bytes`]) is kept beside it.

use std::time::{Duration, Instant};

use anyhow::Context as _;
use haphe::map::{MapBytes, MapOptions, VoxelMap, decode_in_place, encode};
use haphe::mesh::{Mesh, Surface, SurfaceOptions};
use parry3d_f64::shape::{TriMesh, TriMeshFlags};

use super::alloc::live_bytes;

/// Meshes up to this many triangles are built [`SMALL_MESH_BUILDS`] times, larger ones
/// once.
const SMALL_MESH_TRIANGLES: usize = 200_000;
/// Builds (and decodes) per library of a small mesh.
const SMALL_MESH_BUILDS: usize = 3;

/// What building cost.
pub struct BuildCost {
    /// haphe: `Surface::new` plus `VoxelMap::build`, per build.
    pub haphe: Vec<Duration>,
    /// parry: `TriMesh::with_flags(.., ORIENTED)`, per build (empty when parry refused
    /// the mesh).
    pub parry: Vec<Duration>,
    /// haphe: `decode` of the encoded surface and map, per decode.
    pub decode: Vec<Duration>,
    /// Heap bytes of haphe's surface and map, counted by the allocator.
    pub haphe_bytes: usize,
    /// Heap bytes of haphe's surface and map by their own `heap_bytes`.
    pub haphe_heap_bytes: usize,
    /// Heap bytes of parry's mesh, counted by the allocator.
    pub parry_bytes: Option<usize>,
    /// Size of the saved surface and map, bytes.
    pub file_bytes: usize,
    /// haphe: `Shape::prepare_clear_zones` on the shape the queries use (filled in when
    /// the shape is made).
    pub zones: Vec<Duration>,
}

/// The structures of one mesh, with what they cost.
pub struct Built {
    /// haphe's surface.
    pub surface: Surface,
    /// haphe's voxel map.
    pub map: VoxelMap,
    /// parry's mesh, or why parry refused it.
    pub parry: Result<TriMesh, String>,
    /// Times and bytes.
    pub cost: BuildCost,
}

/// Builds haphe's and parry's structures for `mesh`, timing and weighing them.
///
/// # Errors
/// When haphe cannot build a surface or a map of the mesh, or cannot read back its own
/// encoding.
pub fn build(mesh: Mesh) -> anyhow::Result<Built> {
    let builds = if mesh.triangles.len() <= SMALL_MESH_TRIANGLES {
        SMALL_MESH_BUILDS
    } else {
        1
    };
    let mut haphe_times = Vec::new();
    let mut parry_times = Vec::new();
    let mut haphe: Option<(Surface, VoxelMap, usize)> = None;
    let mut parry: Option<(Result<TriMesh, String>, usize)> = None;
    for round in 0..builds {
        for haphe_turn in [round % 2 == 0, round % 2 == 1] {
            if haphe_turn {
                drop(haphe.take()); // the previous build goes before the next is weighed
                let before = live_bytes();
                let input = mesh.clone();
                let start = Instant::now();
                let surface = Surface::new(input, &SurfaceOptions::default())
                    .context("haphe cannot build a surface of this mesh")?;
                let map = VoxelMap::build(&surface, &MapOptions::default())
                    .context("haphe cannot build a voxel map of this mesh")?;
                haphe_times.push(start.elapsed());
                haphe = Some((surface, map, live_bytes().saturating_sub(before)));
            } else {
                drop(parry.take());
                let before = live_bytes();
                let (vertices, triangles) = (mesh.vertices.clone(), mesh.triangles.clone());
                let start = Instant::now();
                let built = TriMesh::with_flags(vertices, triangles, TriMeshFlags::ORIENTED);
                let elapsed = start.elapsed();
                let bytes = live_bytes().saturating_sub(before);
                parry = Some(match built {
                    Ok(trimesh) => {
                        parry_times.push(elapsed);
                        (Ok(trimesh), bytes)
                    }
                    Err(e) => (Err(e.to_string()), 0),
                });
            }
        }
    }
    drop(mesh);
    let (Some((surface, map, haphe_bytes)), Some((parry, parry_bytes))) = (haphe, parry) else {
        anyhow::bail!("no build ran");
    };

    // The saved bytes in one aligned buffer, as a mapped or read file gives them; decoding
    // uses them in place.
    let bytes = MapBytes::copy_from_slice(&encode(&surface, &map));
    let mut decode_times = Vec::new();
    for _ in 0..builds {
        let start = Instant::now();
        let decoded = decode_in_place(&bytes).context("haphe cannot decode its own encoding")?;
        decode_times.push(start.elapsed());
        drop(decoded);
    }

    let cost = BuildCost {
        haphe: haphe_times,
        parry: parry_times,
        decode: decode_times,
        haphe_bytes,
        haphe_heap_bytes: surface.heap_bytes() + map.heap_bytes(),
        parry_bytes: parry.is_ok().then_some(parry_bytes),
        file_bytes: bytes.len(),
        zones: Vec::new(),
    };
    Ok(Built {
        surface,
        map,
        parry,
        cost,
    })
}
