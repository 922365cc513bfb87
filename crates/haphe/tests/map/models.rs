//! Maps of the real meshes (closed and open, CAD and scanned).

use super::*;

/// Every real model (the repository's `meshes/`, or the shared collection when present;
/// closed and open, CAD and scanned): triangles listed exactly where they overlap, sampled
/// free cells classified as the winding number says (solids) or all outside (open
/// surfaces), and the file round trip.
#[test]
fn every_real_model_gets_a_consistent_map() {
    for (name, path) in support::model_files() {
        let bytes = std::fs::read(&path).expect("readable");
        let mesh = haphe::mesh::read_mesh(&name, &bytes, &haphe::mesh::ReadOptions::default())
            .unwrap_or_else(|e| panic!("{e}"));
        let Ok(surface) = Surface::new(mesh, &SurfaceOptions::default()) else {
            continue;
        };
        let map = build(&surface, &MapOptions::default());
        let grid = map.grid();
        for t in 0..surface.triangle_count() as u32 {
            let corners = surface.corners(TriId(t));
            for c in cells_around(grid, corners, 1) {
                assert_eq!(
                    map.triangles_in(c).contains(&t),
                    grid.overlaps_cell(corners, c),
                    "{name}: triangle {t} in cell {c:?}"
                );
            }
        }
        let stats = map.stats();
        if !surface.is_solid() {
            assert_eq!(stats.inside_cells, 0, "{name}");
        } else {
            // Free cells at least two cells from any surface cell, spread over the grid.
            let [dx, dy, dz] = grid.dims();
            let free: Vec<[u32; 3]> = (0..dz)
                .flat_map(|z| (0..dy).flat_map(move |y| (0..dx).map(move |x| [x, y, z])))
                .filter(|&c| map.state(c) != CellState::Surface && map.clearance(c) >= 3)
                .collect();
            let stride = (free.len() / 150).max(1);
            for &c in free.iter().step_by(stride) {
                let w = winding_number(&surface, grid.cell_centre(c));
                let expected = if w.abs() > 0.5 {
                    CellState::Inside
                } else {
                    CellState::Outside
                };
                assert_eq!(
                    map.state(c),
                    expected,
                    "{name}: cell {c:?}, winding number {w}"
                );
            }
        }
        let (_, loaded) = decode(&encode(&surface, &map)).expect("round trip");
        assert_eq!(loaded, map, "{name}");
    }
}
