//! Scenes and the proxy tick.

use std::sync::Arc;

use haphe_lib::DVec3;
use haphe_lib::glam::DQuat;
use haphe_lib::proxy::{Proxy, ProxyOptions};
use haphe_lib::scene::{Material, ObjectId, Param, Pose, Scene, SceneObject, Shape};

use crate::error::{Failure, HapheStatus, guard};
use crate::shape::{HapheShape, shape};

/// A scene: shapes placed in the world with materials. Opaque; made by `haphe_scene_new`,
/// freed by `haphe_scene_free`.
pub struct HapheScene {
    pub(crate) inner: Scene,
    next_id: u32,
    /// The specifications of the scene's effects, in the scene's order.
    pub(crate) effects: Vec<String>,
}

/// The god-object proxy of one device, the centre of its tool. Opaque; made by `haphe_proxy_new`, freed by
/// `haphe_proxy_free`.
pub struct HapheProxy {
    inner: Proxy,
}

/// How a surface feels.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct HapheMaterial {
    /// Spring constant between proxy and device, N/m (500 is safe on common devices).
    pub stiffness: f64,
    /// Damping along the contact normal, N·s/m.
    pub damping: f64,
    /// Static friction coefficient (≥ 0).
    pub static_friction: f64,
    /// Dynamic friction coefficient (0 ≤ dynamic ≤ static).
    pub dynamic_friction: f64,
}

/// What one proxy tick gives.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct HapheTick {
    /// The force to render, newtons, world frame (finite, within the proxy's maximum).
    pub force: [f64; 3],
    /// The proxy position, metres, world frame.
    pub proxy: [f64; 3],
    /// 1 when the proxy touches an object (the fields below are then set, else zero).
    pub in_contact: u8,
    /// The id of the object touched (from `haphe_scene_add`).
    pub object: u32,
    /// The triangle under the proxy, as the face index of that object's mesh as given.
    pub triangle: u32,
    /// The surface point nearest to the proxy, metres, world frame.
    pub point: [f64; 3],
    /// Unit shading normal at that point (the direction of the normal force), world frame.
    pub normal: [f64; 3],
    /// How far the device point is behind the proxy along the contact normal, metres.
    pub penetration: f64,
}

/// The scene behind a handle.
pub(crate) fn scene_mut<'a>(s: *mut HapheScene) -> Result<&'a mut HapheScene, Failure> {
    // SAFETY: a non-null handle comes from this library, is not freed yet and is not used
    // by another thread during the call (documented).
    unsafe { s.as_mut() }.ok_or_else(|| Failure::argument("scene is null"))
}

/// Three doubles at `p`; `default` when `p` is null.
fn vec3(p: *const f64, default: DVec3) -> DVec3 {
    if p.is_null() {
        return default;
    }
    // SAFETY: a non-null `p` points to 3 readable doubles (documented).
    DVec3::from_array(unsafe { *p.cast::<[f64; 3]>() })
}

/// A pose from a position (3 doubles, null: the origin) and a quaternion `x, y, z, w`
/// (null: the identity), checked by the library's table of domains.
pub(crate) fn pose(position: *const f64, rotation: *const f64) -> Result<Pose, Failure> {
    let rotation = if rotation.is_null() {
        DQuat::IDENTITY
    } else {
        // SAFETY: a non-null `rotation` points to 4 readable doubles (documented).
        DQuat::from_array(unsafe { *rotation.cast::<[f64; 4]>() })
    };
    Ok(Pose::new(rotation, vec3(position, DVec3::ZERO))?)
}

/// Writes a new handle to `out`.
fn give<T>(what: &str, out: *mut *mut T, value: T) -> Result<(), Failure> {
    if out.is_null() {
        return Err(Failure::argument(format!("{what} out is null")));
    }
    // SAFETY: `out` is non-null and points to writable storage for a pointer (documented).
    unsafe { *out = Box::into_raw(Box::new(value)) };
    Ok(())
}

/// Frees a handle made by `give` (null is ignored).
fn free<T>(p: *mut T) {
    let _ = guard(|| {
        if !p.is_null() {
            // SAFETY: a non-null handle was made by `Box::into_raw` here and is freed once
            // (documented).
            drop(unsafe { Box::from_raw(p) });
        }
        Ok(())
    });
}

