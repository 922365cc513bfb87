//! The query streams: what the device point does, generated once per mesh with fixed seeds
//! and given unchanged to every method.
//!
//! - **near**: coherent trajectories near and in contact with the surface
//!   ([`haphe::verify::trajectory`]): a hand moving at 0.05–0.5 m/s sampled at 1 kHz,
//!   that is steps of 0.05–0.5 mm on an object 0.2 m across, scaled with the object's
//!   size, starting within 1 % of the object's size of a random surface point and
//!   wandering around it. Each trajectory is one chunk of [`STEPS`] positions.
//! - **free**: the same kind of trajectories moved away from the surface along the start
//!   triangle's normal by 1–5 % of the object's size, keeping only the positions where
//!   the map lists no triangle — a cell without triangles, or beyond the grid, which
//!   extends one cell past the bounding box: a device point moving in free space near the
//!   object. (Around a thin plate the grid is a few cells thick, so most of its free space
//!   lies beyond it; keeping only cells inside the grid would keep only the one layer of
//!   padding cells right beside the plate.)
//! - **random points** and **random segments**: uniform in the bounding box grown by a
//!   fifth on every side ([`haphe::verify::points`], [`haphe::verify::segments`]).

use haphe::DVec3;
use haphe::map::{CellState, VoxelMap};
use haphe::mesh::{Surface, TriId};
use haphe::query::walk_to_nearest;
use haphe::rng::SplitMix64;
use haphe::scene::Scene;
use haphe::verify::{
    SegmentKind, bounds, haptic_path_in_contact, lifted_for_tool, points, segments, trajectory,
};

/// Positions per trajectory (a quarter of a second at 1 kHz), and items per chunk of the
/// random streams: the unit of interleaving.
pub const STEPS: usize = 250;

/// Step lengths of a hand at 0.05–0.5 m/s sampled at 1 kHz, metres, for an object whose
/// bounding box diagonal is that of a 0.2 m cube.
const STEP_RANGE_M: (f64, f64) = (0.05e-3, 0.5e-3);

/// How far the free-space trajectories are moved off the surface, as fractions of the
/// bounding box diagonal.
const FREE_OFFSET: (f64, f64) = (0.01, 0.05);

/// Free-space trajectories tried per chunk wanted, at most, before settling for fewer
/// free positions (a mesh whose cells are large compared with the object leaves little
/// free space near it).
const FREE_ATTEMPTS_PER_CHUNK: usize = 4;

/// One coherent trajectory near the surface.
pub struct Trajectory {
    /// The surface triangle it starts on.
    pub start: TriId,
    /// The device positions, metres, object frame.
    pub positions: Vec<DVec3>,
    /// For each position, the triangle the surface walk stands on before walking to it
    /// (the start, then the previous answer): where the floor query and the walk begin.
    pub current: Vec<TriId>,
}

/// Every stream for one mesh, in chunks.
pub struct Streams {
    /// Coherent trajectories near the surface.
    pub near: Vec<Trajectory>,
    /// The segments between consecutive positions of each near trajectory.
    pub near_segments: Vec<Vec<(DVec3, DVec3)>>,
    /// Coherent positions in cells without triangles.
    pub free: Vec<Vec<DVec3>>,
    /// Random points in the grown bounding box.
    pub random_points: Vec<Vec<DVec3>>,
    /// Random segments in the grown bounding box.
    pub random_segments: Vec<Vec<(DVec3, DVec3)>>,
    /// One device path in steady contact, in chunks (filled by [`Streams::add_contact`]).
    pub contact: Vec<Vec<DVec3>>,
    /// The contact path for a tool of each radius (1 mm, scaled, and 2 % of the object's
    /// size), moved out by the radius: the radius and the chunks.
    pub tool: [(f64, Vec<Vec<DVec3>>); 2],
}

