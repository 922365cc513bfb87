//! The query kinds, the methods that answer them, and the interleaved rounds that time
//! them.
//!
//! Every timed query kind runs on one stream ([`super::streams`]) cut into chunks. Round
//! `c` runs chunk `c` with every method in turn — the order rotating from round to
//! round — together with an empty query that measures the clock ([`time_empty`]). A slow
//! spell of the machine (another process, a busy core) thus falls on every method alike,
//! and each method meets the caches as the previous one left them, as a servo tick
//! meets them after the rest of an application has run. Methods that keep state from one
//! query to the next keep it within a chunk where a chunk is one trajectory (the surface
//! walk), and across chunks where the stream is one path cut into chunks (the proxy in
//! contact).
//!
//! Brute force runs only on small meshes, and on every `k`-th chunk so that its
//! samples still spread over the whole run.

use haphe::map::VoxelMap;
use haphe::mesh::Surface;
use haphe::proxy::{Proxy, ProxyOptions};
use haphe::query::{
    classify_point, closest_point_triangle, first_crossing, first_crossing_brute_force,
    nearest_point_brute_force, walk_to_nearest,
};
use haphe::scene::{Material, Scene};
use haphe::verify::WindingOracle;
use parry3d_f64::query::{PointQuery, Ray, RayCast};
use parry3d_f64::shape::TriMesh;
use serde::Serialize;

use super::alloc;
use super::streams::{Streams, TICK_RATE_HZ};
use super::structures::BuildCost;
use super::timing::{Overhead, Run, Summary, time_each, time_empty};

/// A kind of query, timed per query, or a whole operation (build, decode).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Query {
    /// Inside/outside of a point moving coherently near the object where the map lists no
    /// triangle: the free-space tick.
    FreeSpace,
    /// First crossing of the segment between consecutive positions of a near trajectory.
    Segment,
    /// First crossing of a random segment across the bounding box.
    SegmentRandom,
    /// Inside/outside of the positions of a near trajectory.
    Inside,
    /// Inside/outside of random points in the bounding box.
    InsideRandom,
    /// Nearest surface point of the positions of a near trajectory, walking on from the
    /// previous answer.
    Walk,
    /// One closest point on the triangle the walk stands on: the least a query can cost.
    Floor,
    /// A proxy tick along a path in steady contact: the whole haptic tick.
    Contact,
    /// The same with a tool of radius 1 mm (scaled as the paths are): the sphere proxy.
    Tool,
    /// The same with a tool of radius 2 % of the object's size.
    ToolWide,
    /// The contact tick with a sine texture on the object (amplitude 0.1 mm, wavelength
    /// 2 mm, scaled as the paths are).
    Textured,
    /// Building the structures from the welded mesh.
    Build,
    /// Loading a saved surface and map (checks included).
    Decode,
    /// Computing every triangle's clear zone (before the contact ticks are timed).
    Zones,
}

impl Query {
    /// Every kind, in the order of the report.
    pub const ALL: [Query; 14] = [
        Query::FreeSpace,
        Query::Segment,
        Query::SegmentRandom,
        Query::Inside,
        Query::InsideRandom,
        Query::Walk,
        Query::Floor,
        Query::Contact,
        Query::Tool,
        Query::ToolWide,
        Query::Textured,
        Query::Build,
        Query::Decode,
        Query::Zones,
    ];

    /// The kinds timed one query at a time.
    pub const TIMED: [Query; 11] = [
        Query::FreeSpace,
        Query::Segment,
        Query::SegmentRandom,
        Query::Inside,
        Query::InsideRandom,
        Query::Walk,
        Query::Floor,
        Query::Contact,
        Query::Tool,
        Query::ToolWide,
        Query::Textured,
    ];

