//! `haphe.Scene`, `haphe.Proxy` and `haphe.Contact`: objects placed in the world, and the
//! god-object proxy ticked against them.

use haphe::DVec3;
use haphe::glam::{DMat3, DQuat};
use haphe::proxy::{self, ProxyOptions};
use haphe::scene::{self as hs, Material, ObjectId, Param, Pose, SceneObject};
use std::collections::BTreeMap;
use std::sync::{Mutex, PoisonError};

use pyo3::prelude::*;

use crate::deform;
use crate::errors::{haphe_error, param_error};
use crate::files::{Folder, read_bytes, read_options, units_warning, warn};
use crate::shape::Shape;
use crate::spec;

/// Objects the proxy touches: shapes placed in the world (metres) with a material.
///
/// ``Scene(capacity=64)`` holds up to ``capacity`` objects (storage is reserved once, as
/// for the servo thread). One proxy ticks against a scene: each ``proxy.tick`` starts the
/// scene's tick (objects moved since the previous tick push the proxy).
#[pyclass(module = "haphe")]
pub struct Scene {
    /// The scene, in a mutex only because Python objects must be shareable between
    /// threads (the library's scene is `Send`, not `Sync`); every method but `snapshot`
    /// has the scene exclusively (`&mut self`) and reaches it with `get_mut`, no lock.
    inner: Mutex<hs::Scene>,
    next_id: u32,
    /// The names of the objects that have one (from a glTF file's nodes), by id.
    names: BTreeMap<u32, String>,
    /// The specifications of the objects' textures, by id.
    textures: BTreeMap<u32, String>,
    /// The specifications of the scene's effects, in the scene's order.
    effects: Vec<String>,
}

/// A rotation from a quaternion ``(x, y, z, w)`` (the order of SciPy's ``as_quat``) or a
/// 3×3 matrix (rows); `None` is the identity.
fn rotation(r: Option<&Bound<'_, PyAny>>) -> PyResult<DQuat> {
    let Some(r) = r else {
        return Ok(DQuat::IDENTITY);
    };
    if let Ok([x, y, z, w]) = r.extract::<[f64; 4]>() {
        // Checked (finite, of non-zero length) and normalised by `Pose::new`.
        return Ok(DQuat::from_xyzw(x, y, z, w));
    }
    let rows: [[f64; 3]; 3] = r.extract().map_err(|_| {
        haphe_error(
            "rotation",
            "expected a quaternion (x, y, z, w) or a 3x3 rotation matrix",
        )
    })?;
    let m = DMat3::from_cols_array_2d(&rows).transpose();
    let orthonormal = (m.transpose() * m).abs_diff_eq(DMat3::IDENTITY, 1e-6);
    if !(m.is_finite() && orthonormal && m.determinant() > 0.0) {
        return Err(haphe_error(
            "rotation",
            format!("{rows:?} is not a rotation matrix (orthonormal, determinant 1)"),
        ));
    }
    Ok(DQuat::from_mat3(&m))
}

/// A pose from a position and an optional rotation, checked by the library.
fn pose(position: [f64; 3], rotation: Option<&Bound<'_, PyAny>>) -> PyResult<Pose> {
    Pose::new(self::rotation(rotation)?, DVec3::from_array(position)).map_err(param_error)
}

/// A material from the keyword arguments, checked by the library (`dynamic_friction`
/// defaults to `friction`).
fn material(
    stiffness: f64,
    damping: f64,
    friction: f64,
    dynamic_friction: Option<f64>,
) -> PyResult<Material> {
    Material::builder()
        .stiffness(stiffness)
        .damping(damping)
        .friction(friction, dynamic_friction.unwrap_or(friction))
        .build()
        .map_err(param_error)
}

