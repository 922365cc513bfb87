//! Build the voxel map of a procedural shape, look cells up, save and load it, and time it.
//!
//! ```sh
//! cargo run --release --example 02_build_map                      # a 100k-triangle sphere
//! cargo run --release --example 02_build_map -- torus 1000000     # any shape and size
//! cargo run --release --example 02_build_map -- sphere 1000000 3  # ... and 3 tries, best time
//! ```

use std::time::{Duration, Instant};

use haphe::DVec3;
use haphe::map::{MapOptions, VoxelMap, decode, encode};
use haphe::mesh::shapes::Catalog;
use haphe::mesh::{Surface, SurfaceOptions};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let shape: Catalog = args.first().map_or(Ok(Catalog::Sphere), |s| s.parse())?;
    let target: usize = args.get(1).map_or(Ok(100_000), |s| s.parse())?;
    let tries: u32 = args.get(2).map_or(Ok(1), |s| s.parse())?;

    let mesh = shape.with_triangles(target);
    let surface = Surface::new(mesh, &SurfaceOptions::default())?;
    let triangles = surface.triangle_count();

    // Build: the cell size follows the triangle size (about 3 triangles per surface cell).
    let options = MapOptions::default();
    let (map, build) = best_of(tries, || VoxelMap::build(&surface, &options))?;
    let stats = map.stats();
    println!(
        "{shape}, {triangles} triangles, solid: {}",
        surface.is_solid()
    );
    println!(
        "  cells {:?} = {} ({:.1e} m, {:?})",
        stats.dims, stats.cells, stats.cell_size_m, stats.cell_size_rule
    );
    println!(
        "  surface cells {}, inside {}, outside {}; triangles per surface cell {:.2} (max {})",
        stats.surface_cells,
        stats.inside_cells,
        stats.outside_cells,
        stats.mean_triangles_per_surface_cell,
        stats.max_triangles_per_surface_cell
    );
    println!(
        "  bricks {}: {} detailed, {} graded; {} bytes",
        stats.bricks, stats.detailed_bricks, stats.graded_bricks, stats.bytes
    );
    println!(
        "  build {:.1} ms, {:.1} map bytes per triangle",
        ms(build),
        stats.bytes as f64 / triangles as f64
    );

    // Look cells up: constant time, no allocation.
    let grid = map.grid();
    for p in [
        DVec3::ZERO,
        DVec3::new(0.0, 0.0, 0.3),
        DVec3::new(0.1, 0.0, 0.0),
    ] {
        match grid.cell_of(p) {
            Some(c) => println!(
                "  {p}: cell {c:?} {:?}, clearance {}, {} triangles",
                map.state(c),
                map.clearance(c),
                map.triangles_in(c).len()
            ),
            None => println!("  {p}: outside the grid, so outside the object"),
        }
    }

    // Save and load: one checked file with the surface and its map.
    let start = Instant::now();
    let bytes = encode(&surface, &map);
    let encode_time = start.elapsed();
    let ((_, loaded), decode_time) = best_of(tries, || decode(&bytes))?;
    assert_eq!(loaded, map);
    println!(
        "  file {:.1} MB ({:.0} bytes per triangle): encode {:.1} ms, decode {:.1} ms",
        bytes.len() as f64 / 1e6,
        bytes.len() as f64 / triangles as f64,
        ms(encode_time),
        ms(decode_time)
    );
    Ok(())
}

/// Runs `f` `tries` times (at least once); the last result and the shortest time.
fn best_of<T, E>(tries: u32, mut f: impl FnMut() -> Result<T, E>) -> Result<(T, Duration), E> {
    let start = Instant::now();
    let mut value = f()?;
    let mut best = start.elapsed();
    for _ in 1..tries {
        let start = Instant::now();
        value = f()?;
        best = best.min(start.elapsed());
    }
    Ok((value, best))
}

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}
