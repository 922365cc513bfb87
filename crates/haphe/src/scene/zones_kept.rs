//! Clear zones kept from one version of a shape to the next: a triangle of the new
//! version that was a triangle of the old one, with the same corners, keeps its zone
//! unless a new triangle comes within the zone's reach; the others are computed again.

use std::collections::HashMap;
use std::sync::atomic::{AtomicU64, Ordering};

use glam::DVec3;

use super::shape::Shape;
use crate::map::CellBox;
use crate::mesh::TriId;
use crate::query::ClearZone;

impl Shape {
    /// This shape (a new version of `previous`) with every clear zone computed, those of
    /// `previous` kept where they still hold: for triangle `t` whose corners are those of
    /// triangle `same(t)` of `previous`, on the same grid, when no triangle of `fresh`
    /// (new, or moved: increasing indices of this shape) comes within its zone's reach.
    /// A triangle that left a zone leaves it clearer, so the zone kept stays true.
    pub(crate) fn with_zones_kept(
        mut self,
        previous: &Shape,
        fresh: &[u32],
        same: impl Fn(u32) -> Option<u32>,
    ) -> Shape {
        if self.map.grid() == previous.map.grid() && self.zone_height == previous.zone_height {
            let stale = stale_zones(&self, fresh);
            self.zones = stale
                .iter()
                .enumerate()
                .map(|(t, &stale)| {
                    let kept = same(t as u32)
                        .filter(|_| !stale)
                        .and_then(|old| previous.zones.get(old as usize))
                        .map_or(0, |z| z.load(Ordering::Relaxed));
                    AtomicU64::new(kept)
                })
                .collect();
        }
        self.prepare_clear_zones();
        self
    }
}

/// Which triangles' clear zones a deformation may have changed (on an unchanged grid):
/// the moved triangles, and those whose zone's reach meets a moved triangle's box. A
/// triangle that left a zone leaves it clearer, so the zone it had stays true.
fn stale_zones(shape: &Shape, moved: &[u32]) -> Vec<bool> {
    use crate::par::*;
    let (surface, map) = (shape.surface(), shape.map());
    let grid = map.grid();
    // The moved triangles' boxes, by the bricks of cells they meet.
    let brick = |p: DVec3| {
        let c = CellBox::around(grid, p, p).lo;
        c.map(|k| k.div_euclid(8))
    };
    let mut boxes: Vec<(DVec3, DVec3)> = Vec::with_capacity(moved.len());
    let mut by_brick: HashMap<[i64; 3], Vec<u32>> = HashMap::new();
    for &t in moved {
        let [a, b, c] = surface.corners(TriId(t));
        let (lo, hi) = (a.min(b).min(c), a.max(b).max(c));
        let (blo, bhi) = (brick(lo), brick(hi));
        for x in blo[0]..=bhi[0] {
            for y in blo[1]..=bhi[1] {
                for z in blo[2]..=bhi[2] {
                    by_brick
                        .entry([x, y, z])
                        .or_default()
                        .push(boxes.len() as u32);
                }
            }
        }
        boxes.push((lo, hi));
    }
    let Some(all) = boxes
        .iter()
        .copied()
        .reduce(|(lo, hi), (l, h)| (lo.min(l), hi.max(h)))
    else {
        return vec![false; surface.triangle_count()];
    };
    let mut stale = vec![false; surface.triangle_count()];
    for &t in moved {
        stale[t as usize] = true;
    }
    stale
        .par_iter_mut()
        .enumerate()
        .filter(|(_, s)| !**s)
        .for_each(|(t, s)| {
            let Some((lo, hi)) = ClearZone::reach_box(surface, map, TriId(t as u32)) else {
                return;
            };
            if lo.cmpgt(all.1).any() || hi.cmplt(all.0).any() {
                return;
            }
            let (blo, bhi) = (brick(lo), brick(hi));
            'bricks: for x in blo[0]..=bhi[0] {
                for y in blo[1]..=bhi[1] {
                    for z in blo[2]..=bhi[2] {
                        let Some(listed) = by_brick.get(&[x, y, z]) else {
                            continue;
                        };
                        if listed.iter().any(|&i| {
                            let (l, h) = boxes[i as usize];
                            l.cmple(hi).all() && h.cmpge(lo).all()
                        }) {
                            *s = true;
                            break 'bricks;
                        }
                    }
                }
            }
        });
    stale
}