#[pymethods]
impl Scene {
    #[new]
    #[pyo3(signature = (capacity = 64))]
    fn new(capacity: usize) -> Scene {
        Scene {
            inner: Mutex::new(hs::Scene::local(capacity)),
            next_id: 0,
            names: BTreeMap::new(),
            textures: BTreeMap::new(),
            effects: Vec::new(),
        }
    }

    /// Scene.from_gltf(path, units="m", weld_tolerance=None, capacity=None, stiffness=500.0, damping=0.0, friction=0.0, dynamic_friction=None)
    /// --
    ///
    /// A scene from a glTF 2.0 file (``.glb``, or ``.gltf`` with its ``.bin`` files beside
    /// it): one object per node of the default scene that holds a mesh, at the node's world
    /// pose (a non-uniform scale is baked into the object's shape), named after the node
    /// (``names``), ids from 0 in the scene's order. Nodes that use one mesh the same way
    /// share one shape. The material is the node's ``extras`` (``stiffness``, ``damping``,
    /// ``friction``, ``static_friction``, ``dynamic_friction``) where they give one, else
    /// the arguments. ``capacity`` defaults to the number of objects (at least 64).
    ///
    /// Warns (``UserWarning``) when the scene spans more than 2 m or less than 5 mm, naming
    /// the ``units`` to give.
    ///
    /// Raises ``HapheError`` naming the file and the place (node, mesh, primitive,
    /// accessor, buffer) for bad content or a bad argument, ``OSError`` when the file
    /// cannot be read.
    #[staticmethod]
    #[pyo3(signature = (path, units = "m", weld_tolerance = None, capacity = None, stiffness = 500.0, damping = 0.0, friction = 0.0, dynamic_friction = None))]
    #[allow(clippy::too_many_arguments)]
    fn from_gltf(
        py: Python<'_>,
        path: std::path::PathBuf,
        units: &str,
        weld_tolerance: Option<f64>,
        capacity: Option<usize>,
        stiffness: f64,
        damping: f64,
        friction: f64,
        dynamic_friction: Option<f64>,
    ) -> PyResult<Scene> {
        let options = read_options(units, weld_tolerance)?;
        let material = material(stiffness, damping, friction, dynamic_friction)?;
        let bytes = read_bytes(&path)?;
        let name = path.display().to_string();
        let (objects, warning) = py
            .detach(|| {
                let read =
                    haphe::mesh::read_gltf(&name, &bytes, options.units, &mut Folder::of(&path))
                        .map_err(|e| e.to_string())?;
                let warning = units_warning(&name, read.flatten().bounds(), options.units);
                let objects = hs::gltf_objects(&read).map_err(|e| format!("{name}: {e}"))?;
                objects
                    .build(
                        options.weld,
                        &haphe::map::MapOptions::default(),
                        material,
                        0,
                    )
                    .map(|built| (built, warning))
                    .map_err(|e| format!("{name}: {e}"))
            })
            .map_err(|e| haphe_error("", e))?;
        warn(py, warning)?;
        let mut scene = Scene::new(capacity.unwrap_or(objects.len().max(64)));
        for (object_name, object) in objects {
            let id = object.id.0;
            scene
                .scene()
                .insert(object)
                .map_err(|(e, _)| haphe_error("scene", e))?;
            scene.names.insert(id, object_name);
            scene.next_id = id + 1;
        }
        Ok(scene)
    }

    /// The names of the objects read from a glTF file, by id (``{id: name}``).
    #[getter]
    fn names(&self) -> BTreeMap<u32, String> {
        self.names.clone()
    }

