"""Textures and force effects from Python: specifications refused naming the keyword and
the specification, and what a run renders with them."""

import numpy as np
import pytest

import haphe
from test_params import assert_refused
from test_queries import cube

NAN, INF = float("nan"), float("inf")

# The top face of a unit cube placed at (-0.5, -0.5, -1) lies at z = 0.
CUBE_AT = (-0.5, -0.5, -1.0)
TEXTURE = "sine:0.0002:0.002"


def add_texture(spec):
    haphe.Scene().add(cube(), texture=spec)


def set_texture(spec):
    scene = haphe.Scene()
    oid = scene.add(cube(), texture=TEXTURE)
    try:
        scene.set_texture(oid, spec)
    except haphe.HapheError:
        assert scene.textures == {oid: TEXTURE}, "refused, the texture stays"
        raise
    assert scene.textures == {oid: spec}


def add_effect(spec):
    haphe.Scene().add_effect(spec)


def run_effect(spec, rate_hz=1000.0):
    scene = haphe.Scene()
    scene.add(cube(), position=CUBE_AT)
    scene.add_effect(spec)
    haphe.run(scene, device="hand", seconds=0.01, path="press", rate_hz=rate_hz)


# (keyword, how to give it, the specification with the value in {}, the parameter the
# library names, typical value, 0 allowed, -1 allowed, absurd value), stated from the
# physics: a texture of no height is none, a wavelength of nothing is no texture; an
# effect may be switched off by a zero viscosity, stiffness or force, and a constant force
# points any way.
CASES = [
    ("texture", add_texture, "sine:{}:0.002", "texture amplitude", 2e-4, True, False, 1.0),
    ("texture", set_texture, "noise:0.0001:{}", "texture wavelength", 2e-3, False, False, 100.0),
    ("effect", add_effect, "vibration:{}:0.3", "vibration frequency", 150.0, False, False, 1e6),
    ("effect", add_effect, "viscosity:{}", "viscosity", 2.0, True, False, 1e5),
    ("effect", add_effect, "viscosity:{}:box:0:0:0:1:1:1", "viscosity", 2.0, True, False, 1e5),
    ("effect", add_effect, "spring:{}:0:0:0", "effect stiffness", 100.0, True, False, 1e7),
    ("effect", add_effect, "magnet:{}:1", "magnet distance", 0.01, False, False, 100.0),
    ("effect", add_effect, "constant:{}:0:0", "effect force", 0.3, True, True, 1e4),
    ("effect", add_effect, "stick-slip:{}:0.5", "effect stiffness", 1000.0, True, False, 1e7),
]


def outcomes():
    for keyword, call, template, param, typical, zero, negative, absurd in CASES:
        values = [(typical, True), (NAN, False), (INF, False), (-INF, False),
                  (-1.0, negative), (0.0, zero), (absurd, False), (-absurd, False)]
        for value, accepted in values:
            spec = template.format(repr(value))
            yield pytest.param(keyword, call, spec, param, value, accepted, id=spec)


@pytest.mark.parametrize("keyword, call, spec, param, value, accepted", list(outcomes()))
def test_every_value_of_a_specification_is_checked(keyword, call, spec, param, value, accepted):
    if accepted:
        call(spec)
        return
    assert_refused(lambda: call(spec), f"{keyword}: `{spec}`: {param} must be", value)


@pytest.mark.parametrize("keyword, call, spec, says", [
    ("texture", add_texture, "bumps:1:2", "unknown kind `bumps` (expected one of `sine:A:L`"),
    ("texture", set_texture, "sine:0.001", "expected `KIND:AMPLITUDE:WAVELENGTH`"),
    ("texture", add_texture, "sine:x:0.002", "`x` is not a number"),
    ("texture", add_texture, "sine:0.001:0.001", "texture amplitude must be at most the wavelength / 2π"),
    ("effect", add_effect, "wobble:1", "unknown kind `wobble` (expected one of `vibration`"),
    ("effect", add_effect, "viscosity", "expected `viscosity:B`"),
    ("effect", add_effect, "viscosity:2:inside:x", "expected `viscosity:B`"),
    ("effect", add_effect, "viscosity:2:box:1:0:0:0:1:1", "position must be"),
    ("effect", add_effect, "spring:10:0:0", "expected `spring:K:X:Y:Z`"),
    ("effect", add_effect, "", "unknown kind ``"),
])
def test_a_malformed_specification_is_refused_naming_it(keyword, call, spec, says):
    with pytest.raises(haphe.HapheError) as e:
        call(spec)
    message = str(e.value)
    assert message.startswith(f"{keyword}: `{spec}`: "), message
    assert says in message, message


def test_a_vibration_above_half_the_rate_is_refused_where_the_run_is_made():
    # 600 Hz is a valid vibration, renderable from 1200 Hz up.
    with pytest.raises(haphe.HapheError) as e:
        run_effect("vibration:600:0.3", rate_hz=1000.0)
    assert str(e.value) == (
        "effect: `vibration:600:0.3`: vibration frequency must be at most half the servo "
        "rate (500 Hz at 1000 Hz), not 600"
    )
    run_effect("vibration:600:0.3", rate_hz=1200.0)


