"""Batch queries from Python equal the command line's (the same library calls), on the
shared models."""

import json
from pathlib import Path
import subprocess

import numpy as np
import pytest

import haphe

SOLIDS = ["fandisk.obj", "spot.obj", "rocker-arm.obj", "torus.STL"]


def random_points(shape, n, seed):
    """n points in the shape's bounding box grown by a tenth."""
    lo, hi = (np.array(b) for b in shape.bounds)
    pad = 0.1 * (hi - lo)
    rng = np.random.default_rng(seed)
    return rng.uniform(lo - pad, hi + pad, size=(n, 3))


@pytest.mark.parametrize("name", SOLIDS)
def test_inside_equals_cli(name, models, haphe_cli, tmp_path):
    path = models / name
    shape = haphe.Shape.from_file(path)
    assert shape.is_solid
    points = random_points(shape, 2000, 1)
    csv = tmp_path / "points.csv"
    np.savetxt(csv, points, delimiter=",", fmt="%.17g")
    out = subprocess.run(
        [haphe_cli, "query", str(path), "--inside", str(csv)],
        check=True, capture_output=True, text=True,
    ).stdout.split()
    expected = np.array([w == "inside" for w in out])
    got = shape.inside(points)
    assert got.dtype == np.bool_ and got.shape == (2000,)
    assert 100 < expected.sum() < 1900, "the points straddle the surface"
    np.testing.assert_array_equal(got, expected)


@pytest.mark.parametrize("name", SOLIDS + ["suzanne.obj"])
def test_first_crossing_equals_cli(name, models, haphe_cli, tmp_path):
    path = models / name
    shape = haphe.Shape.from_file(path)
    p0 = random_points(shape, 1000, 2)
    p1 = random_points(shape, 1000, 3)
    csv = tmp_path / "segments.csv"
    np.savetxt(csv, np.hstack([p0, p1]), delimiter=",", fmt="%.17g")
    lines = subprocess.run(
        [haphe_cli, "query", str(path), "--segments", str(csv), "--json"],
        check=True, capture_output=True, text=True,
    ).stdout.splitlines()
    hits = shape.first_crossing(p0, p1)
    assert len(lines) == 1000
    found = 0
    for i, line in enumerate(lines):
        c = json.loads(line)["crossing"]
        if c is None:
            assert np.isnan(hits["t"][i]) and hits["triangle"][i] == -1
            assert np.isnan(hits["point"][i]).all() and not hits["entering"][i]
            continue
        found += 1
        assert hits["triangle"][i] == c["triangle"]
        assert hits["t"][i] == c["t"]
        assert list(hits["point"][i]) == c["point"]
        assert list(hits["normal"][i]) == c["normal"]
        assert hits["entering"][i] == c["entering"]
    assert found > 100


def test_nearest_on_a_cube():
    shape = cube()
    points = np.array([[0.5, 0.5, 1.01], [0.5, 0.5, 1.5], [1.003, 1.004, 0.5]])
    near = shape.nearest(points, 0.02)
    np.testing.assert_allclose(near["distance"][0], 0.01, rtol=1e-12)
    np.testing.assert_allclose(near["point"][0], [0.5, 0.5, 1.0], atol=1e-15)
    assert near["triangle"][0] in (10, 11)  # the faces of the top, as given
    assert np.isinf(near["distance"][1]) and near["triangle"][1] == -1
    np.testing.assert_allclose(near["distance"][2], 0.005, rtol=1e-12)


CUBE_FACES = np.array([
    [0, 2, 1], [0, 3, 2],  # z = 0, facing down
    [0, 1, 5], [0, 5, 4],  # y = 0
    [1, 2, 6], [1, 6, 5],  # x = 1
    [2, 3, 7], [2, 7, 6],  # y = 1
    [3, 0, 4], [3, 4, 7],  # x = 0
    [4, 5, 6], [4, 6, 7],  # z = 1, facing up
])


def cube():
    """The unit cube [0, 1]³ from arrays."""
    v = np.array([[x, y, z] for z in (0, 1) for (x, y) in ((0, 0), (1, 0), (1, 1), (0, 1))],
                 dtype=float)
    return haphe.Shape.from_arrays(v, CUBE_FACES)


def test_from_arrays_cube():
    shape = cube()
    assert shape.is_solid and shape.triangles == 12 and shape.vertices == 8
    got = shape.inside(np.array([[0.5, 0.5, 0.5], [1.5, 0.5, 0.5], [0.5, 0.5, -1e-9]]))
    np.testing.assert_array_equal(got, [True, False, False])
    hits = shape.first_crossing(np.array([[0.5, 0.5, 2.0]]), np.array([[0.5, 0.5, 0.5]]))
    assert hits["entering"][0] and hits["triangle"][0] in (10, 11)
    np.testing.assert_allclose(hits["t"][0], 2.0 / 3.0, rtol=1e-12)
    np.testing.assert_allclose(hits["normal"][0], [0, 0, 1], atol=1e-15)


def test_save_and_load_answer_the_same(models, tmp_path):
    shape = haphe.Shape.from_file(models / "spot.obj")
    saved = tmp_path / "spot.hmap"
    shape.save(saved)
    loaded = haphe.Shape.load(saved)
    assert loaded.triangles == shape.triangles
    points = random_points(shape, 5000, 4)
    np.testing.assert_array_equal(loaded.inside(points), shape.inside(points))
    a = shape.first_crossing(points, points[::-1].copy())
    b = loaded.first_crossing(points, points[::-1].copy())
    np.testing.assert_array_equal(a["triangle"], b["triangle"])