    /// The name in tables, JSON records and plot file names.
    pub fn name(self) -> &'static str {
        match self {
            Query::FreeSpace => "free_space",
            Query::Segment => "segment",
            Query::SegmentRandom => "segment_random",
            Query::Inside => "inside",
            Query::InsideRandom => "inside_random",
            Query::Walk => "walk",
            Query::Floor => "floor",
            Query::Contact => "contact",
            Query::Tool => "tool",
            Query::ToolWide => "tool_wide",
            Query::Textured => "textured",
            Query::Build => "build",
            Query::Decode => "decode",
            Query::Zones => "zones",
        }
    }

    /// What is measured, and by which call of each method.
    pub fn description(self) -> &'static str {
        match self {
            Query::FreeSpace => {
                "free-space tick: inside/outside of a point moving near the object where the \
                 map lists no triangle, in a cell without triangles or beyond the grid (haphe \
                 `classify_point`, the cell-state path; parry \
                 `contains_local_point`; brute force: winding number by counting crossings \
                 with every triangle)"
            }
            Query::Segment => {
                "segment crossing between consecutive positions of a trajectory near the \
                 surface (haphe `first_crossing`; parry `cast_local_ray` up to the segment's \
                 end; brute force: every triangle)"
            }
            Query::SegmentRandom => {
                "segment crossing on random segments across the bounding box (same calls)"
            }
            Query::Inside => {
                "inside/outside of the positions of a trajectory near the surface (haphe \
                 `classify_point`; parry `contains_local_point`; brute force: winding number)"
            }
            Query::InsideRandom => {
                "inside/outside of random points in the bounding box (same calls)"
            }
            Query::Walk => {
                "nearest surface point along a trajectory near the surface (haphe \
                 `walk_to_nearest` from the previous answer's triangle; parry \
                 `project_local_point(p, true)`; brute force: every triangle)"
            }
            Query::Floor => {
                "floor: one `closest_point_triangle` on the triangle the walk stands on"
            }
            Query::Contact => {
                "contact tick along one path in steady contact (touching once, then 0.5–3 mm \
                 deep, 0.05–0.5 m/s at 1 kHz, scaled to the object): haphe `Proxy::tick` \
                 (god-object: crossings, constraint planes, surface walk, force); parry: the \
                 nearest-point proxy, `project_local_point(hip, true)`, its point when inside, \
                 and the spring force"
            }
            Query::Tool => {
                "tool tick: the contact path with a tool of radius 1 mm (scaled to the \
                 object), its centre moved out along the surface's normal by the radius \
                 (haphe `Proxy::tick` with `tool_radius`: the sphere proxy, swept contacts, \
                 constraint planes tangent to the offset surface; parry: the nearest-point \
                 ball proxy, `project_local_point(hip, true)`, the centre pushed out to the \
                 radius along the line to its surface point, and the spring force)"
            }
            Query::ToolWide => {
                "tool tick with a tool of radius 2 % of the object's size (same calls)"
            }
            Query::Textured => {
                "textured contact tick: the contact path over the object with the texture \
                 `sine:A:L`, A = 0.1 mm and L = 2 mm scaled as the paths are (haphe \
                 `Proxy::tick`: the same tick, and the texture's height and slope under the \
                 contact in the force)"
            }
            Query::Build => {
                "build from the welded mesh (haphe `Surface::new` + `VoxelMap::build`; parry \
                 `TriMesh::with_flags(.., ORIENTED)`)"
            }
            Query::Decode => {
                "decode a saved surface and map (haphe `map::decode`, checks included)"
            }
            Query::Zones => {
                "clear zones of every triangle (haphe `Shape::prepare_clear_zones`, on the \
                 threads the process may use), computed once before the contact ticks so \
                 that no timed tick computes one"
            }
        }
    }
}

/// Who answers a query.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Method {
    /// haphe's accelerated query.
    Haphe,
    /// parry3d-f64 on its `TriMesh` with pseudo-normals (`ORIENTED`).
    Parry,
    /// Every triangle tested (small meshes only).
    BruteForce,
}

impl Method {
    /// The name in tables, JSON records and plots.
    pub fn name(self) -> &'static str {
        match self {
            Method::Haphe => "haphe",
            Method::Parry => "parry",
            Method::BruteForce => "brute_force",
        }
    }
}

/// What the methods of one mesh run on.
#[derive(Clone, Copy)]
pub struct Context<'a> {
    /// haphe's surface.
    pub surface: &'a Surface,
    /// haphe's map.
    pub map: &'a VoxelMap,
    /// parry's mesh, where parry accepted the mesh.
    pub parry: Option<&'a TriMesh>,
    /// The brute-force inside/outside oracle, on meshes small enough for brute force.
    pub oracle: Option<&'a WindingOracle<'a>>,
    /// How many queries brute force runs per kind (whole chunks, spread over the run).
    pub brute_samples: usize,
    /// The query streams.
    pub streams: &'a Streams,
    /// A scene holding the mesh alone, at rest, for the proxy.
    pub scene: &'a Scene,
}

/// The times of one method on one query kind.
pub struct Timed {
    /// Who answered.
    pub method: Method,
    /// Per-query percentiles and mean, clock overhead subtracted.
    pub summary: Summary,
    /// Allocation calls made by the process while this method's queries ran.
    pub allocations: u64,
}