def test_a_scene_holds_at_most_sixteen_effects():
    scene = haphe.Scene()
    specs = [f"constant:0:0:{k / 100}" for k in range(16)]
    for s in specs:
        scene.add_effect(s)
    with pytest.raises(haphe.HapheError, match=r"^effect: `viscosity:1`: the scene holds 16"):
        scene.add_effect("viscosity:1")
    assert scene.effects == specs


def test_effects_and_textures_are_listed_and_cleared():
    scene = haphe.Scene()
    plain = scene.add(cube())
    rough = scene.add(cube(), position=(2, 0, 0), texture="noise:0.0001:0.001")
    blank = scene.add(cube(), position=(4, 0, 0), texture="")
    assert scene.textures == {rough: "noise:0.0001:0.001"}
    scene.set_texture(plain, TEXTURE)
    scene.set_texture(rough, None)
    scene.set_texture(blank, "")
    assert scene.textures == {plain: TEXTURE}
    with pytest.raises(KeyError):
        scene.set_texture(99, TEXTURE)
    scene.remove(plain)
    assert scene.textures == {}

    assert scene.effects == []
    scene.add_effect("viscosity:2")
    scene.add_effect("vibration:150:0.3")
    assert scene.effects == ["viscosity:2", "vibration:150:0.3"]
    scene.clear_effects()
    assert scene.effects == []
    # Cleared, the effects no longer reach a run: a vibration too fast for it is gone.
    scene.add_effect("vibration:600:0.3")
    scene.clear_effects()
    haphe.run(scene, device="hand", seconds=0.01, path="press", rate_hz=1000.0)


def test_viscosity_drags_against_the_velocity_in_free_space():
    scene = haphe.Scene()
    scene.add(cube(), position=CUBE_AT, stiffness=600.0)
    plain = haphe.run(scene, device="hand", seconds=1.0, path="press")
    scene.add_effect("viscosity:2")
    out = haphe.run(scene, device="hand", seconds=1.0, path="press")
    # After the 50 ms ramp of the safe start, away from the cube.
    free = (out["t"] >= 0.05) & ~out["contact"]
    plain_free = (plain["t"] >= 0.05) & ~plain["contact"]
    # Guards: enough free ticks, the hand moving there (so the drag is not zero), and
    # without the effect no force in free space at all.
    assert free.sum() > 200, free.sum()
    assert np.abs(out["velocity"][free]).max() > 0.01
    assert np.abs(plain["force"][plain_free]).max() == 0.0
    # −2·v, clamped to the device's maximum force where longer.
    drag = -2.0 * out["velocity"][free]
    length = np.linalg.norm(drag, axis=1, keepdims=True)
    expected = drag * np.minimum(1.0, haphe.DEFAULT_MAX_FORCE / np.maximum(length, 1e-300))
    assert (length < haphe.DEFAULT_MAX_FORCE).sum() > 200  # guard: mostly not clamped
    np.testing.assert_allclose(out["force"][free], expected, rtol=1e-12, atol=1e-15)


def slide(texture):
    """A run of the simulated hand sliding along x over the top face of the cube."""
    scene = haphe.Scene()
    scene.add(cube(), position=CUBE_AT, stiffness=600.0, texture=texture)
    return haphe.run(scene, device="hand", seconds=2.0, path="slide")


def test_a_textured_surface_varies_the_force_where_the_plain_one_is_steady():
    plain, rough = slide(None), slide(TEXTURE)
    wavelength, amplitude = 2e-3, 2e-4
    for out in (plain, rough):
        # The sliding stretch of the path (keys from 0.2 to 0.8 of its time), in contact.
        sliding = (out["t"] > 0.5) & (out["t"] < 1.5) & out["contact"]
        travel = np.ptp(out["proxy"][sliding, 0])
        # Guard: the proxy crosses many wavelengths of the texture.
        assert sliding.sum() > 500 and travel > 10 * wavelength, (sliding.sum(), travel)
        out["sliding"] = sliding
    # The lateral force along the slide: none on the plain frictionless face.
    fx_plain = plain["force"][plain["sliding"], 0]
    fx_rough = rough["force"][rough["sliding"], 0]
    assert np.abs(fx_plain).max() < 1e-9, np.abs(fx_plain).max()
    # On the texture the slope of the bumps pushes the hand downhill: the force along x
    # follows −∂h/∂x ∝ −cos(2πx/L) at the proxy (the cube's frame is the world's moved by
    # CUBE_AT, a whole number of wavelengths along x).
    assert np.abs(fx_rough).max() > 1000 * max(np.abs(fx_plain).max(), 1e-12)
    x = rough["proxy"][rough["sliding"], 0] - CUBE_AT[0]
    slope = -np.cos(2 * np.pi * x / wavelength)
    correlation = np.corrcoef(fx_rough, slope)[0, 1]
    assert correlation > 0.9, correlation
    # Its size: the spring's force on the felt depth times the slope, at most
    # k · (depth + A) · A·2π/(3L) (the module's rule), with the depth the records give.
    depth = rough["penetration"][rough["sliding"]]
    bound = 600.0 * (depth.max() + amplitude) * amplitude * 2 * np.pi / (3 * wavelength)
    assert np.abs(fx_rough).max() <= bound * (1 + 1e-6), (np.abs(fx_rough).max(), bound)