/// A new empty scene with room for `capacity` objects (storage reserved once). On success
/// `*out` is owned by the caller: free it with `haphe_scene_free`.
#[unsafe(no_mangle)]
pub extern "C" fn haphe_scene_new(capacity: usize, out: *mut *mut HapheScene) -> HapheStatus {
    guard(|| {
        give(
            "scene",
            out,
            HapheScene {
                inner: Scene::local(capacity),
                next_id: 0,
                effects: Vec::new(),
            },
        )
    })
}

/// Frees a scene (null is ignored). The shapes it holds are released.
#[unsafe(no_mangle)]
pub extern "C" fn haphe_scene_free(scene: *mut HapheScene) {
    free(scene);
}

/// Places `shape` in the scene at `position` (3 doubles, metres; null: the origin),
/// turned by the quaternion `rotation` (x, y, z, w, object to world; null: none), with
/// `material` (null: 500 N/m, no damping, no friction). The scene keeps its own reference
/// to the shape (the caller may free its handle). `*id` (may be null) receives the
/// object's id. Errors: `HAPHE_STATUS_FULL` at capacity, `HAPHE_STATUS_INVALID_ARGUMENT`
/// (`haphe_last_error()` names the parameter outside its domain in the library's table:
/// a stiffness above 0 and at most 1e6 N/m, damping 0 to 1000 N·s/m, friction 0 to 10
/// with the dynamic at most the static, a position at most 1e9 m from the origin, a
/// quaternion of non-zero length).
#[unsafe(no_mangle)]
pub extern "C" fn haphe_scene_add(
    scene: *mut HapheScene,
    shape: *const HapheShape,
    position: *const f64,
    rotation: *const f64,
    material: *const HapheMaterial,
    id: *mut u32,
) -> HapheStatus {
    guard(|| {
        let sc = scene_mut(scene)?;
        let sh = self::shape(shape)?;
        let pose = pose(position, rotation)?;
        insert(sc, sh.inner.clone(), pose, material, id)
    })
}

/// Inserts `shape` at `pose` with `material` (null: the default) into `sc`, its id
/// written to `id` (may be null): what `haphe_scene_add` does once the pose is made.
pub(crate) fn insert(
    sc: &mut HapheScene,
    shape: Arc<Shape>,
    pose: Pose,
    material: *const HapheMaterial,
    id: *mut u32,
) -> Result<(), Failure> {
    // SAFETY: a non-null `material` points to a readable HapheMaterial (documented).
    let material = match unsafe { material.as_ref() } {
        None => Material::default(),
        Some(m) => Material::builder()
            .stiffness(m.stiffness)
            .damping(m.damping)
            .friction(m.static_friction, m.dynamic_friction)
            .build()?,
    };
    let object_id = ObjectId(sc.next_id);
    sc.inner
        .insert(SceneObject::new(object_id, shape, pose, material))
        .map_err(|(e, _)| Failure(HapheStatus::Full, e.to_string()))?;
    sc.next_id += 1;
    if !id.is_null() {
        // SAFETY: a non-null `id` points to a writable u32 (documented).
        unsafe { *id = object_id.0 };
    }
    Ok(())
}

/// Checks that a tool of radius `tool_radius` metres fits `scene` as placed now: from 0 to
/// 0.5 m and at most the diagonal of the box bounding its objects (a larger tool holds the
/// whole scene). A proxy is not bound to one scene, so `haphe_proxy_new` checks the domain
/// only; call this with the scene it will touch. Errors: `HAPHE_STATUS_INVALID_ARGUMENT`,
/// `haphe_last_error()` naming `tool_radius`.
#[unsafe(no_mangle)]
pub extern "C" fn haphe_scene_check_tool_radius(
    scene: *mut HapheScene,
    tool_radius: f64,
) -> HapheStatus {
    guard(|| {
        let sc = scene_mut(scene)?;
        sc.inner.check_tool_radius(tool_radius)?;
        Ok(())
    })
}

/// Moves object `id` to `position` (metres) turned by `rotation` (x, y, z, w; null: none);
/// the motion is rendered at the next tick. Allocates nothing. Errors:
/// `HAPHE_STATUS_INVALID_ARGUMENT` for an unknown id or a position or rotation outside its
/// domain (named by `haphe_last_error()`).
#[unsafe(no_mangle)]
pub extern "C" fn haphe_scene_set_pose(
    scene: *mut HapheScene,
    id: u32,
    position: *const f64,
    rotation: *const f64,
) -> HapheStatus {
    guard(|| {
        let sc = scene_mut(scene)?;
        let pose = pose(position, rotation)?;
        if sc.inner.set_pose(ObjectId(id), pose) {
            Ok(())
        } else {
            Err(Failure::argument(format!("no object {id} in the scene")))
        }
    })
}

