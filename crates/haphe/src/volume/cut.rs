//! Cutting: the tool removes the material it presses on. A [`Cutter`] owns the volume
//! off the servo thread: it is told where the tool pressed and how hard
//! ([`Cutter::press`], from each tick's output), lowers the values inside the tool's
//! reach, re-extracts only the chunks it changed and makes the next version of the
//! object's shape ([`Cutter::refresh`]), which the servo takes wait-free
//! ([`Edit::SetShape`](crate::scene::Edit::SetShape)).
//!
//! The rule of a press, for a tool of radius `r` centred at `c` pressing with a force of
//! at least the cut force for `dt` seconds: every material voxel within `r + 1.75` voxels
//! of `c` (the cutting ball) gains `dt · rate / voxel` of progress (its layer's rate);
//! once at 1 it is removed: its value goes below iso, to where the field of the cutting
//! ball would put it (`iso + (d − reach) · slope`, lower the deeper inside), so that the
//! cut surface follows the ball rather than the voxels' stairs. Values only go down: the
//! material after a cut lies inside the material before it (the extraction's solid is
//! where a piecewise-linear interpolation of the values is at least iso), so a tool
//! outside the old surface is outside the new one.

use std::collections::HashMap;
use std::sync::Arc;
use std::time::Instant;

use glam::{DAffine3, DVec3};

use super::Volume;
use super::extract::Chunks;
use super::layers::{Layer, Layers};
use crate::map::{MapError, MapOptions};
use crate::mesh::{Surface, SurfaceError, SurfaceOptions};
use crate::par::on_this_thread;
use crate::scene::{Param, ParamError, Shape};

/// How a [`Cutter`] cuts.
#[derive(Debug, Clone, PartialEq)]
pub struct CutOptions {
    tool_radius: f64,
    cut_force: f64,
    layers: Layers,
}

impl CutOptions {
    /// The contact force from which the tool cuts unless told otherwise, N.
    pub const DEFAULT_CUT_FORCE: f64 = 0.5;

    /// A tool of `tool_radius` metres cutting from a contact force of `cut_force` N, in
    /// one material (stiffness and friction of the object, cut at [`Layer::DEFAULT_RATE`]).
    ///
    /// # Errors
    /// [`ParamError`] naming [`Param::ToolRadius`] or [`Param::CutForce`].
    pub fn new(tool_radius: f64, cut_force: f64) -> Result<CutOptions, ParamError> {
        Ok(CutOptions {
            tool_radius: Param::ToolRadius.check(tool_radius)?,
            cut_force: Param::CutForce.check(cut_force)?,
            layers: Layers::default(),
        })
    }

    /// The same with the materials of `layers`: a value takes the layer with the highest
    /// [`Layer::from`] at most the value (the lowest layer below every `from`). Each layer
    /// is cut at its rate, and each triangle of the surface feels like its layer's
    /// material, over the object's: the layer of the highest value at the corners of the
    /// tetrahedron of the extraction it lies in (the material beside it). A hold (deep
    /// penetration, see [`Proxy`](crate::proxy::Proxy)) begins at the saturation depth
    /// of the softest layer. No layer: one material, the object's, cut at
    /// [`Layer::DEFAULT_RATE`].
    pub fn with_layers(mut self, layers: Vec<Layer>) -> CutOptions {
        self.layers = Layers::new(layers);
        self
    }

    /// The tool's radius, metres.
    pub fn tool_radius(&self) -> f64 {
        self.tool_radius
    }

    /// The force from which it cuts, N.
    pub fn cut_force(&self) -> f64 {
        self.cut_force
    }

    /// The materials, sorted by [`Layer::from`].
    pub fn layers(&self) -> &[Layer] {
        self.layers.layers()
    }
}

impl Default for CutOptions {
    /// A point tool (radius 0) cutting from [`CutOptions::DEFAULT_CUT_FORCE`], one
    /// material.
    fn default() -> CutOptions {
        CutOptions {
            tool_radius: 0.0,
            cut_force: CutOptions::DEFAULT_CUT_FORCE,
            layers: Layers::default(),
        }
    }
}

/// Why a cut volume's shape could not be made.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum CutError {
    /// The volume has no material left (or had none): no surface to render.
    #[error("{0}: no material is left")]
    Empty(String),
    /// The extracted surface was refused (not expected of a closed extraction).
    #[error("{0}: {1}")]
    Surface(String, SurfaceError),
    /// Its map could not be built.
    #[error("{0}: {1}")]
    Map(String, MapError),
}

