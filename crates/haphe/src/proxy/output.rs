//! What a proxy tick returns: the proxy, the force, the contact and a small status.

use glam::DVec3;

use crate::mesh::TriId;
use crate::scene::{ObjectId, SurfaceRef};

/// Where and how the proxy touches an object, world frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Contact {
    /// Index of the object in [`Scene::objects`](crate::scene::Scene::objects).
    pub object: usize,
    /// The object's name.
    pub id: ObjectId,
    /// The triangle under the proxy (found by walking from the last one touched), in the
    /// object's surface ([`Surface::source_triangle`](crate::mesh::Surface::source_triangle)
    /// gives its index in the mesh as loaded).
    pub triangle: TriId,
    /// Barycentric weights of `point` in that triangle.
    pub weights: [f64; 3],
    /// The surface point nearest to the proxy, metres, world frame.
    pub point: DVec3,
    /// Unit normal of the last constraint plane touched, pointing to the proxy's side,
    /// world frame.
    pub normal: DVec3,
    /// Unit shading normal at `point` (interpolated corner normals, on the same side as
    /// `normal`), world frame: the direction of the rendered normal force.
    pub shading_normal: DVec3,
    /// How far the device point is behind the proxy along `normal`, metres (≥ 0).
    pub penetration: f64,
    /// Number of active constraint planes: 1 on a face, 2 in a concave edge, 3 in a
    /// concave corner.
    pub constraints: u8,
    /// The version of the object's shape the tick touched ([`Shape::version`]: how many
    /// deformations made it), so that a deformation sent from another thread can be
    /// matched with the first tick that felt it.
    ///
    /// [`Shape::version`]: crate::scene::Shape::version
    pub version: u64,
}

impl Contact {
    /// The object and triangle touched.
    #[inline]
    pub(crate) fn surface(&self) -> SurfaceRef {
        SurfaceRef {
            object: self.object,
            triangle: self.triangle,
        }
    }
}

/// How a tick went: flags a servo loop can count and log off the servo thread.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct TickStatus {
    /// The proxy touches an object.
    pub in_contact: bool,
    /// Static friction holds the proxy where it was.
    pub sticking: bool,
    /// The device position or velocity was not finite: the proxy did not move and the
    /// force is zero.
    pub input_rejected: bool,
    /// The device position was beyond [`ProxyOptions::workspace_radius`](super::ProxyOptions::workspace_radius)
    /// and was pulled back to it.
    pub input_clamped: bool,
    /// The force was larger than the maximum and was scaled down to it.
    pub force_clamped: bool,
    /// A cap on the constraint steps (`MAX_PROXY_STEPS`, or a
    /// fourth plane) stopped the proxy early; it is valid but may not be the closest point.
    pub step_cap_hit: bool,
    /// The active planes left no point to move to (a very narrow wedge): the proxy stayed.
    pub wedged: bool,
    /// The contact walk reached its cap; the contact point is the best found.
    pub walk_cap_hit: bool,
    /// A move of the proxy was shown clear by the clear zone of the triangle it slides on
    /// (see [`crate::proxy`], "Constrain"), so its crossing and touching searches were
    /// skipped (the result is the same).
    pub cleared: bool,
    /// The device point is deeper than the saturation depth (`max_force / stiffness`)
    /// behind the contact plane: the proxy holds where it was, on the same contact (see
    /// [`crate::proxy`], "Deep penetration").
    pub deep_hold: bool,
}

/// The result of one proxy tick.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TickOutput {
    /// The proxy (god-object) position, metres, world frame.
    pub proxy: DVec3,
    /// The force to render on the device, newtons, world frame (finite, within the
    /// maximum).
    pub force: DVec3,
    /// The contact, when the proxy touches an object.
    pub contact: Option<Contact>,
    /// What happened.
    pub status: TickStatus,
}
