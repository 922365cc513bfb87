//! Clearance and reach: free cells around every non-surface cell, exact near the surface,
//! and growing with the distance in bricks far from it.

use super::*;

/// Clearance semantics straight from the definition, on small grids: every cell within
/// Chebyshev distance below a cell's clearance is a non-surface cell, and a cell one
/// further is a surface cell unless the clearance is the cap (exact distances) — in
/// bricks holding or touching a surface cell's brick.
#[test]
fn clearance_means_free_cells_around() {
    for (name, surface) in solids().into_iter().take(3) {
        let options = MapOptions {
            triangles_per_cell: 8.0,
            ..MapOptions::default()
        };
        let map = build(&surface, &options);
        let [dx, dy, dz] = map.grid().dims();
        let dims = [dx, dy, dz].map(i64::from);
        let mut exact_checked = 0;
        for z in 0..dz {
            for y in 0..dy {
                for x in 0..dx {
                    let c = [x, y, z];
                    if map.state(c) == CellState::Surface {
                        assert_eq!(map.clearance(c), 0);
                        continue;
                    }
                    let k = i64::from(map.clearance(c));
                    assert!((1..=i64::from(MAX_CLEARANCE)).contains(&k), "{name}: {c:?}");
                    // The cube of cells at distance < k, and the shell at distance k.
                    let mut surface_at_k = false;
                    for oz in -k..=k {
                        for oy in -k..=k {
                            for ox in -k..=k {
                                let n = [i64::from(x) + ox, i64::from(y) + oy, i64::from(z) + oz];
                                if (0..3).any(|a| n[a] < 0 || n[a] >= dims[a]) {
                                    continue;
                                }
                                let n = n.map(|v| v as u32);
                                let d = ox.abs().max(oy.abs()).max(oz.abs());
                                let is_surface = map.state(n) == CellState::Surface;
                                assert!(
                                    d == k || !is_surface,
                                    "{name}: {c:?} has clearance {k} but {n:?} at {d} is surface"
                                );
                                surface_at_k |= d == k && is_surface;
                            }
                        }
                    }
                    // Exact where the brick or one of its 26 neighbours holds a surface
                    // cell: some surface cell lies at exactly distance k.
                    let brick = c.map(|v| i64::from(v / 8));
                    let near_surface_brick = (0..27 * 512).any(|i| {
                        let (nb, l) = (i / 512, i % 512);
                        let n = [
                            (brick[0] + nb % 3 - 1) * 8 + l % 8,
                            (brick[1] + nb / 3 % 3 - 1) * 8 + l / 8 % 8,
                            (brick[2] + nb / 9 - 1) * 8 + l / 64,
                        ];
                        n.iter().all(|&v| v >= 0)
                            && map.state(n.map(|v| v as u32)) == CellState::Surface
                    });
                    if near_surface_brick && k < i64::from(MAX_CLEARANCE) {
                        assert!(surface_at_k, "{name}: {c:?} clearance {k} is not exact");
                        exact_checked += 1;
                    }
                }
            }
        }
        assert!(exact_checked > 100, "{name}");
    }
}

/// On grids much finer than the automatic one, much of the inside of a round solid lies
/// several bricks from the surface: there the reach exceeds the clearance cap, and still never the distance
/// to the nearest surface cell (checked against the dense reference for every cell).
#[test]
fn reach_grows_with_the_distance_in_bricks() {
    let round = solids()
        .into_iter()
        .filter(|(name, _)| ["sphere", "blob"].contains(name));
    for (name, surface) in round {
        let h = build(&surface, &MapOptions::default()).grid().cell_size();
        let options = MapOptions {
            cell_size_m: Some(h * 0.16),
            ..MapOptions::default()
        };
        let map = build(&surface, &options);
        assert_matches_dense(&format!("{name} ×0.16"), &surface, &map);
        let [dx, dy, dz] = map.grid().dims();
        let far = (0..dz)
            .flat_map(|z| (0..dy).flat_map(move |y| (0..dx).map(move |x| [x, y, z])))
            .filter(|&c| map.reach(c) > u32::from(MAX_CLEARANCE))
            .count();
        assert!(far > 10_000, "{name}: {far} cells reach beyond the cap");
    }
}
