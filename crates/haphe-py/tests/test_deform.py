"""Deformable shapes from Python: a sphere deformed with numpy at every tick while the proxy
presses on it, the library's brute-force comparison, bad deformations refused with the
scene unchanged, and the arrays of a shape in the order deformation takes."""

import sys
import threading

import numpy as np
import pytest

import haphe
from conftest import ROOT

RADIUS = 0.05  # metres: the repository's unit sphere, scaled
RATE_HZ = 1000.0
DENT_DEPTH = 0.008  # metres, as the library's Deformation::Dent


def sphere():
    """The unit icosphere of meshes/models (642 vertices) at a radius of 5 cm."""
    return haphe.Shape.from_file(ROOT / "meshes" / "models" / "sphere.ply", units=str(RADIUS))


def breathe_and_dent(rest, t):
    """The vertices at time t (s): the library's `Deformation::BreatheAndDent` in numpy.
    The shape scales about its centre by 0.85 to 1.15 at 2 Hz; a dent 8 mm deep and a
    third of a radian wide travels around the vertical axis (a turn in 4 s, 30° above the
    equator), pressing vertices toward the centre."""
    lo, hi = rest.min(axis=0), rest.max(axis=0)
    c, size = 0.5 * (lo + hi), 0.5 * (hi - lo).max()
    scale = 1.0 + 0.15 * np.sin(2 * np.pi * 2.0 * t)
    turn = 2 * np.pi * t / 4.0
    up = np.radians(30.0)
    centre = np.array([np.cos(turn) * np.cos(up), np.sin(turn) * np.cos(up), np.sin(up)])
    offset = rest - c
    length = np.linalg.norm(offset, axis=1, keepdims=True)
    away = np.divide(offset, length, out=np.zeros_like(offset), where=length > 0)
    angle = np.arccos(np.clip(away @ centre, -1.0, 1.0))
    width = (size / 3.0) / size
    fall = np.cos(0.5 * np.pi * angle / width) ** 2
    dented = np.where((angle < width)[:, None], rest - away * (DENT_DEPTH * fall)[:, None], rest)
    return c + scale * (dented - c)


def pressing_path(ticks):
    """Device points that press in and out of the breathing sphere: along a direction 30°
    above the equator turning once in 3 s (so the dent, turning once in 4 s, passes under
    it), from 3 mm outside the breathing radius to 11 mm inside it, 1.7 times a second."""
    t = np.arange(ticks) / RATE_HZ
    turn, up = 2 * np.pi * t / 3.0 + 0.5, np.radians(30.0)
    direction = np.stack(
        [np.cos(turn) * np.cos(up), np.sin(turn) * np.cos(up), np.full_like(t, np.sin(up))], 1
    )
    breathing = RADIUS * (1.0 + 0.15 * np.sin(2 * np.pi * 2.0 * t))
    depth = -0.004 + 0.007 * np.cos(2 * np.pi * 1.7 * t)
    return direction * (breathing + depth)[:, None]


def test_a_breathing_dented_sphere_deformed_every_tick_is_never_entered():
    ticks, stiffness, skin, max_force = 600, 300.0, 1e-6, haphe.DEFAULT_MAX_FORCE
    shape = sphere()
    rest, faces = shape.arrays()
    scene = haphe.Scene()
    oid = scene.add(shape, stiffness=stiffness)
    path = pressing_path(ticks)
    proxy = haphe.Proxy(position=path[0], max_force=max_force, skin=skin)
    hand_inside = proxy_inside = examined = 0
    touching = []
    for tick, hip in enumerate(path):
        scene.deform(oid, breathe_and_dent(rest, tick / RATE_HZ))
        force, position, contact = proxy.tick(scene, hip)
        now = scene.shape(oid)
        assert now.version == tick + 1, "one deformation a tick"
        assert np.all(np.isfinite(force)) and np.linalg.norm(force) <= max_force * (1 + 1e-12)
        hand_inside += bool(now.inside([hip])[0])
        if now.inside([position])[0]:
            # Inside by the map: allowed only within the skin (the proxy rests a skin off
            # the surface, and a surface that moved is pushed out of by the next tick).
            depth = now.nearest([position], 0.01)["distance"][0]
            assert depth <= skin, f"tick {tick}: the proxy is {depth:.3g} m inside the surface"
            proxy_inside += 1
        touching.append(contact is not None)
        assert contact is None or contact.version == tick + 1, "the tick felt this deformation"
        examined += 1
    assert examined == ticks
    # Guard: the hand (a path of the scene, not of the proxy) is inside the current surface
    # on a good share of ticks, so the checks above ran in contact, not in free space.
    assert hand_inside > ticks // 4, hand_inside
    assert sum(touching) >= 0.9 * hand_inside, (sum(touching), hand_inside)
    np.testing.assert_array_equal(scene.shape(oid).arrays()[1], faces)

    # The library's own check of the first half of the path (a deformation costs tens of
    # milliseconds in the dev profile the tests build): the proxy against a brute-force
    # proxy (every triangle, no map) at every tick of the same deformation, in Rust.
    checked = ticks // 2
    fresh = haphe.Scene()
    fresh.add(shape, stiffness=stiffness)
    check = haphe.check_deforming(fresh, "breathe-dent", path[:checked])
    assert check["ticks"] == checked
    assert check["mismatches"] == 0 and check["inside"] == 0 and check["bad_forces"] == 0, check
    # Guard: the half checked holds contact (the hand presses in within 0.3 s).
    assert check["contact_ticks"] > checked // 4, check
    # numpy's formula is the library's: the same contact, tick for tick but for a few
    # (rounding), and the same shape at the last tick checked.
    assert abs(check["contact_ticks"] - sum(touching[:checked])) <= checked // 100, check
    np.testing.assert_allclose(
        fresh.shape(0).arrays()[0], breathe_and_dent(rest, (checked - 1) / RATE_HZ),
        rtol=0, atol=1e-12,
    )


