//! The objects near the proxy: which objects a tick's searches look at, found in the
//! scene's broad phase and kept from one tick to the next while they stay valid.

use glam::DVec3;

use crate::query::ToolNear;
use crate::scene::{Near, Scene};

/// Least growth of a remembered box, metres, so that a hand moving slowly keeps the same
/// candidates over many ticks (a millimetre: a tick's travel at 1 m/s and 1 kHz).
const FAT: f64 = 1e-3;

/// Growth of a remembered box in multiples of the size of the search that made it, so that
/// a hand moving steadily keeps the same candidates for several ticks: the broad phase's
/// cells are at least as large as the objects in them, so a box a few steps larger rarely
/// holds more candidates, while a query costs far more than a tick's other bookkeeping.
const GROWTH: f64 = 8.0;

/// Scenes of at most this many objects skip the broad phase: a bounding-sphere test per
/// object (the first step of `Scene::first_hit` and `Scene::touching`) costs
/// less than checking the remembered box, let alone asking the broad phase again.
const SMALL_SCENE: usize = 4;

/// The candidate objects of the proxy's searches: a [`Near`] set for a box, kept while the
/// scene's broad phase is unchanged (same scene, no object changed cell) and every search
/// lies in the box. A search outside the box asks the broad phase again, for its own box
/// grown by [`GROWTH`] times its size (at least [`FAT`]), so that the next searches of the
/// tick and of the following ticks fall inside.
#[derive(Debug, Clone, Copy)]
pub(crate) struct NearCache {
    near: Near,
    lo: DVec3,
    hi: DVec3,
    key: Option<(u64, u64)>,
    /// Every object is a candidate (the linear path, the oracle of the broad phase).
    linear: bool,
    /// The triangles near the tool (a tool with a size only).
    tool: ToolNear,
}

impl NearCache {
    /// An empty cache.
    pub(crate) const fn new() -> NearCache {
        NearCache {
            near: Near::ALL,
            lo: DVec3::ZERO,
            hi: DVec3::ZERO,
            key: None,
            linear: false,
            tool: ToolNear::EMPTY,
        }
    }

    /// A cache that always answers "every object".
    #[cfg(any(test, feature = "testing"))]
    pub(crate) const fn linear() -> NearCache {
        NearCache {
            linear: true,
            ..NearCache::new()
        }
    }

    /// Whether every search tests every object.
    pub(crate) fn is_linear(&self) -> bool {
        self.linear
    }

    /// A superset of the objects of `scene` whose bounding sphere comes within the box
    /// `lo..hi` that `search` gives (called only when the broad phase is asked: a small
    /// scene never computes the box).
    ///
    /// # Real-time
    /// No allocation: at most two broad-phase queries, none when the remembered box holds
    /// this one or the scene is small.
    #[inline]
    pub(crate) fn get(&mut self, scene: &Scene, search: impl FnOnce() -> (DVec3, DVec3)) -> &Near {
        if self.linear || scene.objects().len() <= SMALL_SCENE {
            return &Near::ALL;
        }
        let (lo, hi) = search();
        self.kept(scene, lo, hi)
    }

    /// [`NearCache::get`] for a scene that asks its broad phase: the remembered set, asked
    /// again when the box is not inside the remembered one.
    fn kept(&mut self, scene: &Scene, lo: DVec3, hi: DVec3) -> &Near {
        let key = Some(scene.broad_epoch());
        let inside = self.key == key && lo.cmpge(self.lo).all() && hi.cmple(self.hi).all();
        if !inside {
            let grow = DVec3::splat(((hi - lo).max_element() * GROWTH).max(FAT));
            let (mut l, mut h) = (lo - grow, hi + grow);
            scene.near_into(l, h, &mut self.near);
            if self.near.all() {
                (l, h) = (lo, hi);
                scene.near_into(l, h, &mut self.near);
            }
            (self.lo, self.hi) = (l, h);
            self.key = (l.is_finite() && h.is_finite()).then_some(key).flatten();
        }
        &self.near
    }

    /// [`NearCache::get`], and the triangles kept near the tool.
    #[inline]
    pub(crate) fn parts(
        &mut self,
        scene: &Scene,
        search: impl FnOnce() -> (DVec3, DVec3),
    ) -> (Near, &mut ToolNear) {
        let near = *self.get(scene, search);
        (near, &mut self.tool)
    }
}

/// The box of a search along `p0 → p1` (or at a point) whose probes reach `reach` beyond
/// its ends: the segment's box grown by twice the reach.
pub(crate) fn search_box(p0: DVec3, p1: DVec3, reach: f64) -> (DVec3, DVec3) {
    let m = DVec3::splat(2.0 * reach.max(0.0));
    (p0.min(p1) - m, p0.max(p1) + m)
}
