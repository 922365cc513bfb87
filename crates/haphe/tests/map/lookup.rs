//! Lookups take any input without a panic: cell indices far outside the grid, points
//! anywhere.

use super::file::sample;
use super::*;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// Accessors take any index without a panic; outside the grid they say outside.
    #[test]
    fn accessors_take_any_index(c in any::<[u32; 3]>()) {
        let (_, map, _) = sample();
        let inside = map.grid().contains(c);
        let _ = map.clearance(c);
        if !inside {
            prop_assert_eq!(map.state(c), CellState::Outside);
            prop_assert_eq!(map.clearance(c), 0);
            prop_assert!(map.triangles_in(c).is_empty());
        }
    }

    /// Grid lookups take any point without a panic, and agree with the cell bounds.
    #[test]
    fn cell_of_agrees_with_cell_bounds(p in prop::array::uniform3(-0.3f64..0.3)) {
        let (_, map, _) = sample();
        let grid: &Grid = map.grid();
        let p = DVec3::from_array(p);
        match grid.cell_of(p) {
            Some(c) => {
                let (lo, hi) = grid.cell_bounds(c);
                let h = grid.cell_size();
                prop_assert!((p - lo).min_element() >= -1e-12 * h && (hi - p).min_element() >= -1e-12 * h);
            }
            None => prop_assert!(p.cmplt(grid.origin()).any() || p.cmpge(grid.max_corner()).any()),
        }
    }
}