@pytest.fixture
def deformable():
    shape = sphere()
    scene = haphe.Scene()
    oid = scene.add(shape)
    return scene, oid, shape.arrays()[0]


def refused(scene, oid, rest, error, match, vertices, **kwargs):
    with pytest.raises(error, match=match):
        scene.deform(oid, vertices, **kwargs)
    now = scene.shape(oid)
    assert now.version == 0, f"{match}: the scene changed"
    np.testing.assert_array_equal(now.arrays()[0], rest)


def test_bad_deformations_are_refused_naming_the_row_and_leave_the_scene_unchanged(deformable):
    scene, oid, rest = deformable
    n = len(rest)
    for k, bad in ((17, np.nan), (0, np.inf), (n - 1, -np.inf), (5, 2e9)):
        v = rest.copy()
        v[k, 1] = bad
        refused(scene, oid, rest, haphe.HapheError, f"^vertices: row {k}: a coordinate", v)
    refused(scene, oid, rest, haphe.HapheError, r"^vertices: expected an array of shape \(N, 3\)",
            rest[:, :2])
    refused(scene, oid, rest, haphe.HapheError,
            f"^vertices: {n - 1} vertex positions given, but the shape has {n} vertices", rest[1:])
    refused(scene, oid, rest, haphe.HapheError, "^vertices: cannot be read", [[0, 0, "x"]])
    two = rest[:2] * 1.01
    refused(scene, oid, rest, haphe.HapheError,
            f"^indices: row 1: vertex index {n + 5} is out of range \\(the shape has {n} vertices\\)",
            two, indices=[3, n + 5])
    refused(scene, oid, rest, haphe.HapheError, "^indices: row 0: vertex index -1 is out of range",
            two, indices=np.array([-1, 2]))
    refused(scene, oid, rest, haphe.HapheError, f"^indices: row 1: vertex index {2**40}",
            two, indices=np.array([1, 2**40], dtype=np.uint64))
    refused(scene, oid, rest, haphe.HapheError, "^indices: 3 vertex indices but 2 positions",
            two, indices=[1, 2, 3])
    refused(scene, oid, rest, haphe.HapheError, "^indices: expected a 1-D array of integers",
            two, indices=[[1, 2]])
    refused(scene, oid, rest, haphe.HapheError, "^indices: expected a 1-D array of integers",
            two, indices=[1.0, 2.0])
    nan_row = two.copy()
    nan_row[1, 2] = np.nan
    refused(scene, oid, rest, haphe.HapheError, "^vertices: row 1: a coordinate", nan_row,
            indices=[1, 2])
    for unknown in (oid + 1, 99):
        with pytest.raises(KeyError):
            scene.deform(unknown, rest)
        with pytest.raises(KeyError):
            scene.shape(unknown)
    assert scene.shape(oid).version == 0
    # The scene still takes a good deformation afterwards.
    scene.deform(oid, rest * 1.01)
    assert scene.shape(oid).version == 1


