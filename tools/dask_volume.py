#!/usr/bin/env python3
"""Inside queries over many random points on a Dask cluster: a solid's volume by Monte
Carlo, against the exact volume of `haphe validate`.

The shape is built once, in this process, and sent to every worker by pickle (its map
file's bytes, not rebuilt there); the points are drawn on the workers, block by block, and
`dask.array.map_blocks` runs `shape.inside` on each block. Needs `dask[distributed]`.

    python3 tools/dask_volume.py meshes/models/spot.obj --points 1e8 --workers 2
    python3 tools/dask_volume.py part.stl --scheduler tcp://HOST:8786    # a running cluster
"""

import argparse
import math
import time

import dask.array as da
import distributed
import numpy as np

import haphe


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("mesh", help="a closed mesh file (metres)")
    parser.add_argument("--points", type=float, default=1e8, help="random points (1e8)")
    parser.add_argument("--chunk", type=float, default=1e6, help="points per block (1e6)")
    parser.add_argument("--workers", type=int, default=2,
                        help="worker processes of a local cluster (2), one thread each")
    parser.add_argument("--scheduler", help="address of a running cluster instead")
    parser.add_argument("--seed", type=int, default=1)
    args = parser.parse_args()
    n, chunk = int(args.points), int(args.chunk)

    start = time.perf_counter()
    shape = haphe.Shape.from_file(args.mesh)
    exact = haphe.validate(args.mesh, self_intersections=False)["volume"]
    print(f"{shape!r}: built in {time.perf_counter() - start:.1f} s, "
          f"{len(shape.to_bytes()) / 1e6:.1f} MB pickled")
    lo, hi = (np.array(b) for b in shape.bounds)

    if args.scheduler:
        cluster = None
        client = distributed.Client(args.scheduler)
    else:
        cluster = distributed.LocalCluster(
            n_workers=args.workers, threads_per_worker=1, processes=True,
            host="127.0.0.1", dashboard_address=None,
        )
        client = distributed.Client(cluster)
    try:
        # Every worker gets the shape once, by pickle.
        [remote] = client.scatter([shape], broadcast=True)
        rng = da.random.default_rng(args.seed)
        points = lo + (hi - lo) * rng.random((n, 3), chunks=(chunk, 3))
        inside = da.map_blocks(
            lambda block, s: s.inside(block), points, remote,
            drop_axis=1, dtype=bool, meta=np.array((), dtype=bool),
        )
        start = time.perf_counter()
        count = int(inside.sum().compute())
        seconds = time.perf_counter() - start
        workers = len(client.scheduler_info()["workers"])
    finally:
        client.close()
        if cluster is not None:
            cluster.close()

    box = float(np.prod(hi - lo))
    fraction = count / n
    volume = box * fraction
    sigma = box * math.sqrt(fraction * (1 - fraction) / n)
    print(f"{n:.3g} points in {n // chunk} blocks on {workers} workers: {seconds:.1f} s, "
          f"{seconds / n * 1e9 * workers:.0f} ns per point and worker")
    print(f"inside: {count} ({fraction:.6f} of the box)")
    print(f"volume: {volume:.6e} m³ ± {sigma:.1e} (1σ), exact {exact:.6e} m³: "
          f"off by {(volume - exact) / sigma:+.2f}σ")


if __name__ == "__main__":
    main()
