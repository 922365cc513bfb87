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


def cube_gltf(path, side):
    """A glTF file of one node holding a closed cube of `side` units (a data-URI buffer)."""
    import base64
    import json
    import struct

    corners = [(x, y, z) for z in (0, side) for y in (0, side) for x in (0, side)]
    quads = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    indices = [i for a, b, c, d in quads for i in (a, b, c, a, c, d)]
    positions = struct.pack(f"<{3 * len(corners)}f", *[v for p in corners for v in p])
    index_bytes = struct.pack(f"<{len(indices)}I", *indices)
    data = positions + index_bytes
    document = {
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0, "name": "cube"}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "buffers": [{
            "byteLength": len(data),
            "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode(),
        }],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": len(positions)},
            {"buffer": 0, "byteOffset": len(positions), "byteLength": len(index_bytes)},
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": len(corners), "type": "VEC3",
             "min": [0, 0, 0], "max": [side] * 3},
            {"bufferView": 1, "componentType": 5125, "count": len(indices), "type": "SCALAR"},
        ],
    }
    path.write_text(json.dumps(document))
    return path


def test_a_millimetre_gltf_scene_warns_too(tmp_path):
    cube = cube_gltf(tmp_path / "cube_mm.gltf", 100)
    with pytest.warns(UserWarning, match=r'looks like millimetres: add `units="mm"`'):
        scene = haphe.Scene.from_gltf(cube)
    assert len(scene) == 1
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        haphe.Scene.from_gltf(cube, units="mm")