/// The times of every method on one query kind.
pub struct Measured {
    /// The query kind.
    pub query: Query,
    /// The clock overhead: raw times of the empty query, nothing subtracted.
    pub clock: Summary,
    /// One entry per method that ran.
    pub methods: Vec<Timed>,
}

/// One method of one query kind.
struct Runner<'a> {
    method: Method,
    run: Run<'a>,
    /// Runs chunks `0, every, 2·every, ...`.
    every: usize,
}

/// Times every method on query kind `query` (one of [`Query::TIMED`]), interleaved.
pub fn measure(query: Query, cx: Context<'_>) -> Measured {
    let lengths = chunk_lengths(query, cx.streams);
    let mut runners = runners(query, cx, &lengths);
    // Room for every time up front, so that the timed rounds allocate nothing themselves.
    let mut raw: Vec<Vec<u32>> = runners
        .iter()
        .map(|r| Vec::with_capacity(lengths.iter().step_by(r.every).sum()))
        .collect();
    let mut clock = Vec::with_capacity(lengths.iter().sum());
    let mut allocations = vec![0u64; runners.len()];
    let slots = runners.len() + 1;
    for (c, &length) in lengths.iter().enumerate() {
        for k in 0..slots {
            let i = (c + k) % slots;
            match runners.get_mut(i) {
                None => time_empty(length, &mut clock),
                Some(r) if c % r.every == 0 => {
                    let before = alloc::allocations();
                    (r.run)(c, &mut raw[i]);
                    allocations[i] += alloc::allocations() - before;
                }
                Some(_) => {}
            }
        }
    }
    let clock = Summary::of(&mut clock, Overhead::NONE);
    let overhead = Overhead::of(&clock);
    let methods = runners
        .iter()
        .zip(&mut raw)
        .zip(allocations)
        .map(|((r, times), allocations)| Timed {
            method: r.method,
            summary: Summary::of(times, overhead),
            allocations,
        })
        .collect();
    Measured {
        query,
        clock,
        methods,
    }
}

/// The number of queries in each chunk of the stream of `query`.
fn chunk_lengths(query: Query, streams: &Streams) -> Vec<usize> {
    fn lengths<T>(chunks: &[Vec<T>]) -> Vec<usize> {
        chunks.iter().map(Vec::len).collect()
    }
    match query {
        Query::FreeSpace => lengths(&streams.free),
        Query::Segment => lengths(&streams.near_segments),
        Query::SegmentRandom => lengths(&streams.random_segments),
        Query::Inside | Query::Walk | Query::Floor => {
            streams.near.iter().map(|t| t.positions.len()).collect()
        }
        Query::InsideRandom => lengths(&streams.random_points),
        Query::Contact => lengths(&streams.contact),
        Query::Tool => lengths(&streams.tool[0].1),
        Query::ToolWide => lengths(&streams.tool[1].1),
        Query::Textured => lengths(&streams.contact),
        Query::Build | Query::Decode | Query::Zones => Vec::new(),
    }
}

/// A run that times `query` on each of chunk `c`'s inputs, `inputs(c)`.
fn each<'a, T: Copy + 'a, R>(
    inputs: impl Fn(usize) -> &'a [T] + 'a,
    mut query: impl FnMut(T) -> R + 'a,
) -> Run<'a> {
    Box::new(move |c, out| time_each(inputs(c).iter().copied(), &mut query, out))
}

