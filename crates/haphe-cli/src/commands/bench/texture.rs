//! The textured contact tick: haphe's proxy along the contact path over the object with a
//! sine texture, beside the plain contact tick.

use haphe::DVec3;
use haphe::proxy::ProxyOptions;
use haphe::scene::{Scene, Texture};

use super::timing::Run;

/// haphe's proxy along the chunks of `path` over the objects of `scene` given the texture
/// `sine:A:L` with `A` a tenth and `L` twice `unit` (the scaled millimetre of the paths);
/// `None` when such a texture or scene cannot be made.
pub fn run<'a>(scene: &Scene, unit: f64, path: &'a [Vec<DVec3>]) -> Option<Run<'a>> {
    let texture = Texture::sine(0.1 * unit, 2.0 * unit).ok()?;
    let mut textured = Scene::local(scene.objects().len());
    for o in scene.objects() {
        textured
            .insert(o.clone().with_texture(texture.clone()))
            .ok()?;
    }
    Some(super::tool::haphe_run(
        ProxyOptions::default(),
        path,
        textured,
    ))
}
