//! The default workspace mapping of a real device, shared by every front end (`haphe run`,
//! `haphe view`, Python's `haphe.run`): the device's workspace centred on the scene and
//! scaled to cover its bounds.

use glam::DVec3;
use haphe::scene::{ParamError, Scene};
use haphe::servo::{DeviceMapping, DeviceSpec, scene_bounds};

/// The mapping of a device of `spec` onto `scene`: `scale` world metres per device metre
/// (default: the workspace covers the scene's bounds, [`DeviceMapping::fit`]) and the
/// centre of the workspace at the world point `centre` (default: the centre of the
/// scene's bounds). An empty scene counts as a 10 cm cube at the origin.
///
/// # Errors
/// [`ParamError`] naming `scale` or `centre` outside its domain (the library's table of
/// domains, [`haphe::scene::Param`]).
pub fn workspace_mapping(
    spec: &DeviceSpec,
    scene: &Scene,
    scale: Option<f64>,
    centre: Option<DVec3>,
) -> Result<DeviceMapping, ParamError> {
    let (lo, hi) = scene_bounds(scene).unwrap_or((DVec3::splat(-0.05), DVec3::splat(0.05)));
    let fit = DeviceMapping::fit(spec, lo, hi);
    let scale = scale.unwrap_or(fit.scale());
    let centre = centre.unwrap_or(0.5 * (lo + hi));
    DeviceMapping::centred(spec, scale, centre)
}
