"""Shared fixtures: the repository's paths and the `haphe` command the results are
compared with."""

import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[3]
# The shared collection beside the repository when it is there, else the repository's own
# meshes/ (a subset: tests of models it lacks are skipped, with the reason shown).
MODELS = ROOT.parent / "shared" / "meshes" / "models"
if not MODELS.is_dir():
    MODELS = ROOT / "meshes" / "models"


@pytest.fixture(scope="session")
def haphe_cli():
    """The `haphe` binary (HAPHE_BIN, or the workspace's debug build)."""
    path = Path(os.environ.get("HAPHE_BIN", ROOT / "target" / "debug" / "haphe"))
    if not path.exists():
        subprocess.run(
            ["cargo", "build", "-p", "haphe-cli", "--locked"], cwd=ROOT, check=True
        )
    return str(path)


class Models:
    """The models folder; `models / name` skips the test when that model is not there."""

    def __init__(self, folder: Path):
        self.folder = folder

    def __truediv__(self, name: str) -> Path:
        path = self.folder / name
        if not path.exists():
            pytest.skip(f"needs {name} (in ../shared/meshes/models)")
        return path


@pytest.fixture(scope="session")
def models():
    """The models folder (shared collection or the repository's meshes/)."""
    return Models(MODELS)