    /// add(shape, position=(0, 0, 0), rotation=None, stiffness=500.0, damping=0.0, friction=0.0, dynamic_friction=None, two_sided=None, texture=None)
    /// --
    ///
    /// Places ``shape`` at ``position`` (metres) turned by ``rotation`` (a quaternion
    /// ``(x, y, z, w)`` or a 3×3 matrix; object to world) with a material: ``stiffness``
    /// N/m, ``damping`` N·s/m, static ``friction`` coefficient and ``dynamic_friction``
    /// (default: equal to ``friction``). A closed solid is touched from outside only, an
    /// open surface from both sides, unless ``two_sided`` says otherwise. ``texture`` is
    /// felt on the surface: ``"sine:A:L"`` (a solid sine of amplitude ``A`` and wavelength
    /// ``L`` metres in the object's frame) or ``"noise:A:L"`` (band-limited noise);
    /// ``None`` (or ``""``) for none. Returns the object's id.
    ///
    /// Raises ``HapheError`` naming the keyword: for a texture, ``texture`` and the
    /// specification (an unknown kind, a value not a number, non-finite or outside its
    /// domain, bumps steeper than a slope of 1).
    #[pyo3(signature = (shape, position = [0.0; 3], rotation = None, stiffness = Material::DEFAULT.stiffness(), damping = Material::DEFAULT.damping(), friction = Material::DEFAULT.static_friction(), dynamic_friction = None, two_sided = None, texture = None))]
    #[allow(clippy::too_many_arguments)]
    fn add(
        &mut self,
        shape: &Shape,
        position: [f64; 3],
        rotation: Option<&Bound<'_, PyAny>>,
        stiffness: f64,
        damping: f64,
        friction: f64,
        dynamic_friction: Option<f64>,
        two_sided: Option<bool>,
        texture: Option<&str>,
    ) -> PyResult<u32> {
        let pose = pose(position, rotation)?;
        let material = material(stiffness, damping, friction, dynamic_friction)?;
        let felt = spec::texture(texture)?;
        let id = ObjectId(self.next_id);
        let mut object = SceneObject::new(id, shape.inner.clone(), pose, material);
        let textured = felt.is_some();
        object.texture = felt;
        if let Some(two) = two_sided {
            object = object.with_sides(if two {
                hs::Sides::Both
            } else {
                hs::Sides::Front
            });
        }
        self.scene()
            .insert(object)
            .map_err(|(e, _)| haphe_error("scene", e))?;
        if let (true, Some(t)) = (textured, texture) {
            self.textures.insert(id.0, t.to_owned());
        }
        self.next_id += 1;
        Ok(id.0)
    }

    /// add_volume(volume, position=(0, 0, 0), rotation=None, stiffness=500.0, damping=0.0, friction=0.0, dynamic_friction=None, texture=None)
    /// --
    ///
    /// Adds the surface of a volume as an object: a ``Cutter``'s latest shape (its
    /// triangles feel like its layers, if it has any) or a ``Volume``'s iso-surface,
    /// placed with the centre of its grid at ``position`` (as the command line places a
    /// volume at the origin), turned by ``rotation`` about that centre. The rest as
    /// ``add``. Returns the object's id; give it the cutter's new shapes with
    /// ``replace``. Raises ``TypeError`` for anything but a ``Cutter`` or a ``Volume``.
    #[pyo3(signature = (volume, position = [0.0; 3], rotation = None, stiffness = Material::DEFAULT.stiffness(), damping = Material::DEFAULT.damping(), friction = Material::DEFAULT.static_friction(), dynamic_friction = None, texture = None))]
    #[allow(clippy::too_many_arguments)]
    fn add_volume(
        &mut self,
        py: Python<'_>,
        volume: &Bound<'_, PyAny>,
        position: [f64; 3],
        rotation: Option<&Bound<'_, PyAny>>,
        stiffness: f64,
        damping: f64,
        friction: f64,
        dynamic_friction: Option<f64>,
        texture: Option<&str>,
    ) -> PyResult<u32> {
        let (inner, centre) = crate::volume::surface_of(py, volume)?;
        let turn = self::rotation(rotation)?;
        let at = DVec3::from_array(position) - turn * centre;
        let shape = Shape {
            inner,
            name: "volume".to_owned(),
        };
        self.add(
            &shape,
            at.to_array(),
            rotation,
            stiffness,
            damping,
            friction,
            dynamic_friction,
            None,
            texture,
        )
    }