def test_arrays_round_trip_and_deform_as_given(deformable):
    scene, oid, _ = deformable
    shape = scene.shape(oid)
    v, f = shape.arrays()
    assert v.shape == (shape.vertices, 3) and v.dtype == np.float64
    assert f.shape == (shape.triangles, 3) and f.dtype == np.int64
    assert f.min() == 0 and f.max() == len(v) - 1
    np.testing.assert_allclose(np.linalg.norm(v, axis=1), RADIUS, rtol=1e-6)
    # The arrays are the surface: a shape built from them answers as the shape does.
    points = np.random.default_rng(3).uniform(-1.2 * RADIUS, 1.2 * RADIUS, (2000, 3))
    rebuilt = haphe.Shape.from_arrays(v, f)
    np.testing.assert_array_equal(rebuilt.inside(points), shape.inside(points))
    assert rebuilt.is_solid and rebuilt.bounds == shape.bounds

    scene.deform(oid, v)  # unchanged positions: the same geometry, a new version
    same = scene.shape(oid)
    assert same.version == 1
    np.testing.assert_array_equal(same.arrays()[0], v)
    np.testing.assert_array_equal(same.inside(points), shape.inside(points))

    # Scaled, given as numpy takes arrays: float32, Fortran order, a list.
    for version, given in enumerate(
        (np.asfortranarray(1.1 * v), (1.1 * v).astype(np.float32), (1.1 * v).tolist()), start=2
    ):
        scene.deform(oid, given)
        now = scene.shape(oid)
        assert now.version == version
        np.testing.assert_allclose(now.arrays()[0], 1.1 * v, rtol=1e-6)
        np.testing.assert_array_equal(now.arrays()[1], f)
        np.testing.assert_allclose(now.bounds, np.multiply(shape.bounds, 1.1), rtol=1e-6)
        # Between the two spheres: outside the rest shape, inside the grown one.
        between = np.array([[1.05 * RADIUS, 0, 0], [0, -1.05 * RADIUS, 0], [0, 0, 1.05 * RADIUS]])
        assert not shape.inside(between).any() and now.inside(between).all()

    # A subset: only the vertices named move (a strided view of the indices).
    picked = np.arange(0, len(v), 7)[::-1][::2]
    scene.deform(oid, v[picked] * 0.9, indices=picked)
    now = scene.shape(oid).arrays()[0]
    moved = np.zeros(len(v), bool)
    moved[picked] = True
    np.testing.assert_allclose(now[moved], 0.9 * v[moved], rtol=1e-15)
    np.testing.assert_allclose(now[~moved], 1.1 * v[~moved], rtol=1e-6)
    scene.deform(oid, np.empty((0, 3)), indices=[])  # nothing moves
    assert scene.shape(oid).version == 6


def test_deforming_one_object_leaves_another_sharing_its_shape_unchanged():
    shape = sphere()
    rest = shape.arrays()[0]
    scene = haphe.Scene()
    a = scene.add(shape)
    b = scene.add(shape, position=(0.2, 0, 0))
    scene.deform(a, 0.5 * rest)
    assert scene.shape(a).version == 1 and scene.shape(b).version == 0
    np.testing.assert_allclose(scene.shape(a).arrays()[0], 0.5 * rest)
    np.testing.assert_array_equal(scene.shape(b).arrays()[0], rest)
    np.testing.assert_array_equal(shape.arrays()[0], rest)
    assert shape.version == 0
    # The proxy feels each as it is now: b at its full radius, a at half of it.
    for oid, x, radius in ((b, 0.2, RADIUS), (a, 0.0, 0.5 * RADIUS)):
        proxy = haphe.Proxy(position=(x, 0, 2 * RADIUS))
        for _ in range(3):
            force, position, contact = proxy.tick(scene, (x, 0, radius - 0.002))
        assert contact is not None and contact.object == oid
        assert abs(position[2] - radius) < 1e-4, (oid, position)


def test_deform_releases_the_gil():
    """A second thread runs while the first is inside `Scene.deform` (the argument of
    `test_batch_calls_release_the_gil`: with the switch interval beyond the test, the main
    thread runs only when the worker releases the GIL)."""
    shape = haphe.Shape.from_file(ROOT / "meshes" / "models" / "spot.obj")
    rest = shape.arrays()[0]
    scene = haphe.Scene()
    oid = scene.add(shape)
    started, done = threading.Event(), threading.Event()

    def worker():
        started.set()
        scene.deform(oid, 1.01 * rest)
        done.set()

    interval = sys.getswitchinterval()
    sys.setswitchinterval(1000.0)
    thread = threading.Thread(target=worker)
    try:
        thread.start()
        started.wait()
        overlapped = not done.is_set()
        shape.inside(rest[:100])  # the main thread's own call, during the worker's
    finally:
        sys.setswitchinterval(interval)
        thread.join()
    assert overlapped, "Scene.deform held the GIL: the other thread could not run meanwhile"
    assert done.is_set() and scene.shape(oid).version == 1