/// The methods of `query`, each a closure that times one chunk.
fn runners<'a>(query: Query, cx: Context<'a>, lengths: &[usize]) -> Vec<Runner<'a>> {
    let Context {
        surface,
        map,
        parry,
        oracle,
        streams,
        scene,
        ..
    } = cx;
    // Brute force on every `every`-th chunk: about `brute_samples` queries in all.
    let total: usize = lengths.iter().sum();
    let every = total
        .checked_div(cx.brute_samples)
        .map_or(usize::MAX, |every| every.max(1));
    let brute = oracle.filter(|_| cx.brute_samples > 0);
    let mut runners: Vec<Runner<'a>> = Vec::new();
    let mut add = |method, run: Run<'a>, every| runners.push(Runner { method, run, every });
    match query {
        Query::FreeSpace | Query::Inside | Query::InsideRandom => {
            let points = move |c: usize| match query {
                Query::FreeSpace => streams.free[c].as_slice(),
                Query::Inside => streams.near[c].positions.as_slice(),
                _ => streams.random_points[c].as_slice(),
            };
            add(
                Method::Haphe,
                each(points, move |p| classify_point(surface, map, p)),
                1,
            );
            if let Some(mesh) = parry {
                add(
                    Method::Parry,
                    each(points, move |p| mesh.contains_local_point(p)),
                    1,
                );
            }
            if let Some(oracle) = brute {
                add(
                    Method::BruteForce,
                    each(points, move |p| oracle.winding(p)),
                    every,
                );
            }
        }
        Query::Segment | Query::SegmentRandom => {
            let segments = move |c: usize| match query {
                Query::Segment => streams.near_segments[c].as_slice(),
                _ => streams.random_segments[c].as_slice(),
            };
            add(
                Method::Haphe,
                each(segments, move |(p0, p1)| {
                    first_crossing(surface, map, p0, p1)
                }),
                1,
            );
            if let Some(mesh) = parry {
                add(
                    Method::Parry,
                    each(segments, move |(p0, p1)| {
                        mesh.cast_local_ray(&Ray::new(p0, p1 - p0), 1.0, false)
                    }),
                    1,
                );
            }
            if brute.is_some() {
                add(
                    Method::BruteForce,
                    each(segments, move |(p0, p1)| {
                        first_crossing_brute_force(surface, p0, p1)
                    }),
                    every,
                );
            }
        }
        Query::Walk => {
            add(
                Method::Haphe,
                Box::new(move |c, out| {
                    let trajectory = &streams.near[c];
                    let mut t = trajectory.start;
                    time_each(
                        trajectory.positions.iter().copied(),
                        |p| {
                            let answer = walk_to_nearest(surface, t, p);
                            t = answer.0.triangle;
                            answer
                        },
                        out,
                    )
                }),
                1,
            );
            let positions = move |c: usize| streams.near[c].positions.as_slice();
            if let Some(mesh) = parry {
                add(
                    Method::Parry,
                    each(positions, move |p| mesh.project_local_point(p, true)),
                    1,
                );
            }
            if brute.is_some() {
                add(
                    Method::BruteForce,
                    each(positions, move |p| nearest_point_brute_force(surface, p)),
                    every,
                );
            }
        }
        Query::Floor => add(
            Method::Haphe,
            Box::new(move |c, out| {
                let trajectory = &streams.near[c];
                time_each(
                    trajectory
                        .current
                        .iter()
                        .copied()
                        .zip(trajectory.positions.iter().copied()),
                    |(t, p)| closest_point_triangle(p, surface.corners(t)),
                    out,
                )
            }),
            1,
        ),
        Query::Contact => {
            // One proxy along the whole path, chunk after chunk (they come in order).
            let mut state: Option<(Proxy, haphe::DVec3)> = None;
            add(
                Method::Haphe,
                Box::new(move |c, out| {
                    let path = &streams.contact[c];
                    let (proxy, previous) = state.get_or_insert_with(|| {
                        (Proxy::new(path[0], ProxyOptions::default()), path[0])
                    });
                    time_each(
                        path.iter().copied(),
                        |hip| {
                            let velocity = (hip - *previous) * TICK_RATE_HZ;
                            *previous = hip;
                            proxy.tick(scene, hip, velocity)
                        },
                        out,
                    )
                }),
                1,
            );
            if let Some(mesh) = parry {
                let stiffness = Material::default().stiffness();
                add(
                    Method::Parry,
                    each(
                        move |c| streams.contact[c].as_slice(),
                        move |hip| {
                            let projection = mesh.project_local_point(hip, true);
                            let proxy = if projection.is_inside {
                                projection.point
                            } else {
                                hip
                            };
                            (proxy, stiffness * (proxy - hip))
                        },
                    ),
                    1,
                );
            }
        }
        Query::Tool | Query::ToolWide => {
            let (radius, path) = &streams.tool[usize::from(query == Query::ToolWide)];
            let (haphe, parry) = super::tool::runs(*radius, path, scene, parry);
            for (method, run) in [(Method::Haphe, haphe), (Method::Parry, parry)] {
                if let Some(run) = run {
                    add(method, run, 1);
                }
            }
        }
        Query::Textured => {
            let unit = streams.tool[0].0;
            if let Some(run) = super::texture::run(scene, unit, &streams.contact) {
                add(Method::Haphe, run, 1);
            }
        }
        Query::Build | Query::Decode | Query::Zones => {}
    }
    runners
}

/// Everything measured on one mesh.
pub struct MeshResult {
    /// `SHAPE-SIZE` or the file name.
    pub name: String,
    /// The shape name or the file name.
    pub family: String,
    /// Triangles of the mesh.
    pub triangles: usize,
    /// Build, decode and memory.
    pub cost: BuildCost,
    /// The timed query kinds.
    pub measured: Vec<Measured>,
}
