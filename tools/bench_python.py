#!/usr/bin/env python3
"""Side-by-side benchmark of haphe's Python batch queries against Open3D, libigl and
trimesh, in one process, on the same points and segments.

    taskset -c 1 python tools/bench_python.py MESH [MESH ...] [--points N] [--repeat R]
        [--crossing-only]

Needs `pip install . numpy open3d libigl trimesh` (a release build of haphe: `pip install .`
builds with the release profile). Prints one Markdown table row per method and mesh:
ns per point (best of R interleaved rounds, each method timed once per round) and the
disagreements with the winding-number oracle. Points and segments are uniform in the
mesh's bounding box grown by 5 %; segments join two such points (long random segments).
With --crossing-only, only the first crossings are timed (haphe and Open3D), for many
rounds at little cost.

The oracle: where every method agrees, that answer is taken; where any two disagree, the
exact generalised winding number (igl.winding_number, O(triangles) per point) decides,
inside when it exceeds 0.5.
"""

import argparse
import os
import sys
import time

os.environ.setdefault("OMP_NUM_THREADS", "1")

import numpy as np  # noqa: E402

import haphe  # noqa: E402


def best_of(rounds, fn, n):
    """ns per item of the fastest of the timings in `rounds` (list filled by fn)."""
    return min(rounds[fn]) / n * 1e9


def adversarial(name, shape, scene, o3d, n):
    """How many of `haphe verify`'s adversarial segments Open3D's cast_rays misses (the
    brute-force crossing exists within the segment, Open3D reports none within it) or
    invents, and haphe's map query disagrees with the brute force."""
    if n == 0:
        return
    for kind in ["through_vertex", "through_edge", "in_face_plane", "along_edge", "short",
                 "long"]:
        p0, p1 = shape.sample_segments(kind, n, seed=1)
        brute = shape.first_crossing(p0, p1, brute_force=True)
        fast = shape.first_crossing(p0, p1)
        truth = ~np.isnan(brute["t"])
        rays = o3d.core.Tensor(np.hstack([p0, p1 - p0]).astype(np.float32))
        t = scene.cast_rays(rays, nthreads=1)["t_hit"].numpy().astype(np.float64)
        o3d_hit = t <= 1.0
        missed = int((truth & ~o3d_hit).sum())
        invented = int((~truth & o3d_hit).sum())
        haphe_wrong = int((fast["triangle"] != brute["triangle"]).sum())
        print(f"| {name} | adversarial {kind} | {n} segments, {int(truth.sum())} crossing "
              f"| Open3D misses {missed}, reports {invented} not there | haphe differs from "
              f"brute force on {haphe_wrong} |")