/// How far beyond the tool's radius a cut reaches, in voxels: a surface point touching
/// the tool lies in a tetrahedron of the extraction with a material corner, no farther
/// from it than the tetrahedron's longest edge (a cube's diagonal, √3 voxels), so a
/// pressing tool always reaches material to remove and never stalls on a surface it
/// cannot cut. A little more covers the skin.
const REACH_VOXELS: f64 = 1.75;

/// An inclusive box of voxel indices.
type VoxelBox = ([i64; 3], [i64; 3]);

/// The volume of an object the tool cuts into, and the shape of its surface, owned by the
/// thread that refreshes it (never the servo's).
#[derive(Debug)]
pub struct Cutter {
    name: String,
    volume: Volume,
    chunks: Chunks,
    shape: Arc<Shape>,
    options: CutOptions,
    map_options: MapOptions,
    from_world: DAffine3,
    /// One voxel: the largest spacing of the grid, metres.
    voxel: f64,
    /// The value a removed voxel goes down to at most (below iso).
    air: f32,
    /// Value per metre of the cutting sphere's field.
    slope: f64,
    /// Progress of the voxels pressed on but not removed yet (flat index → 0..1).
    progress: HashMap<usize, f32>,
    /// The voxels changed since the last refresh.
    dirty: Option<VoxelBox>,
    removed: u64,
    /// The last refresh's two steps, seconds: the chunks extracted, the shape built.
    last_refresh: (f64, f64),
}

impl Cutter {
    /// The cutter of `volume` (named `name` in errors), its surface extracted and its
    /// shape built; it cuts as [`CutOptions::default`] says until told otherwise
    /// ([`Cutter::set_options`]).
    ///
    /// # Errors
    /// [`CutError`] when the volume has no material, or its surface cannot be mapped.
    pub fn new(name: &str, volume: Volume, map_options: MapOptions) -> Result<Cutter, CutError> {
        let chunks = Chunks::extract(&volume);
        let voxel = volume.voxel_size();
        let map_options = volume.map_options(&map_options);
        let iso = volume.iso();
        // The lowest value, if it is air; else a value as far below iso as the values go
        // above it.
        let air = match super::grid::finite_range(volume.values()) {
            Some((lowest, _)) if lowest < iso => lowest,
            Some((_, highest)) => iso - (highest - iso).abs().max(iso.abs()).max(1.0),
            None => iso - iso.abs().max(1.0),
        };
        let shape = build(name, &chunks, &map_options, &Layers::default())?;
        // Every clear zone now, so that no tick computes one.
        let shape = Arc::new(shape.with_clear_zones());
        Ok(Cutter {
            name: name.to_owned(),
            from_world: volume.to_world().inverse(),
            slope: f64::from(iso - air) / voxel,
            air,
            voxel,
            shape,
            volume,
            chunks,
            options: CutOptions::default(),
            map_options,
            progress: HashMap::new(),
            dirty: None,
            removed: 0,
            last_refresh: (0.0, 0.0),
        })
    }

    /// The latest shape made (the object's shape once the servo takes it).
    pub fn shape(&self) -> &Arc<Shape> {
        &self.shape
    }

    /// The volume as cut so far.
    pub fn volume(&self) -> &Volume {
        &self.volume
    }

    /// The volume, given back (to save it).
    pub fn into_volume(self) -> Volume {
        self.volume
    }

    /// How it cuts.
    pub fn options(&self) -> &CutOptions {
        &self.options
    }

    /// Cuts as `options` says from now on. When its layers feel otherwise than those
    /// before, the shape is made again now with their materials (a new version, see
    /// [`Cutter::shape`]): call it before handing the shape to a scene.
    ///
    /// # Errors
    /// Those of [`Cutter::new`], when the shape is made again.
    pub fn set_options(&mut self, options: CutOptions) -> Result<(), CutError> {
        let felt = |o: &CutOptions| o.layers.are_felt().then(|| o.layers.clone());
        let remake = felt(&options) != felt(&self.options);
        self.options = options;
        if remake {
            let shape = build(
                &self.name,
                &self.chunks,
                &self.map_options,
                &self.options.layers,
            )?;
            // The same triangles as the shape before: every zone kept.
            let shape = shape.with_zones_kept(&self.shape, &[], Some);
            self.shape = Arc::new(shape.replacing(&self.shape));
        }
        Ok(())
    }

