//! Read a mesh file (or build a procedural torus), validate it and build its topology.
//!
//! ```sh
//! cargo run --release --example 01_validate                 # a built-in torus
//! cargo run --release --example 01_validate -- part.stl mm   # a file, in millimetres
//! ```

use haphe::mesh::{
    MeshReport, ReadOptions, Surface, SurfaceOptions, TriId, Units, read_mesh, shapes,
};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mesh = match args.first() {
        Some(path) => {
            let units: Units = args.get(1).map_or(Ok(Units::Metres), |u| u.parse())?;
            let bytes = std::fs::read(path)?;
            // Errors name the file and the place (line, byte, face or vertex).
            read_mesh(
                path,
                &bytes,
                &ReadOptions {
                    units,
                    ..Default::default()
                },
            )?
        }
        None => shapes::torus(0.08, 0.03, 48, 24),
    };

    // Every defect, with where it is.
    let report = MeshReport::of(&mesh);
    print!("{report}");
    for problem in report.problems() {
        println!("  problem: {problem}");
    }

    // The navigable form: neighbours, vertex fans, barycentric frames, shading normals.
    let surface = Surface::new(mesh, &SurfaceOptions::default())?;
    let t = TriId(0);
    let [a, b, c] = surface.corners(t);
    let centroid = (a + b + c) / 3.0;
    let weights = surface.frame(t).barycentric(centroid);
    println!(
        "triangle 0: neighbours {:?}, barycentric weights of its centroid {:?}, shading normal {:.3}",
        surface.neighbours(t),
        weights,
        surface.shading_normal(t, weights)
    );
    println!(
        "solid: {}, {} bytes of topology ({:.0} bytes per triangle)",
        surface.is_solid(),
        surface.heap_bytes(),
        surface.heap_bytes() as f64 / surface.triangle_count() as f64
    );
    Ok(())
}
