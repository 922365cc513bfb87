"""A model in the wrong unit: Shape.from_file and validate warn (UserWarning) with the
argument to add, by the library's rule (more than 2 m or less than 5 mm across), the same
rule and figures as the command's `--units` warning."""

import subprocess
import warnings

import pytest

import haphe

from conftest import ROOT

CUBE_MM = ROOT / "meshes" / "models" / "20mm-xyz-cube.stl"


def cube_obj(path, side):
    """A closed cube of `side` file units, triangles counter-clockwise seen from outside."""
    corners = [(x, y, z) for z in (0, side) for y in (0, side) for x in (0, side)]
    quads = [(1, 3, 4, 2), (5, 6, 8, 7), (1, 2, 6, 5), (3, 7, 8, 4), (1, 5, 7, 3), (2, 4, 8, 6)]
    lines = [f"v {x} {y} {z}" for x, y, z in corners]
    for a, b, c, d in quads:
        lines += [f"f {a} {b} {c}", f"f {a} {c} {d}"]
    path.write_text("\n".join(lines) + "\n")
    return path


@pytest.mark.parametrize("call", [haphe.Shape.from_file, haphe.validate])
def test_a_millimetre_cube_read_as_metres_warns_with_the_argument_to_add(call, tmp_path):
    cube = cube_obj(tmp_path / "cube_mm.obj", 100)
    with pytest.warns(UserWarning, match=r'looks like millimetres: add `units="mm"`') as caught:
        call(cube)
    assert "spans 100 m" in str(caught[0].message)
    # Read in millimetres it is a 0.1 m cube: no warning.
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        call(cube, units="mm")


def test_the_warning_is_the_commands(haphe_cli):
    with pytest.warns(UserWarning) as caught:
        haphe.validate(CUBE_MM)
    python = str(caught[0].message)
    command = subprocess.run(
        [haphe_cli, "validate", str(CUBE_MM)], capture_output=True, text=True
    ).stderr
    # The same sentence, but for how the unit is given.
    said = python.split(": ", 1)[1].replace('`units="mm"`', "`--units mm`")
    assert said in command, (python, command)
