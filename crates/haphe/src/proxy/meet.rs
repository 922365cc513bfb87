//! What the proxy meets in the scene: the first surface along a move over every object,
//! the surface it touches, the carry of objects that moved, and moves that stop before
//! a surface. Only the objects near the proxy are asked (see [`NearCache`]). The objects
//! met are kept by index from one tick to the next, and followed across removals.

use glam::DVec3;

use super::constraints::{Plane, advance_to_plane};
use super::near::{NearCache, search_box};
use super::options::ProxyOptions;
use crate::scene::{Hit, Scene, SurfaceRef};

/// The first hit of the world segment `p0 → p1` over every object; ties go to the lower
/// object index. Only the objects near the segment are tested (see [`NearCache`]). With a
/// tool radius, the first place the tool's sphere touches an object (`hint`: a surface
/// likely met first, tested first; the answer does not depend on it).
#[inline]
pub(crate) fn first_hit_all(
    scene: &Scene,
    near: &mut NearCache,
    (p0, p1): (DVec3, DVec3),
    options: &ProxyOptions,
    hint: Option<SurfaceRef>,
) -> Option<Hit> {
    if options.tool_radius == 0.0 && scene.objects().len() <= 1 {
        // The only candidate's hit, as it comes (`None` in an empty scene).
        return scene.first_hit(0, p0, p1, options.probe_reach());
    }
    first_hit_among(scene, near, (p0, p1), options, hint)
}

/// [`first_hit_all`] over the candidates of `near`, the first hit kept.
fn first_hit_among(
    scene: &Scene,
    near: &mut NearCache,
    (p0, p1): (DVec3, DVec3),
    options: &ProxyOptions,
    hint: Option<SurfaceRef>,
) -> Option<Hit> {
    let (reach, radius) = (options.probe_reach(), options.tool_radius);
    let search = || search_box(p0, p1, reach);
    let mut best: Option<Hit> = None;
    let mut keep = |h: Hit| {
        if best.is_none_or(|b| h.t < b.t) {
            best = Some(h);
        }
    };
    if radius > 0.0 {
        let (objects, kept) = near.parts(scene, || {
            let (lo, hi) = search();
            (lo - radius, hi + radius)
        });
        for i in objects.indices(scene.objects().len()) {
            let hint = hint.filter(|h| h.object == i).map(|h| h.triangle);
            let tool = (radius, reach);
            scene
                .first_tool_hit(i, (p0, p1), tool, (hint, &mut *kept))
                .map(&mut keep);
        }
    } else {
        for i in near.get(scene, search).indices(scene.objects().len()) {
            scene.first_hit(i, p0, p1, reach).map(&mut keep);
        }
    }
    best
}

/// The surface within a probe's reach of the world point `p` (of the tool's surface, with
/// a tool radius) of the lowest-index object that has one (see [`Scene::touching`]).
#[inline]
pub(crate) fn touching_any(
    scene: &Scene,
    near: &mut NearCache,
    p: DVec3,
    options: &ProxyOptions,
) -> Option<Hit> {
    let (reach, radius) = (options.probe_reach(), options.tool_radius);
    if radius == 0.0 && scene.objects().len() <= 1 {
        // The only candidate's answer, as it comes (`None` in an empty scene).
        return scene.touching(0, p, reach);
    }
    let search = || search_box(p, p, reach);
    if radius > 0.0 {
        let (objects, kept) = near.parts(scene, || {
            let (lo, hi) = search();
            (lo - radius, hi + radius)
        });
        return objects
            .indices(scene.objects().len())
            .find_map(|i| scene.tool_touching(i, p, (radius, reach), kept));
    }
    near.get(scene, search)
        .indices(scene.objects().len())
        .find_map(|i| scene.touching(i, p, reach))
}

/// The constraint plane of `hit`, met by the move `from → to`: the triangle's plane moved
/// out by the skin (see [`Plane::of_hit`]); with a tool radius, the plane tangent to the
/// triangle's offset by the radius where the tool touched it, moved out by the skin.
pub(super) fn hit_plane(hit: &Hit, from: DVec3, to: DVec3, options: &ProxyOptions) -> Plane {
    let radius = options.tool_radius;
    if radius > 0.0 {
        Plane {
            normal: hit.normal,
            offset: hit.normal.dot(hit.point) + radius + options.skin,
        }
    } else {
        Plane::of_hit(hit.normal, hit.point, hit.one_sided, from, to, options.skin)
    }
}

/// Moving objects carry the proxy: for each object that moved since the previous tick (in
/// index order), the proxy's motion relative to it is tested in its frame and stopped a
/// skin's width before its surface.
///
/// Only the objects moved this tick are looked at; when none turned, only those whose
/// cell in the broad phase lies within twice the largest shift of the proxy (a moved
/// object's path relative to the proxy is as long as its shift), asked again after each
/// stop that takes the proxy farther than one shift from where the query was made.
pub(super) fn carry(
    scene: &Scene,
    near: &mut NearCache,
    mut p: DVec3,
    options: &ProxyOptions,
) -> DVec3 {
    if !near.is_linear() && scene.moved_indices().is_empty() {
        // Nothing moved (the common tick): no carry.
        return p;
    }
    let reach = options.probe_reach();
    let carry_one = |i: usize, p: &mut DVec3| {
        let o = &scene.objects()[i];
        if !o.moved() {
            return;
        }
        let from = scene.previous_relative(i, *p);
        let h = if options.tool_radius > 0.0 {
            let mut kept = crate::query::ToolNear::EMPTY;
            let tool = (options.tool_radius, reach);
            scene.first_tool_hit(i, (from, *p), tool, (None, &mut kept))
        } else {
            scene.first_hit(i, from, *p, reach)
        };
        if let Some(h) = h {
            *p = advance_to_plane(from, *p, &hit_plane(&h, from, *p, options));
        }
    };
    if near.is_linear() {
        for i in 0..scene.objects().len() {
            carry_one(i, &mut p);
        }
        return p;
    }
    let moved = scene.moved_indices();
    if moved.is_empty() {
        return p;
    }
    let Some(shift) = scene.moved_shift() else {
        for &i in moved {
            carry_one(i as usize, &mut p);
        }
        return p;
    };
    let mut next = 0;
    'query: loop {
        let centre = p;
        let m = DVec3::splat(2.0 * shift + 3.0 * reach + options.tool_radius);
        let found = scene.near(centre - m, centre + m);
        if found.all() {
            for &i in moved.iter().filter(|&&i| i as usize >= next) {
                carry_one(i as usize, &mut p);
            }
            return p;
        }
        for i in found.indices(scene.objects().len()).filter(|&i| i >= next) {
            carry_one(i, &mut p);
            if p.distance(centre) > shift {
                next = i + 1;
                continue 'query;
            }
        }
        return p;
    }
}

/// Moves from `from` toward `to` and stops a skin's width before the first surface met
/// (`hint`: the surface likely met first).
pub(super) fn move_checked(
    scene: &Scene,
    near: &mut NearCache,
    (from, to): (DVec3, DVec3),
    options: &ProxyOptions,
    hint: Option<SurfaceRef>,
) -> DVec3 {
    if from == to {
        return to;
    }
    match first_hit_all(scene, near, (from, to), options, hint) {
        None => to,
        Some(h) => advance_to_plane(from, to, &hit_plane(&h, from, to, options)),
    }
}
