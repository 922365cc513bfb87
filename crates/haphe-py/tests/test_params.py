"""Every parameter given from Python goes through the library's table of domains: NaN,
±inf, a negative value, zero and an absurd value are each refused with a HapheError (a
ValueError) naming the keyword, or accepted where the domain allows it."""

import math

import pytest

import haphe
from test_queries import cube

NAN, INF = float("nan"), float("inf")


def scene_add(**kw):
    haphe.Scene().add(cube(), **kw)


def scene_move(position):
    scene = haphe.Scene()
    oid = scene.add(cube())
    scene.move(oid, position)


def proxy_reset(position):
    haphe.Proxy().reset(position)


def run(**kw):
    scene = haphe.Scene()
    scene.add(cube(), position=(-0.5, -0.5, -1.0))
    haphe.run(scene, device="hand", seconds=0.01, path="press", **kw)


def vec(v):
    return (v, 0.0, 0.0)


# (keyword, how to give it a value, typical value, 0 allowed, −1 allowed, absurd value),
# stated from the physics rather than read from the library: a material without stiffness
# or a proxy without force renders nothing; a position may be anywhere nearby; a rotation
# is a quaternion of any non-zero length.
CASES = [
    ("stiffness", lambda v: scene_add(stiffness=v), 800.0, False, False, 1e7),
    ("damping", lambda v: scene_add(damping=v), 1.0, True, False, 1e5),
    ("friction", lambda v: scene_add(friction=v), 0.5, True, False, 100.0),
    ("dynamic_friction", lambda v: scene_add(friction=10.0, dynamic_friction=v), 0.3, True, False, 100.0),
    ("position", lambda v: scene_add(position=vec(v)), 0.2, True, True, 1e12),
    ("rotation", lambda v: scene_add(rotation=(v, 0.0, 0.0, 0.0)), 1.0, False, True, None),
    ("position", lambda v: scene_move(vec(v)), 0.2, True, True, 1e12),
    ("max_force", lambda v: haphe.Proxy(max_force=v), 3.3, False, False, 1e4),
    ("skin", lambda v: haphe.Proxy(skin=v), 1e-6, False, False, 1.0),
    ("workspace_radius", lambda v: haphe.Proxy(workspace_radius=v), 1.0, False, False, 1e12),
    # A tool of no size is the point; a tool of metres is a unit mixed up.
    ("tool_radius", lambda v: haphe.Proxy(tool_radius=v), 0.002, True, False, 10.0),
    ("tool_radius", lambda v: haphe.Scene().check_tool_radius(v), 0.002, True, False, 10.0),
    ("tool_radius", lambda v: run(tool_radius=v), 0.002, True, False, 10.0),
    ("position", lambda v: haphe.Proxy(position=vec(v)), 0.2, True, True, 1e12),
    ("position", lambda v: proxy_reset(vec(v)), 0.2, True, True, 1e12),
    ("rate_hz", lambda v: run(rate_hz=v), 1000.0, False, False, 1e6),
    ("scale", lambda v: run(scale=v), 2.0, False, False, 1e9),
    ("centre", lambda v: run(centre=vec(v)), 0.1, True, True, 1e12),
]


def outcomes():
    for name, call, typical, zero, negative, absurd in CASES:
        values = [(typical, True), (NAN, False), (INF, False), (-INF, False),
                  (-1.0, negative), (0.0, zero)]
        if absurd is not None:
            values += [(absurd, False), (-absurd, False)]
        for value, accepted in values:
            yield pytest.param(name, call, value, accepted, id=f"{name}={value}")


@pytest.mark.parametrize("name, call, value, accepted", list(outcomes()))
def test_every_parameter_is_checked_by_the_library(name, call, value, accepted):
    if accepted:
        call(value)
        return
    assert_refused(lambda: call(value), f"{name} must be", value)


def assert_refused(call, prefix, value):
    """call() raises a HapheError (a ValueError) whose message starts with `prefix` and
    ends naming `value`."""
    with pytest.raises(haphe.HapheError) as e:
        call()
    message = str(e.value)
    assert isinstance(e.value, ValueError)
    assert message.startswith(prefix), message
    # The value (or a vector's length) is named, NaN and infinities included.
    shown = message.rsplit("not ", 1)[1]
    if math.isnan(value):
        assert shown == "NaN", message
    else:
        assert abs(float(shown)) == abs(value), message


def test_a_refusal_says_the_domain_with_its_unit():
    with pytest.raises(haphe.HapheError) as e:
        haphe.Proxy(max_force=-1)
    assert str(e.value) == "max_force must be a finite number above 0 and at most 100 N, not -1"
    with pytest.raises(haphe.HapheError) as e:
        scene_add(friction=0.2, dynamic_friction=0.5)
    assert str(e.value) == "dynamic_friction must be at most static_friction (0.2), not 0.5"
