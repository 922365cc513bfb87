"""A shape pickles as its map file's bytes and answers bit for bit the same after the trip,
also in another process."""

import copy
import multiprocessing
import pickle

import numpy as np
import pytest

import haphe

from test_queries import random_points


@pytest.fixture(scope="module")
def spot(models):
    return haphe.Shape.from_file(models / "spot.obj")


def answers(shape, seed):
    """Every batch answer of `shape` on random points and segments, as raw bytes."""
    p0 = random_points(shape, 3000, seed)
    p1 = random_points(shape, 3000, seed + 1)
    out = {"inside": shape.inside(p0)}
    for key, a in shape.first_crossing(p0, p1).items():
        out["crossing_" + key] = a
    for key, a in shape.nearest(p0, 0.02).items():
        out["nearest_" + key] = a
    return {k: (a.dtype.str, a.shape, a.tobytes()) for k, a in out.items()}


def test_pickle_round_trips_bit_for_bit(spot, tmp_path):
    data = pickle.dumps(spot, protocol=pickle.HIGHEST_PROTOCOL)
    back = pickle.loads(data)
    assert isinstance(back, haphe.Shape) and back is not spot
    assert repr(back) == repr(spot)
    assert (back.triangles, back.vertices, back.is_solid, back.bounds) == (
        spot.triangles, spot.vertices, spot.is_solid, spot.bounds)
    before, after = answers(spot, 31), answers(back, 31)
    assert before == after
    # The bytes are the map file `save` writes, read back without rebuilding.
    saved = tmp_path / "spot.hmap"
    spot.save(saved)
    assert spot.to_bytes() == saved.read_bytes() == back.to_bytes()
    assert len(data) < len(saved.read_bytes()) + 1000
    hits = back.first_crossing(*back.sample_segments("through_edge", 200, seed=3))
    brute = back.first_crossing(*back.sample_segments("through_edge", 200, seed=3),
                                brute_force=True)
    np.testing.assert_array_equal(hits["triangle"], brute["triangle"])


@pytest.mark.parametrize("protocol", [2, 4, 5])
def test_every_pickle_protocol(protocol):
    from test_queries import cube
    shape = cube()
    back = pickle.loads(pickle.dumps(shape, protocol=protocol))
    np.testing.assert_array_equal(back.inside([[0.5, 0.5, 0.5], [2, 0, 0]]), [True, False])


def test_copies_are_the_shape_itself(spot):
    assert copy.copy(spot) is spot and copy.deepcopy(spot) is spot
    assert copy.deepcopy({"a": spot})["a"] is spot


def test_damaged_bytes_are_refused_by_name(spot):
    data = bytearray(spot.to_bytes())
    data[len(data) // 2] ^= 0x40
    with pytest.raises(haphe.HapheError, match=r"^pickled: .*checksum"):
        haphe.Shape.from_bytes(bytes(data), name="pickled")
    with pytest.raises(haphe.HapheError, match=r"^bytes: "):
        haphe.Shape.from_bytes(b"not a map")


def worker_answers(shape, seed):
    """Runs in a worker process: the shape arrived by pickle."""
    return answers(shape, seed)


def test_multiprocessing_answers_bit_for_bit(spot):
    # "spawn": a fresh interpreter, which has only what the pickle carries.
    with multiprocessing.get_context("spawn").Pool(2) as pool:
        remote = pool.starmap(worker_answers, [(spot, 41), (spot, 42)], chunksize=1)
    assert remote == [answers(spot, 41), answers(spot, 42)]