impl Streams {
    /// About `samples` queries per stream (whole chunks), deterministic for a `seed`.
    pub fn new(surface: &Surface, map: &VoxelMap, samples: usize, seed: u64) -> Streams {
        let chunks = samples.div_ceil(STEPS).max(1);
        let (_, _, size) = bounds(surface);
        let scale = size / (0.2 * 3f64.sqrt());
        let step_range = (STEP_RANGE_M.0 * scale, STEP_RANGE_M.1 * scale);
        // Distinct seeds per stream, so that no two streams share their random numbers.
        let mut seeds = SplitMix64::new(seed);
        let [
            near_seed,
            free_seed,
            offset_seed,
            points_seed,
            segments_seed,
        ] = std::array::from_fn(|_| seeds.next_u64());

        let near: Vec<Trajectory> = (0..chunks)
            .map(|k| {
                let (start, positions) =
                    trajectory(surface, STEPS, step_range, near_seed.wrapping_add(k as u64));
                let mut t = start;
                let current = positions
                    .iter()
                    .map(|&p| {
                        let before = t;
                        t = walk_to_nearest(surface, t, p).0.triangle;
                        before
                    })
                    .collect();
                Trajectory {
                    start,
                    positions,
                    current,
                }
            })
            .collect();

        let mut offsets = SplitMix64::new(offset_seed);
        let free = (0..chunks * FREE_ATTEMPTS_PER_CHUNK)
            .map(|k| {
                let (start, positions) =
                    trajectory(surface, STEPS, step_range, free_seed.wrapping_add(k as u64));
                let away = surface.frame(start).normal
                    * offsets.range(FREE_OFFSET.0, FREE_OFFSET.1)
                    * size;
                positions
                    .into_iter()
                    .map(|p| p + away)
                    .filter(|&p| is_free(map, p))
                    .collect::<Vec<_>>()
            })
            .filter(|chunk| !chunk.is_empty())
            .take(chunks)
            .collect();

        let near_segments = near
            .iter()
            .map(|t| t.positions.windows(2).map(|w| (w[0], w[1])).collect())
            .collect();
        Streams {
            near,
            near_segments,
            free,
            random_points: chunked(points(surface, chunks * STEPS, points_seed)),
            random_segments: chunked(segments(
                surface,
                SegmentKind::Random,
                chunks * STEPS,
                segments_seed,
            )),
            contact: Vec::new(),
            tool: [(0.0, Vec::new()), (0.0, Vec::new())],
        }
    }

    /// Adds the contact path over the one object of `scene`, cut into as many chunks of
    /// [`STEPS`] ticks as the other streams have: one path at 1 kHz that starts just
    /// outside and then slides 0.5–3 mm deep at 0.05–0.5 m/s (both scaled to the object's
    /// size, as a 0.2 m object), so that the proxy touches once and then stays in steady
    /// contact from chunk to chunk.
    pub fn add_contact(&mut self, scene: &Scene, seed: u64) {
        let Some(object) = scene.objects().first() else {
            return;
        };
        let (_, _, size) = bounds(object.shape.surface());
        let scale = size / (0.2 * 3f64.sqrt());
        let seed = SplitMix64::new(seed ^ 0xC0_47AC7).next_u64();
        self.contact = chunked(haptic_path_in_contact(
            scene,
            self.near.len() * STEPS,
            (0.05 * scale, 0.5 * scale),
            (0.5e-3 * scale, 3e-3 * scale),
            TICK_RATE_HZ,
            seed,
        ));
        self.tool = [1e-3 * scale, 0.02 * size].map(|radius| {
            let lifted = self
                .contact
                .iter()
                .map(|chunk| lifted_for_tool(scene, chunk, radius, 4e-3 * scale))
                .collect();
            (radius, lifted)
        });
    }
}

/// The device rate the contact paths are sampled at, Hz.
pub const TICK_RATE_HZ: f64 = 1e3;

/// `all` cut into chunks of [`STEPS`].
fn chunked<T: Clone>(all: Vec<T>) -> Vec<Vec<T>> {
    all.chunks(STEPS).map(<[T]>::to_vec).collect()
}

/// Whether the map lists no triangle at `p`: its cell has none, or it lies beyond the grid.
fn is_free(map: &VoxelMap, p: DVec3) -> bool {
    map.grid()
        .cell_of(p)
        .is_none_or(|c| map.state(c) != CellState::Surface)
}
