"""haphe.run with real devices: the Force Dimension and OpenHaptics stand-in libraries
(built here with the system's C compiler from the C sources the Rust tests use,
crates/haphe-devices/tests/standin) and a UDP peer in Python push the device point into
a cube; the run reports contact and a force out of the cube, and the device's last force
is zero."""

import os
import shutil
import socket
import struct
import subprocess
import threading
import time
from pathlib import Path

import numpy as np
import pytest

import haphe
from conftest import ROOT
from test_queries import cube

STANDIN = ROOT / "crates" / "haphe-devices" / "tests" / "standin"


@pytest.fixture(scope="module")
def standin(tmp_path_factory):
    """Builds a stand-in library: standin("dhd.c") -> its path."""
    cc = os.environ.get("CC", "cc")
    if shutil.which(cc) is None:
        pytest.fail(f"no C compiler {cc!r} to build the stand-in libraries")
    folder = tmp_path_factory.mktemp("standin")
    built = {}

    def build(source: str) -> Path:
        if source not in built:
            out = folder / (Path(source).stem + ".so")
            subprocess.run(
                [cc, "-shared", "-fPIC", "-O2", "-o", str(out), str(STANDIN / source),
                 "-lpthread", "-lm"],
                check=True,
            )
            built[source] = out
        return built[source]

    return build


def centred_cube():
    """A 1 m cube centred on the origin, stiffness 600 N/m."""
    scene = haphe.Scene()
    scene.add(cube(), position=(-0.5, -0.5, -0.5), stiffness=600.0)
    return scene


def press_file(path: Path, start, end, samples=1500):
    """A straight press at 1 kHz from start to end, then held: six numbers a line."""
    start, end = np.asarray(start, float), np.asarray(end, float)
    v = (end - start) / (samples / 1000.0)
    with open(path, "w") as f:
        for s in np.linspace(0.0, 1.0, samples + 1):
            p = start + s * (end - start)
            f.write(" ".join(repr(float(x)) for x in (*p, *v)) + "\n")
    return path


def assert_pressed_out_of_the_cube(out):
    contact = out["contact"]
    assert contact.sum() > 100, out["stop"]
    force = out["force"][contact]
    assert np.isfinite(out["force"]).all()
    assert (np.linalg.norm(out["force"], axis=1) <= 3.3 + 1e-9).all()
    # Pressed down through the top face: the force points up, out of the cube.
    assert force[:, 2].max() > 1.0
    assert (force[:, 2] >= -1e-9).all()


def last_force(report: Path):
    count, fx, fy, fz, enabled, largest = report.read_text().split()
    return int(count), (float(fx), float(fy), float(fz)), enabled == "1", float(largest)


@pytest.mark.parametrize(
    "device, source, variable, start",
    [
        # Force Dimension frame, metres, z up; OpenHaptics frame, millimetres, y up.
        ("dhd", "dhd.c", "HAPHE_DHD_LIBRARY", (0.0, 0.0, 0.06)),
        ("openhaptics", "hd.c", "HAPHE_HD_LIBRARY", (0.0, 70.0, 0.0)),
    ],
)
def test_run_with_a_vendor_stand_in(
    standin, tmp_path, monkeypatch, device, source, variable, start
):
    monkeypatch.setenv(variable, str(standin(source)))
    monkeypatch.setenv("HAPHE_STANDIN_PATH", str(press_file(tmp_path / "press.txt", start, (0, 0, 0))))
    report = tmp_path / "forces.txt"
    monkeypatch.setenv("HAPHE_STANDIN_FORCES", str(report))
    out = haphe.run(centred_cube(), device=device, seconds=2.0)
    assert "stand-in" in out["device"], out["device"]
    assert out["stop"] == "finished", out["stop"]
    # Deadlines may be skipped on a loaded machine; most ticks run.
    assert 1000 < len(out["t"]) <= 2001
    assert_pressed_out_of_the_cube(out)
    count, last, enabled, largest = last_force(report)
    assert count >= len(out["t"])
    assert last == (0.0, 0.0, 0.0) and not enabled
    assert largest > 1.0


def test_a_missing_library_names_the_variable(monkeypatch):
    monkeypatch.setenv("HAPHE_DHD_LIBRARY", "/nonexistent/libdhd.so")
    with pytest.raises(haphe.DeviceError, match="HAPHE_DHD_LIBRARY") as raised:
        haphe.run(centred_cube(), device="dhd", seconds=0.1)
    assert isinstance(raised.value, OSError)
    with pytest.raises(haphe.HapheError, match="unknown device"):
        haphe.run(centred_cube(), device="phantom", seconds=0.1)
    with pytest.raises(haphe.HapheError, match="udp_timeout"):
        haphe.run(centred_cube(), device="udp:127.0.0.1:1", seconds=0.1, udp_timeout=0.0)


POSITION = struct.Struct("<4sHHQQ3dII")  # docs/devices.md: 56 bytes
FORCE = struct.Struct("<4sHHQQ3d")  # 48 bytes


def test_run_with_a_udp_peer():
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as probe:
        probe.bind(("127.0.0.1", 0))
        port = probe.getsockname()[1]
    peer = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    peer.bind(("127.0.0.1", 0))
    peer.setblocking(False)
    done = threading.Event()
    forces = []

    def receive():
        try:
            while True:
                data = peer.recv(64)
                if len(data) == FORCE.size and data[:4] == b"HPHF":
                    forces.append(FORCE.unpack(data))
        except (BlockingIOError, ConnectionRefusedError):
            pass

    def drive():
        # A press from above the workspace (±0.1 m) to its centre, one position a
        # millisecond, until the run is over; every force datagram is kept.
        started = time.monotonic()
        sequence = 0
        while not done.is_set():
            s = min((time.monotonic() - started) / 1.0, 1.0)
            sequence += 1
            stamp = int((time.monotonic() - started) * 1e6)
            peer.sendto(
                POSITION.pack(b"HPHP", 1, 0, sequence, stamp, 0.0, 0.0, 0.12 * (1 - s), 0, 0),
                ("127.0.0.1", port),
            )
            receive()
            time.sleep(0.001)
        # What haphe sent as it stopped.
        until = time.monotonic() + 0.2
        while time.monotonic() < until:
            receive()
            time.sleep(0.001)

    thread = threading.Thread(target=drive)
    thread.start()
    try:
        # The peer is a Python thread that shares two cores with the servo and the
        # build: under load it can miss 100 ms and more, which the default 50 ms
        # timeout would rightly call a lost peer. Losing it is tested above.
        out = haphe.run(
            centred_cube(), device=f"udp:127.0.0.1:{port}", seconds=2.0, udp_timeout=1.0
        )
    finally:
        done.set()
        thread.join()
        peer.close()
    assert "network device" in out["device"], out["device"]
    assert out["stop"] == "finished", (out["stop"], out["report"])
    assert "positions used" in (out["report"] or ""), out["report"]
    assert_pressed_out_of_the_cube(out)
    # The peer was sent forces while pressed, and zero with status Stopped at the end.
    assert max(f[7] for f in forces) > 1.0
    magic, version, status, _, _, fx, fy, fz = forces[-1]
    assert (magic, version, status) == (b"HPHF", 1, 2)
    assert (fx, fy, fz) == (0.0, 0.0, 0.0)