    /// move(id, position, rotation=None)
    /// --
    ///
    /// Moves object ``id`` to a new pose; the motion is rendered at the next tick (a moving
    /// object pushes the proxy). Raises ``KeyError`` for an unknown id.
    #[pyo3(name = "move", signature = (id, position, rotation = None))]
    fn move_to(
        &mut self,
        id: u32,
        position: [f64; 3],
        rotation: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<()> {
        let pose = pose(position, rotation)?;
        if self.scene().set_pose(ObjectId(id), pose) {
            Ok(())
        } else {
            Err(pyo3::exceptions::PyKeyError::new_err(id))
        }
    }

    /// remove(id)
    /// --
    ///
    /// Removes object ``id``. Raises ``KeyError`` for an unknown id.
    fn remove(&mut self, id: u32) -> PyResult<()> {
        self.names.remove(&id);
        self.textures.remove(&id);
        self.scene()
            .remove(ObjectId(id))
            .map(|_| ())
            .ok_or_else(|| pyo3::exceptions::PyKeyError::new_err(id))
    }

    /// deform(id, vertices, indices=None)
    /// --
    ///
    /// Deforms object ``id``: its vertices move, its triangles stay. ``vertices`` is a
    /// ``(V, 3)`` array of new positions (metres, object frame), one per vertex in the
    /// order of ``shape.arrays()`` (the surface's order, which may differ from the
    /// file's); with ``indices`` (a 1-D integer array-like), vertex ``indices[k]`` moves to
    /// ``vertices[k]`` and the others stay. Both are read as the batch queries read their
    /// arrays (lists, float32, any strides). Other objects sharing the shape keep it as it
    /// was (``scene.shape(id)`` is the object's shape now).
    ///
    /// Only what the moved triangles touch is recomputed, here, without the GIL; the
    /// deformation is in force from the next tick: a proxy resting on the surface rides
    /// it, and a surface that moved over the proxy pushes it out.
    ///
    /// Raises ``KeyError`` for an unknown id, ``HapheError`` naming the argument and the
    /// first bad row for a coordinate that is NaN, infinite or beyond the largest a mesh
    /// may have, an index out of range, a wrong number of positions or of indices, or an
    /// array of the wrong shape. A refused deformation leaves the scene unchanged.
    #[pyo3(signature = (id, vertices, indices = None))]
    fn deform(
        &mut self,
        py: Python<'_>,
        id: u32,
        vertices: &Bound<'_, PyAny>,
        indices: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<()> {
        let scene = self.scene();
        let count = deform::vertex_count(scene, id)?;
        let positions = deform::points("vertices", vertices)?;
        let indices = indices.map(|i| deform::indices(i, count)).transpose()?;
        py.detach(|| match &indices {
            None => scene.deform(ObjectId(id), &positions),
            Some(indices) => scene.deform_at(ObjectId(id), indices, &positions),
        })
        .map_err(deform::deform_error)
    }

    /// shape(id)
    /// --
    ///
    /// The shape of object ``id`` as it is now (deformed, if it was): a ``Shape`` sharing
    /// it, whose ``version`` counts the deformations. Raises ``KeyError`` for an unknown id.
    fn shape(&mut self, id: u32) -> PyResult<Shape> {
        let scene = self.scene();
        let i = scene
            .index_of(ObjectId(id))
            .ok_or_else(|| pyo3::exceptions::PyKeyError::new_err(id))?;
        Ok(Shape {
            inner: scene.objects()[i].shape.clone(),
            name: format!("object {id}"),
        })
    }

    /// replace(id, shape)
    /// --
    ///
    /// Gives object ``id`` a new version of its shape (``Cutter.refresh``'s, or the same
    /// counts of vertices and triangles), in force from the next tick. Raises ``KeyError``
    /// for an unknown id, ``HapheError`` when ``shape`` is not a version of the object's.
    fn replace(&mut self, id: u32, shape: &Shape) -> PyResult<()> {
        match self.scene().replace(ObjectId(id), shape.inner.clone()) {
            Err(hs::EditError::UnknownObject) => Err(pyo3::exceptions::PyKeyError::new_err(id)),
            r => r.map(|_| ()).map_err(|e| haphe_error("shape", e)),
        }
    }

    /// check_tool_radius(tool_radius)
    /// --
    ///
    /// ``tool_radius`` (metres) when a tool of that radius fits this scene: from 0 to
    /// 0.5 m, and at most the diagonal of the box bounding the objects as placed now (a
    /// larger tool holds the whole scene). Raises ``HapheError`` naming ``tool_radius``
    /// otherwise.
    fn check_tool_radius(&mut self, tool_radius: f64) -> PyResult<f64> {
        self.scene()
            .check_tool_radius(tool_radius)
            .map_err(param_error)
    }

    /// set_texture(id, texture)
    /// --
    ///
    /// Changes the texture of object ``id``: a specification as ``add`` takes (``"sine:A:L"``,
    /// ``"noise:A:L"``), or ``None`` (or ``""``) for none. Raises ``HapheError`` naming
    /// ``texture`` and the specification when it is refused (the object keeps its
    /// texture), ``KeyError`` for an unknown id.
    #[pyo3(signature = (id, texture))]
    fn set_texture(&mut self, id: u32, texture: Option<&str>) -> PyResult<()> {
        let felt = spec::texture(texture)?;
        let set = felt.is_some();
        if !self.scene().set_texture(ObjectId(id), felt) {
            return Err(pyo3::exceptions::PyKeyError::new_err(id));
        }
        match texture {
            Some(t) if set => self.textures.insert(id, t.to_owned()),
            _ => self.textures.remove(&id),
        };
        Ok(())
    }

    /// The specifications of the objects' textures, by id (``{id: "sine:0.0002:0.002"}``;
    /// objects without one are not listed).
    #[getter]
    fn textures(&self) -> BTreeMap<u32, String> {
        self.textures.clone()
    }

    /// add_effect(effect)
    /// --
    ///
    /// Adds a force effect to the scene, from its specification:
    ///
    /// - ``"vibration:FREQ:AMPLITUDE"``: in contact, ``AMPLITUDE · sin(2π FREQ t)`` newtons
    ///   along the contact normal (FREQ in Hz, at most half the servo's rate);
    /// - ``"viscosity:B"``: a drag ``−B v`` (N·s/m) everywhere; ``"viscosity:B:inside:ID"``
    ///   where the device point is inside object ``ID``; ``"viscosity:B:box:X0:Y0:Z0:X1:Y1:Z1"``
    ///   inside that box (world, metres);
    /// - ``"spring:K:X:Y:Z"``: ``K (anchor − p)`` toward the point (N/m, metres);
    /// - ``"magnet:DISTANCE:FORCE"``: ``FORCE`` newtons toward the nearest surface within
    ///   ``DISTANCE`` metres of the device point;
    /// - ``"constant:FX:FY:FZ"``: that force, newtons;
    /// - ``"stick-slip"`` or ``"stick-slip:K:FORCE"``: in contact, a spring of ``K`` N/m across
    ///   the surface to an anchor that slips when it pulls harder than ``FORCE`` newtons
    ///   (1000 N/m and 0.5 N by default).
    ///
    /// Each effect is bounded by the device's maximum force, added to the surface's force
    /// and the sum clamped to that maximum. The servo loop (``haphe.run``) renders them; a
    /// bare ``Proxy.tick`` renders the surfaces and their textures only. At most 16 per
    /// scene.
    ///
    /// Raises ``HapheError`` naming ``effect`` and the specification: an unknown kind, a
    /// value not a number, non-finite or outside its domain, or a full scene. ``haphe.run``
    /// refuses a vibration above half its ``rate_hz`` the same way.
    fn add_effect(&mut self, effect: &str) -> PyResult<()> {
        spec::add_effect(self.scene(), effect)?;
        self.effects.push(effect.to_owned());
        Ok(())
    }

    /// The specifications of the scene's effects, in the order added.
    #[getter]
    fn effects(&self) -> Vec<String> {
        self.effects.clone()
    }

    /// clear_effects()
    /// --
    ///
    /// Removes every force effect.
    fn clear_effects(&mut self) {
        self.scene().clear_effects();
        self.effects.clear();
    }

    fn __len__(&mut self) -> usize {
        self.scene().objects().len()
    }
}

impl Scene {
    /// A copy of the objects (shapes shared) and the effects in a new scene, for a servo
    /// run.
    pub fn snapshot(&self) -> hs::Scene {
        let scene = self.inner.lock().unwrap_or_else(PoisonError::into_inner);
        let objects = scene.objects();
        let mut copy = hs::Scene::local(objects.len());
        for o in objects {
            // Cannot fail: the copy has room for every object and the ids are unique.
            let _ = copy.insert(o.clone());
        }
        for e in scene.effects() {
            // Cannot fail: the copy has room for as many effects as the scene.
            let _ = copy.add_effect(*e);
        }
        copy
    }

    /// The specifications of the effects, in the scene's order.
    pub fn effect_specs(&self) -> &[String] {
        &self.effects
    }

    /// The scene, reached without a lock through the exclusive borrow.
    pub fn scene(&mut self) -> &mut hs::Scene {
        self.inner.get_mut().unwrap_or_else(PoisonError::into_inner)
    }
}

/// Where the proxy touches an object (world frame, metres).
#[pyclass(module = "haphe", frozen, get_all)]
pub struct Contact {
    /// The id of the object touched (as returned by ``scene.add``).
    pub object: u32,
    /// The triangle under the proxy: the face index of the object's mesh as given.
    pub triangle: u32,
    /// The surface point nearest to the proxy.
    pub point: (f64, f64, f64),
    /// Unit normal of the last constraint plane, toward the proxy's side.
    pub normal: (f64, f64, f64),
    /// Unit shading normal at ``point``: the direction of the rendered normal force.
    pub shading_normal: (f64, f64, f64),
    /// How far the device point is behind the proxy along ``normal``, metres.
    pub penetration: f64,
    /// Active constraint planes: 1 on a face, 2 in a concave edge, 3 in a corner.
    pub constraints: u8,
    /// The version of the object's shape the tick touched (``Shape.version``: how many
    /// deformations made it).
    pub version: u64,
}

#[pymethods]
impl Contact {
    fn __repr__(&self) -> String {
        format!(
            "Contact(object={}, triangle={}, point={:?}, penetration={:e})",
            self.object, self.triangle, self.point, self.penetration
        )
    }
}

/// A proxy position, checked by the library's table of domains.
fn position_of(position: [f64; 3]) -> PyResult<DVec3> {
    Param::Position
        .check_vector(position)
        .map(DVec3::from_array)
        .map_err(param_error)
}

/// A point or vector as Python sees it.
type Vec3 = (f64, f64, f64);

/// Three numbers as a tuple.
fn tuple(v: DVec3) -> (f64, f64, f64) {
    (v.x, v.y, v.z)
}

/// The god-object proxy of a device: the centre of the tool (a point, or a sphere of
/// ``tool_radius``), which never comes closer to an object than that radius, moved each
/// tick toward the device point (HIP) and stopped and slid by the surfaces it meets; the
/// force pulls the device toward it.
///
/// ``Proxy(position=(0, 0, 0), max_force=DEFAULT_MAX_FORCE, skin=1e-6,
/// workspace_radius=1000.0, tool_radius=0.0)``:
/// the start position (metres, normally the device point at start-up), the largest force
/// rendered (N; ``haphe.DEFAULT_MAX_FORCE``, that of a common desktop device, by default),
/// the distance kept from a touched surface (m), the radius beyond which device points
/// are pulled back (m), and the radius of the tool (m; 0, a point, by default; the proxy
/// keeps the tool's centre that far from every triangle). A value outside its domain
/// (the library's table: a force above 0 and at most 100 N, a skin above 0 and at most
/// 1 mm, a workspace radius above 0, a tool radius from 0 to 0.5 m) raises ``HapheError``
/// naming it. A proxy is not bound to one scene: ``Scene.check_tool_radius`` also refuses
/// a tool larger than a given scene.
#[pyclass(module = "haphe")]
pub struct Proxy {
    inner: proxy::Proxy,
}

#[pymethods]
impl Proxy {
    #[new]
    #[pyo3(signature = (position = [0.0; 3], max_force = haphe::scene::DEFAULT_MAX_FORCE_N, skin = proxy::DEFAULT_SKIN, workspace_radius = 1e3, tool_radius = 0.0))]
    fn new(
        position: [f64; 3],
        max_force: f64,
        skin: f64,
        workspace_radius: f64,
        tool_radius: f64,
    ) -> PyResult<Proxy> {
        let options = ProxyOptions::default()
            .with_max_force(max_force)
            .and_then(|o| o.with_skin(skin))
            .and_then(|o| o.with_workspace_radius(workspace_radius))
            .and_then(|o| o.with_tool_radius(tool_radius))
            .map_err(param_error)?;
        Ok(Proxy {
            inner: proxy::Proxy::new(position_of(position)?, options),
        })
    }

    /// tick(scene, hip, velocity=(0, 0, 0))
    /// --
    ///
    /// One servo tick: starts the scene's tick, moves the proxy toward the device point
    /// ``hip`` (metres, world frame; ``velocity`` in m/s, for damping) and returns
    /// ``(force, position, contact)``: the force to render (N, world frame, finite and
    /// within ``max_force``), the proxy position (m) and a ``Contact`` or ``None``. The
    /// objects' textures are felt; the scene's effects are not (``haphe.run`` renders
    /// them, with the time and each device's state they need).
    ///
    /// Allocates nothing on the Rust side; a non-finite input gives zero force and leaves
    /// the proxy where it was.
    #[pyo3(signature = (scene, hip, velocity = [0.0; 3]))]
    fn tick(
        &mut self,
        mut scene: PyRefMut<'_, Scene>,
        hip: [f64; 3],
        velocity: [f64; 3],
    ) -> (Vec3, Vec3, Option<Contact>) {
        let scene = scene.scene();
        scene.begin_tick();
        let out = self
            .inner
            .tick(scene, DVec3::from_array(hip), DVec3::from_array(velocity));
        let contact = out.contact.and_then(|c| {
            let object = scene.objects().get(c.object)?;
            Some(Contact {
                object: c.id.0,
                triangle: object.shape.surface().source_triangle(c.triangle),
                point: tuple(c.point),
                normal: tuple(c.normal),
                shading_normal: tuple(c.shading_normal),
                penetration: c.penetration,
                constraints: c.constraints,
                version: c.version,
            })
        });
        (tuple(out.force), tuple(out.proxy), contact)
    }

    /// reset(position)
    /// --
    ///
    /// Puts the proxy at ``position`` (metres) with no contact.
    fn reset(&mut self, position: [f64; 3]) -> PyResult<()> {
        self.inner.reset(position_of(position)?);
        Ok(())
    }

    /// The proxy position, metres, world frame.
    #[getter]
    fn position(&self) -> (f64, f64, f64) {
        tuple(self.inner.position())
    }

    /// The radius of the tool, metres (0: a point).
    #[getter]
    fn tool_radius(&self) -> f64 {
        self.inner.options().tool_radius()
    }
}
