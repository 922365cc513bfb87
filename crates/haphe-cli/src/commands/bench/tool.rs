//! The tool tick's methods: haphe's sphere proxy, and parry's nearest-point ball proxy.

use std::borrow::Borrow;

use haphe::DVec3;
use haphe::proxy::{Proxy, ProxyOptions};
use haphe::scene::{Material, Scene};
use parry3d_f64::query::PointQuery;
use parry3d_f64::shape::TriMesh;

use super::streams::TICK_RATE_HZ;
use super::timing::{Run, time_each};

/// The runs of a tool of `radius` metres along `path` (chunks of one path, in order):
/// haphe's proxy carried from chunk to chunk (none for a radius out of its domain), and
/// parry's ball where parry took the mesh.
pub fn runs<'a>(
    radius: f64,
    path: &'a [Vec<DVec3>],
    scene: &'a Scene,
    parry: Option<&'a TriMesh>,
) -> (Option<Run<'a>>, Option<Run<'a>>) {
    let haphe = ProxyOptions::default()
        .with_tool_radius(radius)
        .ok()
        .map(|options| haphe_run(options, path, scene));
    let parry = parry.map(|mesh| parry_run(mesh, radius, path));
    (haphe, parry)
}

/// haphe's proxy (a tool when `options` say so) along the chunks of `path` over `scene`
/// (borrowed or owned), carried from chunk to chunk.
pub fn haphe_run<'a>(
    options: ProxyOptions,
    path: &'a [Vec<DVec3>],
    scene: impl Borrow<Scene> + 'a,
) -> Run<'a> {
    let mut state: Option<(Proxy, DVec3)> = None;
    Box::new(move |c, out| {
        let chunk = &path[c];
        let (proxy, previous) =
            state.get_or_insert_with(|| (Proxy::new(chunk[0], options), chunk[0]));
        time_each(
            chunk.iter().copied(),
            |hip| {
                let velocity = (hip - *previous) * TICK_RATE_HZ;
                *previous = hip;
                proxy.tick(scene.borrow(), hip, velocity)
            },
            out,
        )
    })
}

/// parry's ball proxy along the chunks of `path`, with the spring force.
fn parry_run<'a>(mesh: &'a TriMesh, radius: f64, path: &'a [Vec<DVec3>]) -> Run<'a> {
    let stiffness = Material::default().stiffness();
    Box::new(move |c, out| {
        time_each(
            path[c].iter().copied(),
            |hip| {
                let proxy = ball_proxy(mesh, hip, radius);
                (proxy, stiffness * (proxy - hip))
            },
            out,
        )
    })
}

/// parry's ball proxy: the centre pushed out along the line to its nearest surface point
/// to `radius` from it (through the surface when the centre is inside), or left where it
/// is when the ball touches nothing.
fn ball_proxy(mesh: &TriMesh, hip: DVec3, radius: f64) -> DVec3 {
    let projection = mesh.project_local_point(hip, true);
    let gap = hip - projection.point;
    let distance = gap.length();
    if projection.is_inside {
        projection.point - gap * (radius / distance.max(f64::MIN_POSITIVE))
    } else if distance < radius {
        projection.point + gap * (radius / distance.max(f64::MIN_POSITIVE))
    } else {
        hip
    }
}