/// The largest force a device renders unless told otherwise, newtons: the library's
/// default, that of a common desktop device. Pass it as `haphe_proxy_new`'s `max_force`
/// when the device's own maximum is not known.
#[unsafe(no_mangle)]
pub extern "C" fn haphe_default_max_force() -> f64 {
    haphe_lib::scene::DEFAULT_MAX_FORCE_N
}

/// A new proxy at `position` (3 doubles, metres; null: the origin), rendering at most
/// `max_force` newtons (`haphe_default_max_force()` unless the device says otherwise),
/// for a tool of radius `tool_radius` metres: the proxy is the centre of a sphere of that
/// radius and keeps it that far from every triangle (0: a point). On success `*out` is
/// owned by the caller: free it with `haphe_proxy_free`. Errors:
/// `HAPHE_STATUS_INVALID_ARGUMENT`, `haphe_last_error()` naming `max_force` (above 0, at
/// most 100 N), `tool_radius` (0 to 0.5 m) or `position`.
#[unsafe(no_mangle)]
pub extern "C" fn haphe_proxy_new(
    position: *const f64,
    max_force: f64,
    tool_radius: f64,
    out: *mut *mut HapheProxy,
) -> HapheStatus {
    guard(|| {
        let options = ProxyOptions::default()
            .with_max_force(max_force)?
            .with_tool_radius(tool_radius)?;
        let p = DVec3::from_array(
            Param::Position.check_vector(vec3(position, DVec3::ZERO).to_array())?,
        );
        give(
            "proxy",
            out,
            HapheProxy {
                inner: Proxy::new(p, options),
            },
        )
    })
}

/// Frees a proxy (null is ignored).
#[unsafe(no_mangle)]
pub extern "C" fn haphe_proxy_free(proxy: *mut HapheProxy) {
    free(proxy);
}

/// One servo tick: starts the scene's tick (objects moved since the last one push the
/// proxy), moves the proxy toward the device point `hip` (3 doubles, metres, world frame;
/// `velocity` 3 doubles m/s or null) and writes the force, proxy and contact to `*out`.
///
/// The objects' textures are felt; the scene's effects are not (`haphe_run` renders them,
/// with the time and the device's state they need).
///
/// Real-time: allocates nothing, takes no lock, never panics; a non-finite input gives
/// zero force and leaves the proxy where it was. One proxy per scene.
#[unsafe(no_mangle)]
pub extern "C" fn haphe_proxy_tick(
    proxy: *mut HapheProxy,
    scene: *mut HapheScene,
    hip: *const f64,
    velocity: *const f64,
    out: *mut HapheTick,
) -> HapheStatus {
    guard(|| {
        // SAFETY: a non-null handle comes from this library and is not freed or shared
        // during the call (documented).
        let px = unsafe { proxy.as_mut() }.ok_or_else(|| Failure::argument("proxy is null"))?;
        let sc = scene_mut(scene)?;
        if hip.is_null() || out.is_null() {
            return Err(Failure::argument("hip or out is null"));
        }
        // SAFETY: `hip` and a non-null `velocity` point to 3 readable doubles (documented);
        // non-finite values are handled by the proxy (zero force).
        let h = DVec3::from_array(unsafe { *hip.cast::<[f64; 3]>() });
        let v = if velocity.is_null() {
            DVec3::ZERO
        } else {
            // SAFETY: as above.
            DVec3::from_array(unsafe { *velocity.cast::<[f64; 3]>() })
        };
        sc.inner.begin_tick();
        let t = px.inner.tick(&sc.inner, h, v);
        let mut tick = HapheTick {
            force: t.force.to_array(),
            proxy: t.proxy.to_array(),
            in_contact: 0,
            object: 0,
            triangle: 0,
            point: [0.0; 3],
            normal: [0.0; 3],
            penetration: 0.0,
        };
        if let Some(c) = t.contact
            && let Some(o) = sc.inner.objects().get(c.object)
        {
            tick.in_contact = 1;
            tick.object = c.id.0;
            tick.triangle = o.shape.surface().source_triangle(c.triangle);
            tick.point = c.point.to_array();
            tick.normal = c.shading_normal.to_array();
            tick.penetration = c.penetration;
        }
        // SAFETY: `out` is non-null and points to a writable HapheTick (documented).
        unsafe { *out = tick };
        Ok(())
    })
}
