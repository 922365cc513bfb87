"""Shared fixtures: the repository's paths and the `haphe` command the results are
compared with."""

import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[3]
MODELS = ROOT.parent / "shared" / "meshes" / "models"
if not MODELS.is_dir():
    MODELS = ROOT / ".." / "shared" / "meshes" / "models"


@pytest.fixture(scope="session")
def haphe_cli():
    """The `haphe` binary (HAPHE_BIN, or the workspace's debug build)."""
    path = Path(os.environ.get("HAPHE_BIN", ROOT / "target" / "debug" / "haphe"))
    if not path.exists():
        subprocess.run(
            ["cargo", "build", "-p", "haphe-cli", "--locked"], cwd=ROOT, check=True
        )
    return str(path)


@pytest.fixture(scope="session")
def models():
    """The shared models folder."""
    if not MODELS.is_dir():
        pytest.fail(f"the shared meshes are missing: {MODELS}")
    return MODELS
