"""Bad input raises a Python exception whose message names the file and the place."""

import numpy as np
import pytest

import haphe


def test_bad_mesh_names_file_and_line(tmp_path):
    bad = tmp_path / "bad.obj"
    bad.write_text("v 0 0 0\nf 1 2 9\n")
    with pytest.raises(haphe.HapheError) as e:
        haphe.Shape.from_file(bad)
    assert str(bad) in str(e.value) and "line 2" in str(e.value)
    with pytest.raises(haphe.HapheError) as e:
        haphe.validate(bad)
    assert str(bad) in str(e.value)


def test_missing_file_is_an_os_error(tmp_path):
    missing = tmp_path / "missing.stl"
    with pytest.raises(FileNotFoundError) as e:
        haphe.Shape.from_file(missing)
    assert str(missing) in str(e.value)


def test_foreign_map_file_names_the_file(tmp_path):
    fake = tmp_path / "fake.hmap"
    fake.write_bytes(b"HAPHEMAP" + b"\0" * 40)
    with pytest.raises(haphe.HapheError) as e:
        haphe.Shape.load(fake)
    assert str(fake) in str(e.value)


def test_degenerate_mesh_names_the_file(tmp_path):
    flat = tmp_path / "flat.obj"
    flat.write_text("v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n")
    with pytest.raises(haphe.HapheError) as e:
        haphe.Shape.from_file(flat)
    assert str(flat) in str(e.value)


def test_bad_arrays():
    v = np.zeros((3, 3))
    with pytest.raises(haphe.HapheError, match="face 0: vertex index 7"):
        haphe.Shape.from_arrays(v, np.array([[0, 1, 7]]))
    with pytest.raises(haphe.HapheError, match="vertex 1"):
        haphe.Shape.from_arrays(np.array([[0, 0, 0], [np.nan, 0, 0], [0, 1, 0]]),
                                np.array([[0, 1, 2]]))
    with pytest.raises(haphe.HapheError, match=r"shape \(N, 3\)"):
        haphe.Shape.from_arrays(np.zeros((3, 2)), np.array([[0, 1, 2]]))


def test_bad_query_arrays():
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
    shape = haphe.Shape.from_arrays(v, np.array([[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]]))
    with pytest.raises(haphe.HapheError, match="points"):
        shape.inside(np.zeros((4, 2)))
    with pytest.raises(haphe.HapheError, match="rows"):
        shape.first_crossing(np.zeros((4, 3)), np.zeros((5, 3)))
    with pytest.raises(haphe.HapheError, match="max_distance"):
        shape.nearest(np.zeros((1, 3)), -1.0)
    with pytest.raises(haphe.HapheError, match="units"):
        haphe.Shape.from_file("x.obj", units="furlongs")
