//! The records of a run: one per (mesh, query, method), written by `--json` as one JSON
//! array, and the source of the tables and plots.

use std::path::Path;

use serde::Serialize;

use super::methods::{MeshResult, Method, Query};
use super::timing::Summary;

/// The fields of a record, for `haphe bench --help`.
pub const FIELDS: &str = "\
JSON output (--json OUT): an array with one record per (mesh, query, method):
  mesh                 mesh name: SHAPE-SIZE (e.g. blob-10k) or the file name
  family               shape name (blob, thin-plate, ...) or the file name
  triangles            triangle count of the mesh
  query                free_space | segment | segment_random | inside | inside_random |
                       walk | floor | contact | tool | tool_wide | build | decode |
                       zones
  method               haphe | parry | brute_force
  samples              queries timed (builds, decodes or zone runs for build, decode,
                       zones)
  p50_ns, p99_ns, p999_ns, max_ns
                       per-query percentiles in nanoseconds, the clock overhead's median
                       subtracted (build, decode, zones: per run, nothing subtracted)
  trimmed_mean_ns      mean of the fastest 99 % of the queries, the same mean of the
                       clock overhead subtracted: resolves costs below the clock's step
  clock_overhead_ns    median cost of reading the clock around an empty query, the
                       amount subtracted from the percentiles (null for build, decode,
                       zones)
  vs_haphe_p50, vs_haphe_p99
                       this method's time divided by haphe's on the same mesh and query
                       (null on haphe's own records)
  vs_floor_p50         p50 divided by the floor's p50 on the same mesh (timed queries)
  allocations          allocation calls made while this method's queries ran (timed
                       queries; 0 means the query path allocates nothing)
  bytes                build: heap bytes the built structures hold, counted by the
                       allocator (haphe: surface + map; parry: TriMesh); decode: size of
                       the saved surface and map
  heap_bytes           build, haphe: surface + map by their own heap_bytes()";

/// One line of the results.
#[derive(Debug, Clone, Serialize)]
pub struct Record {
    /// Mesh name.
    pub mesh: String,
    /// Shape family or file name.
    pub family: String,
    /// Triangles of the mesh.
    pub triangles: usize,
    /// Query kind.
    pub query: Query,
    /// Method.
    pub method: Method,
    /// Queries (or builds) timed.
    pub samples: usize,
    /// Median, nanoseconds.
    pub p50_ns: f64,
    /// 99th percentile, nanoseconds.
    pub p99_ns: f64,
    /// 99.9th percentile, nanoseconds.
    pub p999_ns: f64,
    /// Slowest, nanoseconds.
    pub max_ns: f64,
    /// Mean of the fastest 99 %, nanoseconds.
    pub trimmed_mean_ns: f64,
    /// Clock overhead subtracted, nanoseconds.
    pub clock_overhead_ns: Option<f64>,
    /// p50 over haphe's p50.
    pub vs_haphe_p50: Option<f64>,
    /// p99 over haphe's p99.
    pub vs_haphe_p99: Option<f64>,
    /// p50 over the floor's p50.
    pub vs_floor_p50: Option<f64>,
    /// Allocation calls during the timed queries.
    pub allocations: Option<u64>,
    /// Heap bytes of the built structures (allocator count), or the saved file's size.
    pub bytes: Option<usize>,
    /// Heap bytes of haphe's structures by their own account.
    pub heap_bytes: Option<usize>,
}

impl Record {
    fn new(mesh: &MeshResult, query: Query, method: Method, s: &Summary) -> Record {
        Record {
            mesh: mesh.name.clone(),
            family: mesh.family.clone(),
            triangles: mesh.triangles,
            query,
            method,
            samples: s.samples,
            p50_ns: s.p50,
            p99_ns: s.p99,
            p999_ns: s.p999,
            max_ns: s.max,
            trimmed_mean_ns: s.trimmed_mean,
            clock_overhead_ns: None,
            vs_haphe_p50: None,
            vs_haphe_p99: None,
            vs_floor_p50: None,
            allocations: None,
            bytes: None,
            heap_bytes: None,
        }
    }
}

/// The records of every mesh, mesh by mesh, in the order of [`Query::ALL`].
pub fn records(results: &[MeshResult]) -> Vec<Record> {
    let mut all = Vec::new();
    for mesh in results {
        let first = all.len();
        for measured in &mesh.measured {
            for timed in &measured.methods {
                let mut r = Record::new(mesh, measured.query, timed.method, &timed.summary);
                r.clock_overhead_ns = Some(measured.clock.p50);
                r.allocations = Some(timed.allocations);
                all.push(r);
            }
        }
        let cost = &mesh.cost;
        let mut haphe = Record::new(
            mesh,
            Query::Build,
            Method::Haphe,
            &Summary::of_durations(&cost.haphe),
        );
        haphe.bytes = Some(cost.haphe_bytes);
        haphe.heap_bytes = Some(cost.haphe_heap_bytes);
        all.push(haphe);
        if !cost.parry.is_empty() {
            let mut parry = Record::new(
                mesh,
                Query::Build,
                Method::Parry,
                &Summary::of_durations(&cost.parry),
            );
            parry.bytes = cost.parry_bytes;
            all.push(parry);
        }
        let mut decode = Record::new(
            mesh,
            Query::Decode,
            Method::Haphe,
            &Summary::of_durations(&cost.decode),
        );
        decode.bytes = Some(cost.file_bytes);
        all.push(decode);
        if !cost.zones.is_empty() {
            all.push(Record::new(
                mesh,
                Query::Zones,
                Method::Haphe,
                &Summary::of_durations(&cost.zones),
            ));
        }
        add_ratios(&mut all[first..]);
    }
    all
}

/// Fills the ratios of one mesh's records to haphe's and to the floor.
fn add_ratios(records: &mut [Record]) {
    let find = |query: Query| {
        records
            .iter()
            .find(|r| r.query == query && r.method == Method::Haphe)
            .map(|r| (r.p50_ns, r.p99_ns))
    };
    let floor = find(Query::Floor).map(|(p50, _)| p50);
    let haphe: Vec<_> = Query::ALL.iter().map(|&q| find(q)).collect();
    for r in records.iter_mut() {
        let index = Query::ALL.iter().position(|&q| q == r.query);
        if r.method != Method::Haphe
            && let Some((p50, p99)) = index.and_then(|i| haphe[i])
        {
            r.vs_haphe_p50 = ratio(r.p50_ns, p50);
            r.vs_haphe_p99 = ratio(r.p99_ns, p99);
        }
        if r.clock_overhead_ns.is_some()
            && let Some(floor) = floor
        {
            r.vs_floor_p50 = ratio(r.p50_ns, floor);
        }
    }
}

/// `a / b`, or `None` when `b` is not a positive time (below the clock's resolution).
pub fn ratio(a: f64, b: f64) -> Option<f64> {
    (b > 0.0 && a.is_finite() && b.is_finite()).then(|| a / b)
}

/// Writes the records as one JSON array to `path`.
///
/// # Errors
/// When the file cannot be written.
pub fn write(path: &Path, records: &[Record]) -> anyhow::Result<()> {
    let text = serde_json::to_string_pretty(records)?;
    crate::output::write_output(path, |out| Ok(out.write_all((text + "\n").as_bytes())?))
}
