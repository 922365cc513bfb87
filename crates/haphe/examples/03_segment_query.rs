//! The collision core on one object: a fast probe moves through a thin plate in one tick
//! (the segment test catches it), is classified inside or outside, and the surface walk
//! finds the contact point on the side of entry, step by step from the last triangle.
//!
//! ```sh
//! cargo run --release --example 03_segment_query
//! ```

use haphe::DVec3;
use haphe::map::{MapOptions, VoxelMap};
use haphe::mesh::shapes::Catalog;
use haphe::mesh::{Surface, SurfaceOptions};
use haphe::query::{Side, WalkStatus, classify_point, first_crossing, walk_to_nearest};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    // A 0.2 m square plate, 0.1 mm thick, centred on the origin, normal along z.
    let surface = Surface::new(
        Catalog::ThinPlate.with_triangles(2_000),
        &SurfaceOptions::default(),
    )?;
    let map = VoxelMap::build(&surface, &MapOptions::default())?;

    // At 10 m/s and 1 kHz the probe moves 1 cm per tick: from 5 mm above the plate to
    // 5 mm below it. Both samples are outside; only the segment between them shows contact.
    let (above, below) = (
        DVec3::new(0.01, 0.02, 0.005),
        DVec3::new(0.01, 0.02, -0.005),
    );
    for p in [above, below] {
        let (side, _) = classify_point(&surface, &map, p);
        println!(
            "{p:.4}: {}",
            if side == Side::Inside {
                "inside"
            } else {
                "outside"
            }
        );
    }
    let Some(crossing) = first_crossing(&surface, &map, above, below) else {
        return Err("the segment test missed the plate".into());
    };
    println!(
        "crossing at t = {:.4} on triangle {} at {:.6} ({}), normal {:.3}",
        crossing.t,
        crossing.triangle.0,
        crossing.point,
        if crossing.entering {
            "entering"
        } else {
            "leaving"
        },
        crossing.face_normal
    );

    // The nearest point to the lower probe is on the plate's underside; the walk from the
    // entry triangle stays on the side of entry (the top), as a haptic contact must.
    let (contact, status) = walk_to_nearest(&surface, crossing.triangle, below);
    println!(
        "walk from the entry triangle: {:.6} on triangle {}, {:?}, shading normal {:.3} ({:?})",
        contact.point, contact.triangle.0, contact.feature, contact.shading_normal, status
    );
    assert_eq!(status, WalkStatus::Converged);

    // Coherence: following the probe sliding 0.2 mm per tick along the plate, each walk
    // starts at the last answer and ends after zero or one step.
    let mut triangle = contact.triangle;
    for k in 1..=5 {
        let target = above + DVec3::new(2e-4 * f64::from(k), 0.0, -0.004_98);
        let (next, _) = walk_to_nearest(&surface, triangle, target);
        println!(
            "tick {k}: triangle {:>4}, {:.3} mm from the probe",
            next.triangle.0,
            next.distance * 1e3
        );
        triangle = next.triangle;
    }
    Ok(())
}
