"""Batch queries take what numpy takes, refuse non-finite rows by name (or skip them on
request), and release the GIL."""

import sys
import threading

import numpy as np
import pytest

import haphe

from test_queries import CUBE_FACES, cube, random_points


@pytest.fixture(scope="module")
def spot(models):
    return haphe.Shape.from_file(models / "spot.obj")


def test_array_likes_convert_as_numpy_does(spot):
    points = random_points(spot, 3000, 21)
    expected = spot.inside(points)
    assert 100 < expected.sum() < 2900, "the points straddle the surface"
    # What each form turns into under numpy.asarray(x, dtype=float64): the same numbers,
    # except float32, whose rounded points are the float64 array of their values.
    as_f32 = points.astype(np.float32)
    fortran = np.asfortranarray(points)
    wide = np.zeros((3000, 7))
    wide[:, 2:5] = points
    strided = wide[:, 2:5]
    reversed_rows = points[::-1]
    assert not fortran.flags.c_contiguous and not strided.flags.c_contiguous
    cases = [
        (points.tolist(), expected),
        (tuple(map(tuple, points)), expected),
        (fortran, expected),
        (strided, expected),
        (reversed_rows, expected[::-1]),
        (points.astype(">f8"), expected),  # byte-swapped
        (as_f32, spot.inside(as_f32.astype(np.float64))),
    ]
    for x, want in cases:
        np.testing.assert_array_equal(spot.inside(x), want)
    # Integers (whole metres): converted, not refused. The cube [0, 2]³ holds (1, 1, 1).
    v = np.array([[x, y, z] for z in (0, 2) for (x, y) in ((0, 0), (2, 0), (2, 2), (0, 2))])
    big = haphe.Shape.from_arrays(v.tolist(), CUBE_FACES)
    np.testing.assert_array_equal(big.inside(np.array([[1, 1, 1], [3, 1, 1]])), [True, False])
    np.testing.assert_array_equal(cube().inside(np.array([[0.5, 0.5, 0.5]], np.float16)), [True])


def test_segments_and_nearest_take_array_likes(spot):
    p0 = random_points(spot, 500, 22)
    p1 = random_points(spot, 500, 23)
    a = spot.first_crossing(p0, p1)
    assert (a["triangle"] >= 0).sum() > 50
    b = spot.first_crossing(p0.tolist(), np.asfortranarray(p1))
    for key in a:
        np.testing.assert_array_equal(a[key], b[key])
    near_a = spot.nearest(p0, 0.01)
    near_b = spot.nearest(p0.tolist(), 0.01)
    for key in near_a:
        np.testing.assert_array_equal(near_a[key], near_b[key])


@pytest.mark.parametrize("bad", [
    np.zeros((4, 2)), np.zeros(3), np.zeros((2, 3, 1)), [[1.0, 2.0], [3.0]], "abc",
])
def test_a_wrong_shape_names_the_argument(bad):
    shape = cube()
    with pytest.raises(haphe.HapheError, match=r"^points: .*shape \(N, 3\)"):
        shape.inside(bad)
    with pytest.raises(haphe.HapheError, match=r"^p1: .*shape \(N, 3\)"):
        shape.first_crossing(np.zeros((4, 3)), bad)
    with pytest.raises(haphe.HapheError, match=r"^points: .*shape \(N, 3\)"):
        shape.nearest(bad, 0.1)


def test_empty_batches_answer_empty_arrays():
    shape = cube()
    assert shape.inside(np.zeros((0, 3))).shape == (0,)
    hits = shape.first_crossing(np.zeros((0, 3)), np.zeros((0, 3)))
    assert hits["t"].shape == (0,) and hits["point"].shape == (0, 3)


