"""The scene, the proxy and the servo loop from Python."""

import numpy as np
import pytest

import haphe
from test_queries import CUBE_FACES, cube


def test_pressing_on_a_cube_pushes_back():
    scene = haphe.Scene()
    oid = scene.add(cube(), position=(0, 0, -1), stiffness=1000.0)
    proxy = haphe.Proxy(position=(0.5, 0.5, 0.1))
    force, position, contact = proxy.tick(scene, (0.5, 0.5, 0.05))
    assert contact is None and force == (0.0, 0.0, 0.0)
    force, position, contact = proxy.tick(scene, np.array([0.5, 0.5, -0.001]))
    assert contact is not None and contact.object == oid
    assert contact.triangle in (10, 11)
    assert position[2] >= 0.0 and abs(position[2]) < 1e-5
    np.testing.assert_allclose(force, (0, 0, 1000.0 * 0.001), rtol=1e-2)


def test_rotation_and_friction_are_accepted():
    scene = haphe.Scene(capacity=2)
    scene.add(cube(), rotation=(0, 0, np.sin(0.3), np.cos(0.3)), friction=0.5)
    scene.add(cube(), position=(3, 0, 0), rotation=np.eye(3))
    with pytest.raises(haphe.HapheError, match="capacity|full"):
        scene.add(cube())
    with pytest.raises(haphe.HapheError, match="rotation"):
        haphe.Scene().add(cube(), rotation=[[1, 0, 0], [0, 1, 0], [0, 0, 2]])
    assert len(scene) == 2


@pytest.mark.parametrize("texture, effects", [
    (None, []),
    ("sine:0.0002:0.002", ["viscosity:2", "vibration:150:0.3"]),
])
def test_tick_loop_allocates_nothing(texture, effects):
    count = haphe.allocations()
    if count is None:
        pytest.fail("built without the count-allocations feature")
    scene = haphe.Scene()
    scene.add(cube(), position=(0, 0, -1), stiffness=800.0, friction=0.3, texture=texture)
    for e in effects:
        scene.add_effect(e)
    proxy = haphe.Proxy(position=(0.5, 0.5, 0.1))
    proxy.tick(scene, (0.5, 0.5, 0.1))  # the first tick may prepare what it needs
    t = np.linspace(0, 20 * np.pi, 100_000)
    hips = np.stack([0.5 + 0.3 * np.cos(t), 0.5 + 0.3 * np.sin(t), -0.002 + 0.004 * np.sin(7 * t)], 1)
    hips = [tuple(h) for h in hips]
    before = haphe.allocations()
    touched = 0
    for hip in hips:
        force, position, contact = proxy.tick(scene, hip)
        touched += contact is not None
    after = haphe.allocations()
    assert touched > 10_000
    assert after - before == 0, f"{after - before} allocations in 100000 ticks"


def test_the_servo_ticks_allocate_nothing_with_a_texture_and_effects():
    """A run allocates what it sets up and its arrays, whatever its length: a run twice as
    long (1000 ticks more, the hand sliding on the textured face with the effects on)
    allocates exactly as much."""
    if haphe.allocations() is None:
        pytest.fail("built without the count-allocations feature")
    scene = haphe.Scene()
    scene.add(cube(), position=(-0.5, -0.5, -1.0), texture="sine:0.0002:0.002")
    for e in ("viscosity:2", "vibration:150:0.3", "stick-slip", "magnet:0.01:0.5"):
        scene.add_effect(e)
    counts = {}
    for seconds in (1.0, 2.0, 1.0, 2.0):
        before = haphe.allocations()
        out = haphe.run(scene, device="hand", seconds=seconds, path="slide")
        counts.setdefault(seconds, set()).add(haphe.allocations() - before)
        assert out["contact"].sum() > 100 * seconds  # guard: the hand slides on the face
    assert counts[1.0] == counts[2.0] and len(counts[1.0]) == 1, counts


