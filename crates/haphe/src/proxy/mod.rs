//! Stage 5 — the haptic proxy: the god-object of Zilles & Salisbury, moved each tick
//! toward the device point and held outside every object of a [`Scene`](crate::scene::Scene),
//! with the force that pulls the device toward it.
//!
//! # Semantics
//!
//! The proxy is a point that never crosses a triangle. Each tick:
//!
//! 1. **Carry.** Each object that moved since the previous tick tests the proxy's motion
//!    relative to it (in its frame, between its previous and current pose); if that
//!    motion meets its surface, the proxy is stopped a skin's width in front of it — the
//!    object pushes the proxy.
//! 2. **Constrain.** The proxy aims at the point closest to the device point (HIP) on the
//!    free side of the active constraint planes (none at first) and moves toward it in a
//!    straight line. If the line meets a triangle (the first crossing over every object,
//!    lowest object index on ties), the proxy stops where the line meets that triangle's
//!    plane moved out by the skin, the plane becomes a constraint, and it aims again. At
//!    most three planes (a face, a concave edge, a concave corner) and
//!    [`MAX_PROXY_STEPS`] legs. A leg that meets nothing but ends within a probe's reach
//!    of a surface ([`ProxyOptions::probe_reach`]; the nearest triangle, lowest object
//!    index first) *touches* it: the leg stands, and that triangle's plane moved out by
//!    the skin becomes a constraint too. So the proxy never rests on a surface, where the
//!    next leg, running along the surface's plane, could slip through its edge unseen
//!    (the watertight test decides crossings exactly only for end points off the
//!    surface). A proxy placed ([`Proxy::new`], [`Proxy::reset`]) within a probe's reach
//!    of a surface touches it on its first tick when the device point lies behind that
//!    surface's constraint plane.
//!
//!    A proxy *resting* on a surface keeps it (the god-object's constraint kept from one
//!    tick to the next): when the last constraint of the previous tick was triangle `T`,
//!    the proxy lies on the free side of `T`'s plane no farther than its constraint plane
//!    (or a thousandth of the skin beyond it, the rounding of the projection that put it
//!    there), the device point lies behind `T`'s plane and the line toward it meets that
//!    plane inside `T`, the first leg takes `T`'s constraint plane without a crossing
//!    search (the proxy does not move along that leg, except onto the plane from that
//!    hair in front of it; every later leg is tested as above).
//!
//!    A leg that stays in the *clear zone* of the triangle last met or rested on
//!    (`Scene::clear_move`) is known to meet nothing
//!    and to end farther than a probe's reach from every surface, so its searches are
//!    skipped; the result is the one they would give.
//! 3. **Friction.** In contact, with friction, the proxy stays where it rested while the
//!    tangential force is inside the static friction cone, and otherwise slips to the
//!    edge of the dynamic cone; that last move is tested for
//!    crossings too.
//! 4. **Contact and force.** The surface point under the proxy is found by walking from
//!    the last triangle touched; the force is the spring–damper toward the proxy with
//!    force shading, clamped.
//! 5. **Deep penetration.** When the tick ends with the device point deeper than the
//!    *saturation depth* `max_force / stiffness` behind the contact plane (where the spring
//!    alone reaches the device's maximum force; [`saturation_depth`]), the proxy *holds*
//!    from the next tick on: while the device point stays deeper than that behind the held
//!    plane, steps 2 and 3 are skipped — the proxy stays where it is (moving objects still
//!    carry it), on the same contact, and the force is the plain spring–damper from the
//!    hand back to where it went deep, without force shading ([`TickStatus::deep_hold`]). On the first tick the device point
//!    is back within the saturation depth of that plane, the proxy lets go and the
//!    god-object resumes from where it held.
//!
//! Below the saturation depth (the physical range) the proxy is exactly the god-object of
//! Zilles & Salisbury. Beyond it the god-object's rule — get as close to the device point
//! as the surface allows — is wrong for a thick part: the closest surface point of a
//! point deep inside a convex body lies toward its far side, the god-object crawls around
//! the body after it (about a quarter of the way round a sphere in a 35° strike at
//! 1.5 m/s) and the force then pulls the hand on through the object. A proxy that holds
//! keeps the side of entry at any depth: a straight strike, however deep, and on out of
//! the far side, feels a force back toward the entry point only, as a thin wall does. The
//! price: pushed past the device's maximum force, the surface holds the hand's contact
//! point (as a very sticky surface would) until the hand eases back within the saturation
//! depth; with no stiffness or no maximum force there is no saturation and no hold.
//!
//! # A tool with a size
//!
//! With [`ProxyOptions::tool_radius`] `r > 0` the proxy is the centre of a sphere of
//! radius `r`, and the rules above apply to the offset of every triangle by `r` (the
//! face moved out both ways, a cylinder round each edge, a sphere round each vertex)
//! instead of the triangles: a leg stops a skin's width before the first place the sphere
//! swept along it touches a triangle (`Scene::first_tool_hit`; a sphere within a probe's
//! reach of a triangle's offset at the start of a leg touches it when it moves closer),
//! and the constraint plane is the offset's tangent plane there, facing the centre, moved
//! out by the skin; a free leg that ends within the radius and a probe's reach of a
//! triangle touches the nearest. So the centre never comes closer than `r` less the skin to
//! any triangle, a gap narrower than `2r` is never entered, convex edges and corners are
//! round to slide over (the tangent plane turns with the contact) and concave ones hold up
//! to three planes. The resting rule, the clear zones and the convex shortcut of step 2
//! are the point's and are not used; the hold, friction and force are the same, measured
//! from the centre (so the saturation depth is measured from the tool's surface). The
//! contact's point is the surface point nearest to the centre. `r = 0` runs the point's
//! code, unchanged.
//!
//! Inside a solid means a winding number other than 0 (the non-zero rule, as in
//! [`classify_point`](crate::query::classify_point)): where closed parts of one mesh
//! overlap, the union is solid. The proxy, which never crosses a triangle, stops on the
//! first surface it meets from outside and so never reaches the faces of one part that lie
//! inside another; the servo loop's safe start and the checks of
//! `verify::check_proxy` (feature `testing`) ask `classify_point`.
//!
//! # Real-time
//!
//! A tick allocates nothing, takes no lock and never panics, whatever the input (a
//! non-finite device point gives zero force and [`TickStatus::input_rejected`]; a point
//! beyond [`ProxyOptions::workspace_radius`] is pulled back to it). Every loop has a named
//! cap: the objects of the scene (its fixed capacity), [`MAX_PROXY_STEPS`] constraint legs
//! of at most [`MAX_CONSTRAINTS`] planes, the cells of a segment walk (the grid's
//! `dims[0] + dims[1] + dims[2]`), the cells around a point in a touching search
//! (`MAX_NEAR_CELLS_PER_AXIS` per axis), and the
//! surface walk's `MAX_WALK_STEPS` and
//! `MAX_FAN_SCAN`. Reaching a cap returns a valid proxy
//! (outside every object) and says so in the status. The force is finite and never above
//! [`ProxyOptions::max_force`].
//!
//! The constraint steps and the friction rule are plain crate-private functions
//! (`constraints.rs`, `force.rs`) so that the brute-force proxy of `verify` (feature
//! `testing`), which tests every triangle of every object, runs the same semantics as the
//! fast one.

