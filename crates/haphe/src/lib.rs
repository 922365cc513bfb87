//! # haphe — haptic rendering against triangle meshes
//!
//! haphe answers, every servo tick (1 kHz and faster), where a point haptic device touches a
//! triangle mesh, where the surface contact point (proxy) is, and what force to render.
//!
//! A complete program: a 10 cm cube read from OBJ text, pressed for two seconds by a
//! simulated hand (a mass–spring–damper arm following a scripted path, pushed back by the
//! force) in the servo loop at 1 kHz, on a virtual clock:
//!
//! ```
//! use std::sync::Arc;
//!
//! use haphe::map::MapOptions;
//! use haphe::mesh::{ReadOptions, Surface, SurfaceOptions, read_mesh};
//! use haphe::scene::{Material, ObjectId, Pose, Scene, SceneObject, Shape};
//! use haphe::servo::{HandOptions, PathKind, Servo, ServoOptions, SimulatedHand, scripted_path};
//!
//! const CUBE: &str = "v 0 0 0\nv 0.1 0 0\nv 0.1 0.1 0\nv 0 0.1 0\n\
//!                     v 0 0 0.1\nv 0.1 0 0.1\nv 0.1 0.1 0.1\nv 0 0.1 0.1\n\
//!                     f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 3 4 8 7\nf 1 5 8 4\nf 2 3 7 6\n";
//!
//! fn main() -> Result<(), Box<dyn std::error::Error>> {
//!     // Stages 1 and 2: the mesh, its surface and its voxel map, built once.
//!     let mesh = read_mesh("cube.obj", CUBE.as_bytes(), &ReadOptions::default())?;
//!     let surface = Surface::new(mesh, &SurfaceOptions::default())?;
//!     let shape = Arc::new(Shape::build(surface, &MapOptions::default())?);
//!
//!     // Stage 5: a scene of one object.
//!     let mut scene = Scene::local(1);
//!     let object = SceneObject::new(ObjectId(0), shape, Pose::IDENTITY, Material::default());
//!     scene.insert(object).map_err(|(e, _)| e)?;
//!
//!     // Stage 6: the servo loop over a device, here the simulated hand pressing on the top.
//!     let path = scripted_path(PathKind::Press, &scene, 2.0, 0)?;
//!     let hand = SimulatedHand::new(path, HandOptions::default());
//!     let mut servo = Servo::new(hand, scene, ServoOptions::default())?;
//!     let (mut contact_ticks, mut strongest) = (0, 0.0f64);
//!     servo.run_simulated(2_000, |tick| {
//!         contact_ticks += usize::from(tick.in_contact());
//!         strongest = strongest.max(tick.force.length());
//!     });
//!     println!("{contact_ticks} ticks in contact; strongest force {strongest:.2} N");
//!     assert!(contact_ticks > 0 && strongest <= haphe::scene::DEFAULT_MAX_FORCE_N + 1e-9);
//!     Ok(())
//! }
//! ```
//!
//! ## Conventions (stated once, holding everywhere)
//!
//! - **Units** are SI: metres, seconds, newtons, N/m, N·s/m, radians. A file in millimetres
//!   or inches is scaled once, when it is read ([`mesh::Units`]).
//! - **Precision**: all geometry is `f64` ([`glam::DVec3`]).
//! - **Axes** are right-handed. **Winding**: triangles are counter-clockwise seen from
//!   outside, so `(b − a) × (c − a)` points out of a solid.
//! - **Frames**: *object* (the mesh as read and scaled), *world* (the scene) and *device*.
//!   Names carry their frame (`p_object`, `world_from_object`).
//!
//! ## The pipeline
//!
//! Data flows one way; each stage hands the next a validated type. The stages are numbered
//! in the order they depend on each other: a stage uses only the stages numbered before it
//! (a test, `stage_order`, reads the sources and fails on a `crate::` path that points to a
//! later stage).
//!
//! 1. [`mesh`] — read OBJ/STL/PLY/OFF bytes into a [`mesh::Mesh`], weld duplicate
//!    vertices, validate into a [`mesh::MeshReport`], and build the topology of a
//!    [`mesh::Surface`] (neighbours, vertex fans, barycentric frames, shading normals).
//!    Procedural shapes (to try haphe without a mesh file, and for tests) live in
//!    [`mesh::shapes`].
//! 2. [`map`] — the voxel map of one object: cells outside, inside or on the surface, the
//!    triangles of each surface cell, clearance for free-space early-outs.
//! 3. [`query`] — segment crossing, inside/outside, the barycentric surface walk and the
//!    geometric kernels under them.
//! 4. [`scene`] — many objects, each a shared [`scene::Shape`] at a rigid pose with a
//!    material, edited from other threads without locking the servo thread, and the first
//!    surface a move meets among them.
//! 5. [`proxy`] — the god-object proxy that never enters an object, with friction, force
//!    shading and the rendered force, ticked against a scene.
//! 6. [`servo`] — the fixed-rate loop: a [`servo::Device`] read and written every tick,
//!    simulated devices (a hand, scripted paths, replayed traces), safe start, traces and
//!    tick statistics.
//! 7. [`volume`] — grids of values (NIfTI scans, voxelised meshes) whose iso-surface is
//!    extracted in chunks into a [`scene::Shape`], and material the tool removes.
//!
//! Stages up to the proxy touch no files, threads, clocks or globals: readers take bytes,
//! so they can be fuzzed, and only the command-line tool opens paths. The servo stage owns
//! the clock and the servo thread.
//!
//! ## What a tick may do
//!
//! Everything the servo thread runs each tick (device read, scene edits, proxy, force,
//! statistics) allocates nothing, takes no lock, does no I/O and never panics; bad input
//! gives zero force and a status. Tests prove the first rule with a counting allocator.
#![cfg_attr(
    not(test),
    warn(clippy::unwrap_used, clippy::expect_used, clippy::panic)
)]
#![deny(missing_docs)]

mod array;
pub mod map;
pub mod mesh;
// "Did you mean": the front ends' (command, Python, devices) spelling suggestions.
#[doc(hidden)]
pub mod names;
mod par;
pub mod proxy;
pub mod query;
#[cfg(feature = "testing")]
pub mod rng;
#[cfg(not(feature = "testing"))]
mod rng;
pub mod scene;
pub mod servo;
#[cfg(any(test, feature = "testing"))]
pub mod verify;
pub mod volume;

#[cfg(test)]
mod stage_order;

pub use glam;
pub use glam::DVec3;

/// The README's code, compiled with the doctests (`cargo test --doc -p haphe`).
#[cfg(doctest)]
#[doc = include_str!("../../../README.md")]
pub struct ReadmeDoctests;

/// The library guide's program, compiled and run with the doctests.
#[cfg(doctest)]
#[doc = include_str!("../../../docs/library.md")]
pub struct LibraryDoctests;
