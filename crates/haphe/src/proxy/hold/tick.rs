//! The ticks of a proxy that holds beyond the saturation depth (see [`super`]).

use glam::DVec3;

use super::{Hold, is_deep, saturation_depth};
use crate::proxy::constrain::{Start, Sweep, constrain};
use crate::proxy::force::contact_force;
use crate::proxy::godobject::{Hand, Proxy, contact_at};
use crate::proxy::output::{TickOutput, TickStatus};
use crate::scene::{Relief, Scene};

impl Proxy {
    /// The hold of a tick whose god-object steps ended with the device point beyond the
    /// saturation depth: it begins where the proxy first met a surface this tick (the
    /// `sweep`'s touch-down, on the first plane met), with the hand where it was at the
    /// start of the tick and the direction it went deep in this tick's motion, and this
    /// tick is its first. So the tick that goes deep never slides the proxy on toward the
    /// point closest to the hand (over a crest, for a grazing strike into a convex part).
    /// `None`, and nothing changed, where the device point is not deeper than the
    /// saturation depth behind that first plane.
    pub(in crate::proxy) fn hold_from_touch_down(
        &mut self,
        scene: &Scene,
        sweep: &Sweep,
        hand: &Hand,
        input_clamped: bool,
    ) -> Option<TickOutput> {
        let first = sweep.first_hit?;
        let plane = sweep.planes.planes().first()?;
        let object = scene.objects().get(first.object)?;
        let entry = sweep.touch_down;
        let hold = Hold::begin(
            &object.pose,
            (first, 1),
            (entry, plane.normal),
            hand.previous.unwrap_or(hand.hip),
            (hand.previous, hand.hip),
        );
        // The same test as the hold's own, so that it goes ahead once begun.
        let depth = saturation_depth(object.hold_material(), self.options.max_force);
        if !is_deep(entry, hand.hip, hold.normal(&object.pose), depth) {
            return None;
        }
        self.rest = Some(first);
        self.under = Some(first);
        let status = TickStatus {
            input_clamped,
            ..TickStatus::default()
        };
        self.hold_tick(scene, entry, hand, hold, status)
    }

    /// A tick of a holding proxy (see [`super`]): while the device point stays deeper than
    /// the saturation depth behind the held plane, the proxy at `p` moves by the
    /// god-object's constraint steps toward the hold's goal (the entry plus the hand's
    /// offset across the direction it went deep, at the saturation depth), without
    /// friction; `None` (and no change) once it is back within that depth or the held
    /// object is gone.
    pub(in crate::proxy) fn hold_tick(
        &mut self,
        scene: &Scene,
        p: DVec3,
        hand: &Hand,
        mut hold: Hold,
        mut status: TickStatus,
    ) -> Option<TickOutput> {
        let hip = hand.hip;
        let object = scene.objects().get(hold.on.object)?;
        let material = object.material_on(hold.on.triangle);
        let depth = saturation_depth(object.hold_material(), self.options.max_force)?;
        if !is_deep(p, hip, hold.normal(&object.pose), Some(depth)) {
            return None;
        }
        status.in_contact = true;
        status.deep_hold = true;
        status.sticking = self.sticking;
        // Toward the point over the goal on the held plane, pulled back into the surface
        // by the saturation depth, by the god-object's constraint steps. A hand that moved
        // across by no more than a skin since the proxy last moved leaves it where it is
        // (a straight strike never moves it).
        let (slide, normal) = hold.targets(&object.pose, p, hip);
        let mut p = p;
        if slide.distance(p) > self.options.skin {
            let start = Start {
                placed: false,
                rest: self.rest,
                under: self.under,
            };
            let near = (scene, &mut self.near);
            let mut sweep = Sweep::at(p);
            constrain(
                near,
                &mut sweep,
                slide - normal * depth,
                start,
                &self.options,
                &mut status,
            );
            p = sweep.position;
            self.rest = sweep.last_hit.map(|(hit, _)| hit.surface());
            if let Some((hit, plane)) = sweep.last_hit
                && hit.object == hold.on.object
            {
                hold.on.triangle = hit.triangle;
                hold.normal_object = object.pose.vector_to_object(plane.normal);
                hold.constraints = sweep.planes.len() as u8;
            }
        }
        let normal = hold.normal(&object.pose);
        let contact = contact_at(
            scene,
            hold.on,
            p,
            hip,
            (normal, hold.constraints),
            &mut status,
        );
        // The plain spring toward the held point: no force shading, whose normal (turned
        // toward the next face near an edge) would, this deep, lead the force off the
        // line back to the point of entry.
        let (force, force_clamped) = contact_force(
            p,
            hip,
            hand.velocity,
            contact.map(|c| (c.normal, c.normal, c.constraints)),
            (material, &Relief::FLAT),
            self.options.max_force,
        );
        status.force_clamped = force_clamped;
        if let Some(c) = contact {
            self.under = Some(c.surface());
            hold.on.triangle = c.triangle;
        }
        self.hold = Some(hold);
        Some(self.output(p, force, contact, status))
    }
}