def crossings(name, f, n, rounds, answers, segments):
    """The first crossings' rows: haphe against Open3D (float32 rays), hits within the
    segment."""
    pts, p1, size = segments
    h = answers["haphe first_crossing"]
    th = answers["Open3D cast_rays"]["t_hit"].numpy().astype(np.float64)
    o3d_hit = th <= 1.0
    haphe_hit = ~np.isnan(h["t"])
    # A hit/miss difference with the crossing clearly inside or outside the segment
    # (beyond float32 rounding), or a first hit at a clearly different place.
    clear = np.abs(np.where(o3d_hit, th, 2.0) - 1.0) > 1e-5
    hitmiss = int(((o3d_hit != haphe_hit) & clear).sum())
    both = o3d_hit & haphe_hit
    seglen = np.linalg.norm(p1 - pts, axis=1)
    far = int((np.abs(th[both] - h["t"][both]) * seglen[both] > 1e-5 * size.max()).sum())
    print(f"| {name} | {len(f)} | first crossing | haphe first_crossing "
          f"| {best_of(rounds, 'haphe first_crossing', n):.0f} "
          f"| {hitmiss} hit/miss and {far} place differences with Open3D, "
          f"of {int(haphe_hit.sum())} hits |")
    print(f"| {name} | {len(f)} | first crossing | Open3D cast_rays "
          f"| {best_of(rounds, 'Open3D cast_rays', n):.0f} | (float32) |")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("meshes", nargs="+")
    ap.add_argument("--points", type=int, default=200_000)
    # trimesh 5 without Embree takes milliseconds a point, and memory that grows with the
    # points taken at once (20 000 on a 100k mesh filled 24 GiB).
    ap.add_argument("--trimesh-points", type=int, default=20,
                    help="points timed with trimesh contains (default 20)")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--adversarial", type=int, default=1000,
                    help="segments of each adversarial kind (0: skip)")
    ap.add_argument("--crossing-only", action="store_true",
                    help="time only haphe first_crossing and Open3D cast_rays")
    args = ap.parse_args()

    import igl
    import open3d as o3d
    import trimesh

    print(f"affinity: {sorted(os.sched_getaffinity(0))}, points: {args.points}, "
          f"rounds: {args.repeat}")
    print("| mesh | triangles | query | method | ns/query | disagreements with the oracle |")
    print("| --- | ---: | --- | --- | ---: | ---: |")
    for path in args.meshes:
        loaded = trimesh.load(path, force="mesh", process=False, skip_materials=True)
        mesh = trimesh.Trimesh(vertices=loaded.vertices, faces=loaded.faces, process=False)
        v = np.asarray(mesh.vertices, dtype=np.float64)
        f = np.asarray(mesh.faces, dtype=np.int64)
        name = os.path.basename(path)
        t0 = time.perf_counter()
        shape = haphe.Shape.from_file(path)
        build_s = time.perf_counter() - t0
        scene = o3d.t.geometry.RaycastingScene()
        scene.add_triangles(o3d.core.Tensor(v.astype(np.float32)),
                            o3d.core.Tensor(f.astype(np.uint32)))
        lo, hi = v.min(0), v.max(0)
        pad = 0.05 * (hi - lo)
        rng = np.random.default_rng(7)
        pts = rng.uniform(lo - pad, hi + pad, size=(args.points, 3))
        p1 = rng.uniform(lo - pad, hi + pad, size=(args.points, 3))
        few = pts[: args.trimesh_points]
        pts32 = o3d.core.Tensor(pts.astype(np.float32))
        rays = o3d.core.Tensor(np.hstack([pts, p1 - pts]).astype(np.float32))
        vf, ff = v.copy(), f.copy()

        methods = {
            "haphe inside": (lambda: shape.inside(pts), args.points),
            "Open3D compute_occupancy": (
                lambda: scene.compute_occupancy(pts32, nthreads=1).numpy() > 0.5, args.points),
            "libigl fast_winding_number": (
                lambda: igl.fast_winding_number(vf, ff, pts) > 0.5, args.points),
            "trimesh contains": (lambda: mesh.contains(few), args.trimesh_points),
            "haphe first_crossing": (lambda: shape.first_crossing(pts, p1), args.points),
            "Open3D cast_rays": (lambda: scene.cast_rays(rays, nthreads=1), args.points),
        }
        if args.crossing_only:
            methods = {k: m for k, m in methods.items() if "first_crossing" in k or "cast" in k}
        rounds = {k: [] for k in methods}
        answers = {}
        for _ in range(args.repeat):
            for k, (fn, _n) in methods.items():  # interleaved: each method once per round
                t = time.perf_counter()
                answers[k] = fn()
                rounds[k].append(time.perf_counter() - t)
                print(f"  {name}: {k} {rounds[k][-1]:.2f} s", file=sys.stderr, flush=True)

        if args.crossing_only:
            crossings(name, f, args.points, rounds, answers, (pts, p1, hi - lo))
            continue
        # Inside: the oracle where the methods disagree.
        inside_keys = ["haphe inside", "Open3D compute_occupancy", "libigl fast_winding_number"]
        a = np.stack([np.asarray(answers[k], dtype=bool) for k in inside_keys])
        disputed = np.flatnonzero((a != a[0]).any(0))
        t_dispute = np.asarray(answers["trimesh contains"], dtype=bool)
        disputed_few = np.flatnonzero(t_dispute != a[0][: len(few)])
        check = np.union1d(disputed, disputed_few)
        oracle = a[0].copy()
        print(f"  {name}: {len(check)} disputed points for the oracle", file=sys.stderr,
              flush=True)
        if len(check):
            w = igl.winding_number(vf, ff, pts[check])
            oracle[check] = w > 0.5
        for k in inside_keys:
            wrong = int((np.asarray(answers[k], dtype=bool) != oracle).sum())
            print(f"| {name} | {len(f)} | inside | {k} | {best_of(rounds, k, args.points):.0f} "
                  f"| {wrong} of {args.points} |")
        wrong = int((t_dispute != oracle[: len(few)]).sum())
        print(f"| {name} | {len(f)} | inside | trimesh contains "
              f"| {best_of(rounds, 'trimesh contains', len(few)):.0f} | {wrong} of {len(few)} |")

        crossings(name, f, args.points, rounds, answers, (pts, p1, hi - lo))
        print(f"<!-- {name}: haphe shape built in {build_s:.2f} s -->")
        adversarial(name, shape, scene, o3d, args.adversarial)


if __name__ == "__main__":
    main()