    /// The last refresh's two steps, seconds: the changed chunks extracted again, then
    /// the shape of the new surface built.
    pub fn last_refresh_seconds(&self) -> (f64, f64) {
        self.last_refresh
    }

    /// How many voxels it removed.
    pub fn removed(&self) -> u64 {
        self.removed
    }

    /// One tick of the tool centred at `centre` (the volume's frame, metres) pressing
    /// with a contact force of `force` N for `dt` seconds: below the cut force nothing
    /// happens; at or above it the voxels in reach make progress and those done are
    /// removed (see the module's rule). Returns how many voxels it removed.
    pub fn press(&mut self, centre: DVec3, force: f64, dt: f64) -> usize {
        if !(force >= self.options.cut_force && dt > 0.0 && centre.is_finite()) {
            return 0;
        }
        let reach = self.options.tool_radius + REACH_VOXELS * self.voxel;
        let (lo, hi) = self.voxels_within(centre, reach);
        let mut done = Vec::new();
        for k in lo[2]..=hi[2] {
            for j in lo[1]..=hi[1] {
                for i in lo[0]..=hi[0] {
                    let d = self
                        .volume
                        .point(i as f64, j as f64, k as f64)
                        .distance(centre);
                    if d > reach || !self.volume.is_material(i, j, k) {
                        continue;
                    }
                    let at = self.flat(i, j, k);
                    let value = self.volume.values()[at];
                    let step = dt * self.options.layers.of(value).rate / self.voxel;
                    let progress = self.progress.entry(at).or_insert(0.0);
                    *progress += step as f32;
                    if *progress >= 1.0 {
                        self.progress.remove(&at);
                        done.push(at);
                    }
                }
            }
        }
        if done.is_empty() {
            return 0;
        }
        self.carve(centre, reach, &done);
        done.len()
    }

    /// Lowers the `done` voxels to the field of the cutting sphere (centre, radius
    /// `reach`): the deeper inside it, the lower.
    fn carve(&mut self, centre: DVec3, reach: f64, done: &[usize]) {
        let (iso, slope, air) = (self.volume.iso(), self.slope, self.air);
        let field = |d: f64| ((f64::from(iso) + (d - reach) * slope) as f32).max(air);
        for &at in done {
            let [i, j, k] = super::grid::index_of(self.volume.dims(), at).map(|x| x as i64);
            let d = self
                .volume
                .point(i as f64, j as f64, k as f64)
                .distance(centre);
            let v = &mut self.volume.values_mut()[at];
            *v = v.min(field(d).min(iso.next_down()));
            grow(&mut self.dirty, [i, j, k]);
            self.removed += 1;
        }
    }

    /// The chunks changed since the last call re-extracted, and the next version of the
    /// shape made ([`Shape::replacing`] the latest); `None` when nothing changed. The
    /// work runs on the calling thread alone, never on rayon's pool.
    ///
    /// # Errors
    /// [`CutError::Empty`] once no material is left; the others as [`Cutter::new`].
    pub fn refresh(&mut self) -> Result<Option<Arc<Shape>>, CutError> {
        let Some((lo, hi)) = self.dirty.take() else {
            return Ok(None);
        };
        on_this_thread(|| {
            let began = Instant::now();
            let before = self.chunks.triangle_offsets();
            let touched = self.chunks.refreshed_chunks(&self.volume, lo, hi);
            let extracted = began.elapsed().as_secs_f64();
            let layers = &self.options.layers;
            let shape = build(&self.name, &self.chunks, &self.map_options, layers)?;
            let shape = kept_zones(shape, &self.shape, (&before, &self.chunks), &touched)
                .replacing(&self.shape);
            self.last_refresh = (extracted, began.elapsed().as_secs_f64() - extracted);
            self.shape = Arc::new(shape);
            Ok(Some(Arc::clone(&self.shape)))
        })
    }

