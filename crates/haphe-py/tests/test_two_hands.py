"""haphe.run with several devices in one scene: a list of devices returns a list of dicts,
one per device. Two simulated hands each render what they render alone; two Force
Dimension devices behind the stand-in (built from the C source the Rust tests use) each
press out of the cube with their own proxy; a fault of one stops both with zero force and
names it; a device given twice, an index that does not exist and a mapping missing for
one device are refused."""

import numpy as np
import pytest

import haphe
from test_devices import (assert_pressed_out_of_the_cube, centred_cube, last_force,
                          press_file, standin)  # noqa: F401 (a fixture)

ARRAYS = ("t", "hip", "proxy", "force", "contact", "object", "triangle", "penetration",
          "buttons", "clutch")


def test_two_hands_each_render_as_alone():
    scene = centred_cube()
    # The first hand holds a tool of 2 cm radius, the second is a point.
    tools = [0.02, 0.0]
    both = haphe.run(scene, device=["hand", "hand"], seconds=2.0, seed=3, tool_radius=tools)
    assert isinstance(both, list) and len(both) == 2
    for k, out in enumerate(both):
        alone = haphe.run(scene, device="hand", seconds=2.0, seed=3 + k, tool_radius=tools[k])
        for name in ARRAYS:
            np.testing.assert_array_equal(out[name], alone[name], err_msg=f"hand {k}: {name}")
        # Guard, counted on the hand alone: its path touches the cube.
        assert alone["contact"].sum() > 100
    # Each hand's force is its own, not the first hand's.
    differ = np.linalg.norm(both[0]["force"] - both[1]["force"], axis=1) > 1e-6
    assert differ.sum() > 100
    # A list of one is a list of one dict.
    one = haphe.run(scene, device=["hand:4"], seconds=0.5)
    assert isinstance(one, list) and len(one) == 1
    np.testing.assert_array_equal(one[0]["hip"], both[1]["hip"][: len(one[0]["hip"])])


def two_dhd(standin, tmp_path, monkeypatch, fail_from=None):
    """Two Force Dimension devices pressing into the cube from above, side by side."""
    monkeypatch.setenv("HAPHE_DHD_LIBRARY", str(standin("dhd.c")))
    monkeypatch.setenv("HAPHE_STANDIN_DEVICES", "2")
    reports = []
    for i, x in enumerate((-0.02, 0.02)):
        suffix = "" if i == 0 else f"_{i}"
        path = press_file(tmp_path / f"press{i}.txt", (x, 0.0, 0.06), (x, 0.0, 0.0))
        monkeypatch.setenv("HAPHE_STANDIN_PATH" + suffix, str(path))
        reports.append(tmp_path / f"forces{i}.txt")
        monkeypatch.setenv("HAPHE_STANDIN_FORCES" + suffix, str(reports[-1]))
    if fail_from is not None:
        monkeypatch.setenv("HAPHE_STANDIN_FAIL_FROM_1", str(fail_from))
    return reports


def test_two_force_dimension_devices(standin, tmp_path, monkeypatch):
    reports = two_dhd(standin, tmp_path, monkeypatch)
    outs = haphe.run(centred_cube(), device=["dhd:0", "dhd:1"], seconds=2.0)
    assert [("omega.3" in o["device"], "sigma.7" in o["device"]) for o in outs] == [
        (True, False), (False, True)]
    for out, report in zip(outs, reports):
        assert out["stop"] == "finished", out["stop"]
        assert_pressed_out_of_the_cube(out)
        count, last, enabled, largest = last_force(report)
        assert count >= len(out["t"])
        assert last == (0.0, 0.0, 0.0) and not enabled and largest > 1.0
    # Both devices every tick: the same ticks.
    np.testing.assert_array_equal(outs[0]["t"], outs[1]["t"])
    # Each one's own mapping: the default puts both workspaces over the cube.
    assert outs[0]["hip"][-1][0] < 0 < outs[1]["hip"][-1][0]


def test_a_fault_of_one_device_zeroes_both_and_names_it(standin, tmp_path, monkeypatch):
    reports = two_dhd(standin, tmp_path, monkeypatch, fail_from=1200)
    outs = haphe.run(centred_cube(), device=["dhd:0", "dhd:1"], seconds=2.0)
    for out, report in zip(outs, reports):
        assert out["stop"].startswith("fault: device 2 (dhd:1): device error code 5"), out["stop"]
        count, last, enabled, largest = last_force(report)
        assert last == (0.0, 0.0, 0.0) and not enabled
        # Pressing before the fault: a force to zero.
        assert largest > 1.0
        assert np.linalg.norm(out["force"][-1]) == 0.0
    assert "communication error" in (outs[1]["report"] or ""), outs[1]["report"]


def test_bad_sets_of_devices_are_refused(standin, monkeypatch):
    monkeypatch.setenv("HAPHE_DHD_LIBRARY", str(standin("dhd.c")))
    monkeypatch.setenv("HAPHE_STANDIN_DEVICES", "2")
    scene = centred_cube()
    with pytest.raises(haphe.HapheError, match=r"device 2 \(dhd:0\) is device 1 \(dhd:0\) again"):
        haphe.run(scene, device=["dhd:0", "dhd:0"], seconds=0.1)
    with pytest.raises(haphe.DeviceError, match="no Force Dimension device at index 5"):
        haphe.run(scene, device=["dhd:0", "dhd:5"], seconds=0.1)
    with pytest.raises(haphe.HapheError, match="scale: give one value per device"):
        haphe.run(scene, device=["dhd:0", "dhd:1"], seconds=0.1, scale=[2.0])
    with pytest.raises(haphe.HapheError, match="centre: give one value per device"):
        haphe.run(scene, device=["hand", "hand"], seconds=0.1, centre=(0.0, 0.0, 0.0))
    with pytest.raises(haphe.HapheError, match="tool_radius: give one value per device"):
        haphe.run(scene, device=["hand", "hand"], seconds=0.1, tool_radius=[0.01])
