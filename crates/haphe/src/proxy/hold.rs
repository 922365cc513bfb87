//! The ticks of a proxy that holds beyond the saturation depth (see [`super::deep`]).

use glam::DVec3;

use super::deep::{Hold, is_deep, saturation_depth};
use super::force::contact_force;
use super::godobject::{LastContact, Proxy, Sweep, constrain, contact_at};
use super::output::{TickOutput, TickStatus};
use super::rest::Rest;
use crate::scene::Scene;

impl Proxy {
    /// The hold of a tick whose god-object steps ended with the device point `hip` beyond
    /// the saturation depth: it begins where the proxy first met a surface this tick (the
    /// `sweep`'s touch-down, on the first plane met), with the hand where it was at the
    /// start of the tick (`previous_hip`) and the direction it went deep in this tick's
    /// motion, and this tick is its first. So the tick that goes deep never slides the
    /// proxy on toward the point closest to the hand (over a crest, for a grazing strike
    /// into a convex part). `None`, and nothing changed, where the device point is not
    /// deeper than the saturation depth behind that first plane.
    pub(super) fn hold_from_touch_down(
        &mut self,
        scene: &Scene,
        sweep: &Sweep,
        (hip, velocity): (DVec3, DVec3),
        previous_hip: Option<DVec3>,
        input_clamped: bool,
    ) -> Option<TickOutput> {
        let (index, triangle) = sweep.first_hit?;
        let plane = sweep.planes.planes().first()?;
        let object = scene.objects().get(index)?;
        let entry = sweep.touch_down;
        let hold = Hold::begin(
            &object.pose,
            (index, triangle, 1),
            (entry, plane.normal),
            previous_hip.unwrap_or(hip),
            (previous_hip, hip),
        );
        // The same test as the hold's own, so that it goes ahead once begun.
        let depth = saturation_depth(&object.material, self.options.max_force);
        if !is_deep(entry, hip, hold.normal(&object.pose), depth) {
            return None;
        }
        self.rest = Some(Rest {
            object: index,
            triangle,
        });
        self.last = Some(LastContact {
            object: index,
            triangle,
        });
        let status = TickStatus {
            input_clamped,
            ..TickStatus::default()
        };
        self.hold_tick(scene, entry, hip, velocity, hold, status)
    }

    /// A tick of a holding proxy (see [`super::deep`]): while the device point `hip` stays
    /// deeper than the saturation depth behind the held plane, the proxy at `p` moves by
    /// the god-object's constraint steps toward the hold's goal (the entry plus the hand's
    /// offset across the direction it went deep, at the saturation depth), without
    /// friction; `None` (and no change) once it is back within that depth or the held
    /// object is gone.
    pub(super) fn hold_tick(
        &mut self,
        scene: &Scene,
        p: DVec3,
        hip: DVec3,
        velocity: DVec3,
        hold: Hold,
        mut status: TickStatus,
    ) -> Option<TickOutput> {
        let object = scene.objects().get(hold.object)?;
        let normal = hold.normal(&object.pose);
        let material = object.material;
        let depth = saturation_depth(&material, self.options.max_force)?;
        if !is_deep(p, hip, normal, Some(depth)) {
            return None;
        }
        status.in_contact = true;
        status.deep_hold = true;
        status.sticking = self.sticking;
        // Toward the point over the goal on the held plane, pulled back into the surface
        // by the saturation depth, by the god-object's constraint steps.
        let (slide, normal) = hold.targets(&object.pose, p, hip);
        let under = self.last.map(|l| (l.object, l.triangle));
        // A hand that moved across by no more than a skin since the proxy last moved
        // leaves it where it is (a straight strike never moves it).
        let sweep = (slide.distance(p) > self.options.skin).then(|| {
            constrain(
                (scene, &mut self.near),
                p,
                slide - normal * depth,
                false,
                (self.rest, under),
                &self.options,
                &mut status,
            )
        });
        let p = sweep.as_ref().map_or(p, |s| s.position);
        if let Some(sweep) = &sweep {
            self.rest = sweep.last_hit.map(|(hit, _)| Rest {
                object: hit.object,
                triangle: hit.triangle,
            });
        }
        let mut hold = hold;
        if let Some(sweep) = &sweep
            && let Some((hit, plane)) = sweep.last_hit
            && hit.object == hold.object
        {
            hold.triangle = hit.triangle;
            hold.normal_object = object.pose.vector_to_object(plane.normal);
            hold.constraints = sweep.planes.len() as u8;
        }
        let normal = hold.normal(&object.pose);
        let contact = contact_at(
            scene,
            (hold.object, hold.triangle),
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
            velocity,
            contact.map(|c| (c.normal, c.normal, c.constraints)),
            &material,
            self.options.max_force,
        );
        status.force_clamped = force_clamped;
        self.position = p;
        if let Some(c) = contact {
            self.last = Some(LastContact {
                object: c.object,
                triangle: c.triangle,
            });
        }
        self.hold = Some(Hold {
            triangle: contact.map_or(hold.triangle, |c| c.triangle),
            ..hold
        });
        Some(TickOutput {
            proxy: p,
            force,
            contact,
            status,
        })
    }
}
