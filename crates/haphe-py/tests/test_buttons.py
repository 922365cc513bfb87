"""Buttons and the clutch through haphe.run: the simulated hand holds button 1 on its
way down to a cube; the arrays record it, and with clutch_button=1 the tool stays while
it is held, the returned offset is minus the hand's travel, and the tool continues from
where it stayed."""

import numpy as np
import pytest

import haphe
from test_devices import centred_cube

SECONDS = 3.0


def run(**kwargs):
    return haphe.run(centred_cube(), device="hand", path="press", seconds=SECONDS,
                     clutch_button=1, **kwargs)


def test_the_clutch_keeps_the_tool_and_the_offset_moves_by_the_hands_travel():
    free = run()
    assert free["buttons"].dtype == np.uint32
    assert not free["buttons"].any() and not free["clutch"].any()
    np.testing.assert_array_equal(free["offset"], [0.0, 0.0, 0.0])
    first_force = int(np.argmax(np.linalg.norm(free["force"], axis=1) > 0))
    assert first_force > 100, "the hand starts away from the cube"
    # Held over the middle half of the approach, where no force acts in either run, so
    # the hand moves as in the free run until the release.
    start, end = first_force // 4, 3 * first_force // 4
    held = run(presses=[(1, start / 1000.0, end / 1000.0)])
    expected = np.zeros(len(free["t"]), dtype=bool)
    expected[start:end] = True
    np.testing.assert_array_equal(held["clutch"], expected)
    np.testing.assert_array_equal(held["buttons"], np.where(expected, 2, 0))
    before = free["hip"][start - 1]
    travel = free["hip"][end - 1] - before
    assert np.linalg.norm(travel) > 5e-3, "the hand travels while the clutch is held"
    np.testing.assert_allclose(held["hip"][start:end], np.tile(before, (end - start, 1)),
                               rtol=0, atol=1e-12)
    np.testing.assert_allclose(held["hip"][:start], free["hip"][:start], rtol=0, atol=0)
    np.testing.assert_allclose(held["hip"][end], free["hip"][end] - travel, rtol=0,
                               atol=1e-12)
    np.testing.assert_allclose(held["offset"], -travel, rtol=0, atol=1e-12)


@pytest.mark.parametrize("kwargs, word", [
    ({"clutch_button": 32}, "clutch_button"),
    ({"presses": [(0, 2.0, 1.0)]}, "presses"),
    ({"presses": [(0, 1.0, 2.0)], "device": "dhd"}, "presses"),
])
def test_bad_buttons_are_refused_naming_the_argument(kwargs, word):
    args = {"device": "hand", "seconds": 0.1, **kwargs}
    with pytest.raises(haphe.HapheError, match=word):
        haphe.run(centred_cube(), **args)