    /// The inclusive box of voxels (clamped to the grid) holding the ball of `radius`
    /// around `centre`.
    fn voxels_within(&self, centre: DVec3, radius: f64) -> VoxelBox {
        let q = self.from_world.transform_point3(centre);
        let m = self.from_world.matrix3.transpose();
        // The half-extent of the ball's image along index axis a: radius × |row a|.
        let half = DVec3::new(m.x_axis.length(), m.y_axis.length(), m.z_axis.length()) * radius;
        let dims = self.volume.dims().map(|d| d as i64 - 1);
        let lo = (q - half).ceil();
        let hi = (q + half).floor();
        let clamp =
            |x: f64, a: usize| (x.clamp(-1.0, dims[a] as f64 + 1.0) as i64).clamp(0, dims[a]);
        (
            [clamp(lo.x, 0), clamp(lo.y, 1), clamp(lo.z, 2)],
            [clamp(hi.x, 0), clamp(hi.y, 1), clamp(hi.z, 2)],
        )
    }

    fn flat(&self, i: i64, j: i64, k: i64) -> usize {
        let [nx, ny, _] = self.volume.dims();
        i as usize + nx * (j as usize + ny * k as usize)
    }
}

/// The shape of the surface of `chunks` (named `name`), each triangle feeling like its
/// layer when the layers are felt; no clear zone computed yet.
fn build(
    name: &str,
    chunks: &Chunks,
    map_options: &MapOptions,
    layers: &Layers,
) -> Result<Shape, CutError> {
    if chunks.triangle_count() == 0 {
        return Err(CutError::Empty(name.to_owned()));
    }
    let surface = Surface::new(chunks.mesh(), &SurfaceOptions::default())
        .map_err(|e| CutError::Surface(name.to_owned(), e))?;
    let shape =
        Shape::build(surface, map_options).map_err(|e| CutError::Map(name.to_owned(), e))?;
    let shape = if layers.are_felt() {
        let palette = layers.layers().iter().map(|l| l.material).collect();
        shape.with_triangle_materials(palette, &layers.indices_of(&chunks.triangle_values()))
    } else {
        shape
    };
    Ok(shape)
}

/// `shape` (the surface of `chunks`, which were `before` (their triangle offsets) when
/// `previous` was made, then `touched` re-extracted) with every clear zone computed now,
/// so that no tick computes one: those of `previous` kept for the triangles of chunks not
/// touched, where no new triangle comes within their reach.
fn kept_zones(
    shape: Shape,
    previous: &Shape,
    (before, chunks): (&[usize], &Chunks),
    touched: &[usize],
) -> Shape {
    let after = chunks.triangle_offsets();
    if before.len() != after.len() {
        return shape.with_clear_zones();
    }
    // The surface triangle of `previous` made of each triangle of its mesh.
    let mut old_of_mesh = vec![u32::MAX; before.last().copied().unwrap_or(0)];
    for (t, &m) in previous.surface().source_triangles().iter().enumerate() {
        if let Some(slot) = old_of_mesh.get_mut(m as usize) {
            *slot = t as u32;
        }
    }
    let mut changed = vec![false; after.len().saturating_sub(1)];
    for &c in touched {
        if let Some(slot) = changed.get_mut(c) {
            *slot = true;
        }
    }
    // A mesh triangle's chunk, and there the triangle it was in `previous`'s mesh.
    let same = |m: usize| -> Option<u32> {
        let c = after.partition_point(|&o| o <= m).checked_sub(1)?;
        if *changed.get(c)? {
            return None;
        }
        let old = m - after[c] + before[c];
        old_of_mesh.get(old).copied().filter(|&t| t != u32::MAX)
    };
    let sources = shape.surface().source_triangles();
    let same_of: Vec<Option<u32>> = sources.iter().map(|&m| same(m as usize)).collect();
    let fresh: Vec<u32> = (0..same_of.len() as u32)
        .filter(|&t| same_of[t as usize].is_none())
        .collect();
    shape.with_zones_kept(previous, &fresh, |t| {
        same_of.get(t as usize).copied().flatten()
    })
}

/// Grows `b` to hold voxel `v`.
fn grow(b: &mut Option<VoxelBox>, v: [i64; 3]) {
    *b = Some(match *b {
        None => (v, v),
        Some((lo, hi)) => (
            [lo[0].min(v[0]), lo[1].min(v[1]), lo[2].min(v[2])],
            [hi[0].max(v[0]), hi[1].max(v[1]), hi[2].max(v[2])],
        ),
    });
}