@pytest.mark.parametrize("value", [np.nan, np.inf, -np.inf])
def test_a_non_finite_point_names_the_first_bad_row(value):
    shape = cube()
    points = np.full((50, 3), 0.5)
    points[7, 2] = value
    points[30, 0] = np.nan
    with pytest.raises(haphe.HapheError, match=r"^points: row 7 is not finite") as e:
        shape.inside(points)
    assert "skip" in str(e.value), "the message tells how to skip such rows"
    with pytest.raises(haphe.HapheError, match=r"^points: row 7 is not finite"):
        shape.nearest(points, 0.1)
    with pytest.raises(haphe.HapheError, match=r"^p0: row 7 is not finite"):
        shape.first_crossing(points, np.zeros((50, 3)))
    with pytest.raises(haphe.HapheError, match=r"^p1: row 7 is not finite"):
        shape.first_crossing(np.zeros((50, 3)), points, brute_force=True)
    # The lists and float32 arrays a caller may pass are checked the same way.
    with pytest.raises(haphe.HapheError, match=r"^points: row 7 is not finite"):
        shape.inside(points.astype(np.float32).tolist())


def test_skip_answers_nothing_found_on_the_bad_rows_only():
    shape = cube()
    rng = np.random.default_rng(5)
    points = rng.uniform(-0.5, 1.5, size=(400, 3))
    bad = np.zeros(400, bool)
    bad[[3, 99, 250]] = True
    spoiled = points.copy()
    spoiled[3, 0], spoiled[99, 1], spoiled[250, 2] = np.nan, np.inf, -np.inf
    good = ~bad
    # The truth for the unit cube, computed from the coordinates.
    truth = ((points > 0) & (points < 1)).all(axis=1)
    inside = shape.inside(spoiled, nonfinite="skip")
    np.testing.assert_array_equal(inside[good], truth[good])
    assert not inside[bad].any()
    far = np.array([0.5, 0.5, 3.0])
    hits = shape.first_crossing(np.broadcast_to(far, spoiled.shape), spoiled, nonfinite="skip")
    assert (hits["triangle"][bad] == -1).all() and np.isnan(hits["t"][bad]).all()
    assert np.isnan(hits["point"][bad]).all() and not hits["entering"][bad].any()
    # A segment from above the cube to an inside point enters through the top.
    enters = good & truth
    assert enters.sum() > 20
    assert hits["entering"][enters].all()
    np.testing.assert_allclose(hits["point"][enters][:, 2], 1.0, rtol=0, atol=1e-12)
    near = shape.nearest(spoiled, 0.2, nonfinite="skip")
    assert np.isinf(near["distance"][bad]).all() and (near["triangle"][bad] == -1).all()
    with pytest.raises(haphe.HapheError, match="^nonfinite: must be"):
        shape.inside(points, nonfinite="ignore")


@pytest.mark.parametrize("query", ["inside", "first_crossing", "nearest"])
def test_batch_calls_release_the_gil(spot, query):
    """A second Python thread runs while the first is inside a batch call.

    With the switch interval set far beyond the test, the interpreter never takes the GIL
    from a thread that holds it: the main thread, woken by `started`, runs only when the
    worker releases the GIL. So if the batch call held it, the worker would have finished
    (and set `done`) before the main thread ran again; that the main thread finds `done`
    unset, and runs a batch call of its own meanwhile, shows the two overlapping.
    """
    points = random_points(spot, 200_000, 24)
    call = {
        "inside": lambda p: spot.inside(p),
        "first_crossing": lambda p: spot.first_crossing(p, p[::-1]),
        "nearest": lambda p: spot.nearest(p, 0.01),
    }[query]
    started, done = threading.Event(), threading.Event()

    def worker():
        started.set()
        call(points)
        done.set()

    interval = sys.getswitchinterval()
    sys.setswitchinterval(1000.0)
    thread = threading.Thread(target=worker)
    try:
        thread.start()
        started.wait()
        overlapped = not done.is_set()
        call(points[:1000])  # the main thread's own batch call, during the worker's
    finally:
        sys.setswitchinterval(interval)
        thread.join()
    assert overlapped, f"{query} held the GIL: the other thread could not run meanwhile"
    assert done.is_set()