def test_units_scale_the_file(models):
    m = haphe.Shape.from_file(models / "spot.obj")
    mm = haphe.Shape.from_file(models / "spot.obj", units="mm")
    np.testing.assert_allclose(np.array(mm.bounds) * 1000.0, np.array(m.bounds), rtol=1e-12)


def test_strided_and_integer_inputs():
    shape = cube()
    pts = np.array([[0.5, 0.5, 0.5, 9.0], [2.0, 0.5, 0.5, 9.0]])[:, :3]  # not contiguous
    np.testing.assert_array_equal(shape.inside(pts), [True, False])


@pytest.mark.parametrize("kind", ["random", "through_vertex", "through_edge", "in_face_plane",
                                  "along_edge", "short", "long"])
def test_crossings_equal_brute_force_on_adversarial_segments(kind, models):
    shape = haphe.Shape.from_file(models / "spot.obj")
    p0, p1 = shape.sample_segments(kind, 300, seed=5)
    assert p0.shape == (300, 3) and p1.shape == (300, 3)
    fast = shape.first_crossing(p0, p1)
    brute = shape.first_crossing(p0, p1, brute_force=True)
    np.testing.assert_array_equal(fast["triangle"], brute["triangle"])
    np.testing.assert_array_equal(fast["t"], brute["t"])
    np.testing.assert_array_equal(fast["entering"], brute["entering"])
    with pytest.raises(haphe.HapheError, match="unknown segment kind"):
        shape.sample_segments("sideways", 1)


def obj_triangles(path):
    """The triangles of a triangulated OBJ file, an (F, 3, 3) array, read here without
    haphe."""
    vertices, faces = [], []
    for line in Path(path).read_text().splitlines():
        words = line.split()
        if words[:1] == ["v"]:
            vertices.append([float(w) for w in words[1:4]])
        elif words[:1] == ["f"]:
            faces.append([int(w.split("/")[0]) - 1 for w in words[1:4]])
    return np.array(vertices)[np.array(faces)]


def distance_to_triangles(p, tri):
    """The distance from p to the nearest of the triangles (F, 3, 3): the minimum over
    each triangle's interior (when p projects into it) and its three edges."""
    a, b, c = tri[:, 0], tri[:, 1], tri[:, 2]
    n = np.cross(b - a, c - a)
    n /= np.linalg.norm(n, axis=1)[:, None]
    h = np.einsum("ij,ij->i", p - a, n)
    q = p - h[:, None] * n
    inside = np.ones(len(tri), dtype=bool)
    for u, v in ((a, b), (b, c), (c, a)):
        inside &= np.einsum("ij,ij->i", np.cross(v - u, q - u), n) >= 0
    best = np.where(inside, np.abs(h), np.inf)
    for u, v in ((a, b), (b, c), (c, a)):
        e = v - u
        t = np.clip(np.einsum("ij,ij->i", p - u, e) / np.einsum("ij,ij->i", e, e), 0, 1)
        best = np.minimum(best, np.linalg.norm(p - (u + t[:, None] * e), axis=1))
    return best.min()


def test_nearest_is_exact_far_beyond_a_map_cell(models):
    # The point 0.1 m outside spot along its top's normal, with max_distance=1.0: many
    # map cells away, and well within the distance asked.
    path = models / "spot.obj"
    shape = haphe.Shape.from_file(path)
    tri = obj_triangles(path)
    lo, hi = (np.array(b) for b in shape.bounds)
    top = np.array([(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, hi[2]])
    points = np.array([top + [0, 0, 0.1], hi + 0.1, lo - [0.3, 0.0, 0.0]])
    near = shape.nearest(points, 1.0)
    within = 0
    for i, p in enumerate(points):
        expected = distance_to_triangles(p, tri)
        assert expected > 0.09
        if expected > 1.0:
            assert np.isinf(near["distance"][i]) and near["triangle"][i] == -1
            continue
        within += 1
        np.testing.assert_allclose(near["distance"][i], expected, rtol=1e-9)
        assert near["triangle"][i] >= 0
        np.testing.assert_allclose(np.linalg.norm(near["point"][i] - p), expected, rtol=1e-9)
    assert within >= 2
    # Asked for less than the distance: none.
    short = shape.nearest(points, 0.05)
    assert np.isinf(short["distance"]).all() and (short["triangle"] == -1).all()


def test_from_file_takes_a_map_and_refuses_a_stale_one(models, haphe_cli, tmp_path):
    source = tmp_path / "spot.obj"
    source.write_bytes((models / "spot.obj").read_bytes())
    saved = tmp_path / "spot.map"
    subprocess.run([haphe_cli, "build", str(source), "-o", str(saved)],
                   check=True, capture_output=True)
    mesh = haphe.Shape.from_file(source)
    for shape in (haphe.Shape.from_file(saved), haphe.Shape.load(saved)):
        assert shape.triangles == mesh.triangles
        points = random_points(mesh, 3000, 8)
        np.testing.assert_array_equal(shape.inside(points), mesh.inside(points))
        a, b = shape.nearest(points, 0.05), mesh.nearest(points, 0.05)
        np.testing.assert_array_equal(a["distance"], b["distance"])
        np.testing.assert_array_equal(a["triangle"], b["triangle"])
    with pytest.raises(haphe.HapheError, match="in metres"):
        haphe.Shape.from_file(saved, units="mm")
    # The source beside the map changes: the map is refused, naming both files.
    source.write_bytes(source.read_bytes() + b"# edited\n")
    for load in (haphe.Shape.from_file, haphe.Shape.load):
        with pytest.raises(haphe.HapheError, match=r"spot\.map was built from spot\.obj.*haphe build"):
            load(saved)