mod constrain;
mod constraints;
mod deform;
mod force;
mod godobject;
mod hold;
mod meet;
mod near;
mod options;
mod output;
mod rest;

#[doc(hidden)]
pub use constrain::MAX_PROXY_STEPS;
#[doc(hidden)]
pub use constraints::MAX_CONSTRAINTS;
#[doc(hidden)]
pub use force::MIN_MAX_FORCE;
#[doc(hidden)]
pub use godobject::MAX_WORKSPACE_RADIUS;
pub use godobject::Proxy;
#[doc(hidden)]
pub use hold::saturation_depth;
// The skin's default, which the Python binding names in its signature (`ProxyOptions::default`
// states it: a micrometre).
#[doc(hidden)]
pub use options::DEFAULT_SKIN;
pub use options::ProxyOptions;
pub use output::{Contact, TickOutput, TickStatus};
// The clamp of the servo's sum of the proxy's force and the effects.
#[cfg(any(test, feature = "testing"))]
pub(crate) use deform::{Ride, pushed_from, ride_on};
pub(crate) use force::clamp_force;
// The god-object's geometric steps, which the brute-force proxy of `verify` runs too.
#[cfg(any(test, feature = "testing"))]
pub(crate) use {
    constraints::{Constraints, Plane, advance_to_plane},
    godobject::clamp_to_radius,
    rest::rests_on,
};
