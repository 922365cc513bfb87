"""haphe.validate returns the record of `haphe validate --json`."""

import json
import subprocess

import pytest

import haphe


@pytest.mark.parametrize("name", ["fandisk.obj", "suzanne.obj", "bunny.ply"])
def test_validate_equals_cli(name, models, haphe_cli):
    path = models / name
    line = subprocess.run(
        [haphe_cli, "validate", "--json", str(path)], capture_output=True, text=True
    )
    expected = json.loads(line.stdout)
    got = haphe.validate(path)
    assert got.pop("exit_code") == line.returncode
    got.pop("seconds"), expected.pop("seconds")
    assert got == expected
