//! The scene's force effects ([`Effect`](crate::scene::Effect)), evaluated for one device
//! each tick after its proxy: each bounded by the device's maximum force, added to the
//! proxy's force, the sum clamped to that maximum.

use std::f64::consts::TAU;

use glam::DVec3;

use crate::proxy::{Contact, clamp_force};
use crate::query::{Side, classify_point, nearest_within};
use crate::scene::{EffectKind, MAX_EFFECTS, Scene, Zone};

/// What one device's effects remember from tick to tick: the stick-slip anchors, one slot
/// per effect of the scene.
#[derive(Debug, Clone, Copy)]
pub(super) struct EffectState {
    anchors: [Option<DVec3>; MAX_EFFECTS],
}

impl EffectState {
    pub(super) const fn new() -> EffectState {
        EffectState {
            anchors: [None; MAX_EFFECTS],
        }
    }
}

/// The device on this tick, as the effects see it: its point and velocity (world frame),
/// the time (seconds since the start) and the proxy's contact.
pub(super) struct Sensed<'a> {
    pub(super) hip: DVec3,
    pub(super) velocity: DVec3,
    pub(super) t: f64,
    pub(super) contact: Option<&'a Contact>,
}

/// The sum of the scene's effects on the device (newtons, world frame), each bounded by
/// `max_force`; zero without effects.
///
/// # Real-time
/// No allocation, no lock, no panic; per effect a few products, except a viscosity inside
/// an object (one inside test) and a magnet (a nearest-triangle search within its
/// distance over the objects near the device point, which grows with that distance).
pub(super) fn effects_force(
    scene: &Scene,
    state: &mut EffectState,
    sensed: &Sensed<'_>,
    max_force: f64,
) -> DVec3 {
    let mut total = DVec3::ZERO;
    for (e, anchor) in scene.effects().iter().zip(&mut state.anchors) {
        let f = match e.kind {
            EffectKind::Vibration {
                frequency,
                amplitude,
            } => sensed.contact.map_or(DVec3::ZERO, |c| {
                amplitude * (TAU * frequency * sensed.t).sin() * c.normal
            }),
            EffectKind::Viscosity { viscosity, zone } => {
                if in_zone(scene, zone, sensed.hip) {
                    -viscosity * sensed.velocity
                } else {
                    DVec3::ZERO
                }
            }
            EffectKind::Spring { stiffness, anchor } => stiffness * (anchor - sensed.hip),
            EffectKind::Magnet { distance, force } => magnet(scene, sensed, distance, force),
            EffectKind::Constant { force } => force,
            EffectKind::StickSlip {
                stiffness,
                breakaway,
            } => stick_slip(anchor, sensed, stiffness, breakaway),
        };
        total += clamp_force(f, max_force).0;
    }
    total
}

/// Whether the device point `p` lies in `zone`.
fn in_zone(scene: &Scene, zone: Zone, p: DVec3) -> bool {
    match zone {
        Zone::Everywhere => true,
        Zone::Box { min, max } => p.cmpge(min).all() && p.cmple(max).all(),
        Zone::Inside(id) => scene.index_of(id).is_some_and(|i| {
            let o = &scene.objects()[i];
            let shape = &*o.shape;
            shape.is_solid()
                && classify_point(shape.surface(), shape.map(), o.pose.to_object(p)).0
                    == Side::Inside
        }),
    }
}

/// A magnet's pull: in contact, `force` into the surface (against the contact normal);
/// free, `force` toward the nearest surface point within `distance` of the device point.
fn magnet(scene: &Scene, sensed: &Sensed<'_>, distance: f64, force: f64) -> DVec3 {
    if let Some(c) = sensed.contact {
        return -force * c.normal;
    }
    let p = sensed.hip;
    let reach = DVec3::splat(distance);
    let objects = scene.objects();
    let mut nearest: Option<(f64, DVec3)> = None;
    for i in scene.near(p - reach, p + reach).indices(objects.len()) {
        let o = &objects[i];
        let shape = &*o.shape;
        let within = nearest.map_or(distance, |(d, _)| d);
        if let Some(n) = nearest_within(shape.surface(), shape.map(), o.pose.to_object(p), within) {
            let q = o.pose.to_world(n.closest.point);
            let d = q.distance(p);
            if d < within {
                nearest = Some((d, q));
            }
        }
    }
    nearest
        .and_then(|(_, q)| (q - p).try_normalize())
        .map_or(DVec3::ZERO, |u| force * u)
}

/// Stick-slip: in contact, `stiffness` times the device point's offset across the surface
/// from the anchor (set where contact began); beyond `breakaway` newtons the anchor jumps
/// to the device point and the force drops to zero. Out of contact the anchor is dropped.
fn stick_slip(
    anchor: &mut Option<DVec3>,
    sensed: &Sensed<'_>,
    stiffness: f64,
    breakaway: f64,
) -> DVec3 {
    let Some(c) = sensed.contact else {
        *anchor = None;
        return DVec3::ZERO;
    };
    let a = *anchor.get_or_insert(sensed.hip);
    let offset = a - sensed.hip;
    let across = offset - offset.dot(c.normal) * c.normal;
    let f = stiffness * across;
    if f.length() > breakaway {
        *anchor = Some(sensed.hip);
        DVec3::ZERO
    } else {
        f
    }
}