def test_run_with_the_simulated_hand():
    scene = haphe.Scene()
    scene.add(cube(), position=(-0.5, -0.5, -1.0), stiffness=600.0)
    out = haphe.run(scene, device="hand", seconds=1.0, path="press")
    assert out["t"].shape == (1000,) and out["force"].shape == (1000, 3)
    assert out["contact"].sum() > 100
    assert np.isfinite(out["force"]).all()
    assert (np.linalg.norm(out["force"], axis=1) <= 3.3 + 1e-9).all()
    assert out["force"][out["contact"], 2].max() > 0.1
    assert out["device"] == "the simulated hand (press)" and out["stop"] == "finished"
    with pytest.raises(haphe.HapheError, match="unknown device"):
        haphe.run(scene, device="phantom", seconds=0.1)


def test_a_tool_rests_its_radius_above_the_surface():
    r = 0.05
    scene = haphe.Scene()
    scene.add(cube(), position=(0, 0, -1), stiffness=1000.0)  # the top face at z = 0
    tool = haphe.Proxy(position=(0.5, 0.5, 0.2), tool_radius=r)
    point = haphe.Proxy(position=(0.5, 0.5, 0.2))
    assert tool.tool_radius == r and point.tool_radius == 0.0
    # The device point 1 mm closer to the face than the radius: the point is free, the
    # tool touches; its centre stays r above the face and the spring pulls the device out.
    hip = (0.5, 0.5, r - 0.001)
    assert point.tick(scene, hip)[2] is None
    force, position, contact = tool.tick(scene, hip)
    assert contact is not None and contact.triangle in (10, 11)
    assert abs(position[2] - r) < 1e-5, position
    np.testing.assert_allclose(contact.point, (0.5, 0.5, 0.0), atol=1e-9)
    np.testing.assert_allclose(contact.normal, (0, 0, 1), atol=1e-12)
    np.testing.assert_allclose(force, (0, 0, 1000.0 * 0.001), rtol=1e-2)


def test_a_tool_larger_than_the_scene_is_refused():
    scene = haphe.Scene()
    corners = [[x, y, z] for z in (0, 1) for (x, y) in ((0, 0), (1, 0), (1, 1), (0, 1))]
    small = haphe.Shape.from_arrays(0.1 * np.array(corners, dtype=float), CUBE_FACES)
    scene.add(small)
    diagonal = 0.1 * 3 ** 0.5
    assert scene.check_tool_radius(0.99 * diagonal) == 0.99 * diagonal
    with pytest.raises(haphe.HapheError) as e:
        scene.check_tool_radius(1.01 * diagonal)
    message = str(e.value)
    assert message.startswith("tool_radius must be at most 0.1732 m, the diagonal"), message
    assert isinstance(e.value, ValueError)


def test_run_with_a_tool_keeps_its_centre_its_radius_above_the_face():
    r = 0.01
    outs = {}
    for radius in (0.0, r):
        scene = haphe.Scene()
        scene.add(cube(), position=(-0.5, -0.5, -1.0), stiffness=600.0)  # the top at z = 0
        outs[radius] = haphe.run(scene, device="hand", seconds=1.0, path="press",
                                 tool_radius=radius)
    for radius, out in outs.items():
        touching = out["proxy"][out["contact"], 2]
        assert touching.size > 100
        # Resting on the face: the centre r above it (less the skin), never closer.
        assert touching.min() > radius - 2e-6, (radius, touching.min())
        np.testing.assert_allclose(np.median(touching), radius, atol=1e-5)
    # A radius larger than the scene is refused naming it.
    scene = haphe.Scene()
    corners = [[x, y, z] for z in (0, 1) for (x, y) in ((0, 0), (1, 0), (1, 1), (0, 1))]
    scene.add(haphe.Shape.from_arrays(0.01 * np.array(corners, dtype=float), CUBE_FACES))
    with pytest.raises(haphe.HapheError, match="^tool_radius must be at most 0.01732 m"):
        haphe.run(scene, device="hand", seconds=0.1, path="press", tool_radius=0.02)
