"""Batch queries on a Dask cluster of worker processes, the shape sent to them by pickle,
agree with the same queries in this process (the example of docs/python.md, small)."""

import os

import numpy as np
import pytest

import haphe

from test_queries import random_points

# CI installs dask[distributed] and must run this test; elsewhere it is skipped without it.
if os.environ.get("CI"):
    import dask.array as da
    import distributed
else:
    da = pytest.importorskip("dask.array")
    distributed = pytest.importorskip("distributed")

# Every wait is bounded, so that a broken cluster fails the test instead of hanging it.
TIMEOUT = 120


def test_map_blocks_on_a_local_cluster_agrees(models):
    shape = haphe.Shape.from_file(models / "spot.obj")
    points = random_points(shape, 20_000, 51)
    ends = random_points(shape, 20_000, 52)
    inside = shape.inside(points)
    hits = shape.first_crossing(points, ends)
    assert 1000 < inside.sum() < 19_000 and (hits["triangle"] >= 0).sum() > 1000

    cluster = distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1",
        dashboard_address=None, silence_logs=40, timeout=TIMEOUT,
    )
    try:
        with distributed.Client(cluster, timeout=TIMEOUT) as client:
            # The shape goes to every worker once, by pickle (its map file's bytes).
            [remote_shape] = client.scatter([shape], broadcast=True)
            x = da.from_array(points, chunks=(2_500, 3))
            y = da.from_array(ends, chunks=(2_500, 3))
            got_inside = da.map_blocks(
                lambda block, s: s.inside(block), x, remote_shape,
                drop_axis=1, dtype=bool,
            )
            got_t = da.map_blocks(
                lambda a, b, s: s.first_crossing(a, b)["t"], x, y, remote_shape,
                drop_axis=1, dtype=np.float64,
            )
            got_triangle = da.map_blocks(
                lambda a, b, s: s.first_crossing(a, b)["triangle"], x, y, remote_shape,
                drop_axis=1, dtype=np.int64,
            )
            futures = client.compute([got_inside, got_t, got_triangle])
            a, t, triangle = [f.result(timeout=TIMEOUT) for f in futures]
            # The blocks ran in the workers' processes, not here.
            pids = client.run(os.getpid)
            assert len(pids) == 2 and os.getpid() not in pids.values()
    finally:
        cluster.close(timeout=TIMEOUT)
    assert a.dtype == np.bool_ and a.shape == (20_000,)
    np.testing.assert_array_equal(a, inside)
    assert t.tobytes() == hits["t"].tobytes()
    np.testing.assert_array_equal(triangle, hits["triangle"])
