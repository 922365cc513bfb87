"""One default for the device's maximum force and one default material, whatever the entry
point: Python, the C API and the command agree with each other and with the library's
(`haphe::scene::DEFAULT_MAX_FORCE_N`, `Material::DEFAULT`, whose Python face is
`haphe.DEFAULT_MAX_FORCE`)."""

import ctypes
import re
import subprocess

import numpy as np

import haphe
from conftest import ROOT
from test_queries import cube


def c_library():
    """The C API's shared library (built when missing)."""
    path = ROOT / "target" / "debug" / "libhaphe.so"
    if not path.exists():
        subprocess.run(["cargo", "build", "-p", "haphe-c", "--locked"], cwd=ROOT, check=True)
    lib = ctypes.CDLL(str(path))
    lib.haphe_default_max_force.restype = ctypes.c_double
    lib.haphe_default_max_force.argtypes = []
    return lib


def pressed(depth, slide=0.0):
    """The force of a default proxy on a default cube after the hand went `depth` metres
    into its top face (straight down, from above), then `slide` metres along x."""
    scene = haphe.Scene()
    scene.add(cube(), position=(0, 0, -1))
    proxy = haphe.Proxy(position=(0.5, 0.5, 0.1))
    proxy.tick(scene, (0.5, 0.5, 0.05))
    force, _, contact = proxy.tick(scene, (0.5, 0.5, -depth))
    if slide:
        force, _, contact = proxy.tick(scene, (0.5 + slide, 0.5, -depth))
    assert contact is not None
    return np.asarray(force)


def cli_default(haphe_cli, command, flag):
    """The `[default: X]` of `--flag` in `haphe COMMAND --help`."""
    text = subprocess.run(
        [haphe_cli, command, "--help"], capture_output=True, text=True, check=True
    ).stdout
    match = re.search(r"--" + flag + r" <[^>]*>.*?\[default: ([^\]]+)\]", text, re.S)
    assert match, text
    return float(match.group(1))


def test_the_maximum_force_is_one_number_everywhere(haphe_cli):
    # Python: the constant, and what a default proxy renders pushed far past it.
    assert haphe.DEFAULT_MAX_FORCE > 0
    np.testing.assert_allclose(np.linalg.norm(pressed(0.5)), haphe.DEFAULT_MAX_FORCE, rtol=1e-12)
    # C: the API's default.
    assert c_library().haphe_default_max_force() == haphe.DEFAULT_MAX_FORCE
    # The command: its flags, and what a run says the device's maximum is.
    for command in ("simulate", "run"):
        assert cli_default(haphe_cli, command, "max-force") == haphe.DEFAULT_MAX_FORCE
    run = subprocess.run(
        [haphe_cli, "simulate", "--shape", "box", "--triangles", "2000", "--path", "press",
         "--seconds", "0.5"],
        capture_output=True, text=True, check=True,
    ).stdout
    maximum = re.search(r"device maximum ([0-9.]+) N", run)
    assert maximum and float(maximum.group(1)) == haphe.DEFAULT_MAX_FORCE, run


def test_the_default_material_is_the_commands(haphe_cli):
    # A default object pressed 1 mm: the spring of the default stiffness (the proxy is
    # given no velocity, so no damping), so the stiffness is force / depth.
    depth = 1e-3
    stiffness = np.linalg.norm(pressed(depth)) / depth
    np.testing.assert_allclose(stiffness, cli_default(haphe_cli, "simulate", "stiffness"), rtol=1e-2)
    # Slid 1 mm sideways at that depth: a tangential force only with static friction.
    force = pressed(depth, slide=1e-3)
    sticks = abs(force[0]) > 1e-9
    assert sticks == (cli_default(haphe_cli, "simulate", "static-friction") > 0), force
