"""Volumes from Python: NIfTI-1 files read and written (and read as nibabel reads them),
numpy grids, voxelised shapes, and a tool drilling into a block while the proxy presses
on it, each cut a new version of the object's shape; bad input refused by name."""

import gzip
import struct

import numpy as np
import pytest

import haphe
from conftest import ROOT

RATE_HZ = 1000.0
VOXEL = 1e-3  # metres
TOOL_RADIUS = 2e-3  # metres


def rotation(axis, angle):
    """The rotation of `angle` radians about `axis` (Rodrigues)."""
    a = np.asarray(axis, dtype=float) / np.linalg.norm(axis)
    k = np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
    return np.eye(3) + np.sin(angle) * k + (1 - np.cos(angle)) * k @ k


def affine_of(linear, translation):
    """The 4×4 affine of a 3×3 linear part and a translation."""
    a = np.eye(4)
    a[:3, :3], a[:3, 3] = linear, translation
    return a


def block(n=24, margin=4):
    """n³ voxels of 1 mm centred on the origin, material (1) from voxel `margin` to
    `n - 1 - margin` on each axis, air (0) around it; iso 0.5. Returns the volume and the
    height of its top face (metres)."""
    values = np.zeros((n, n, n), dtype=np.float32)
    values[margin : n - margin, margin : n - margin, margin : n - margin] = 1.0
    half = 0.5 * (n - 1) * VOXEL
    volume = haphe.Volume(values, affine_of(np.eye(3) * VOXEL, [-half] * 3), iso=0.5)
    top = (n - margin - 0.5) * VOXEL - half
    return volume, top


def test_a_volume_saved_reads_back_with_its_values_and_affine(tmp_path):
    rng = np.random.default_rng(7)
    values = rng.normal(size=(5, 7, 3)).astype(np.float32)
    # Entries that are float32 in millimetres, the unit of the file written.
    affine = affine_of(np.diag([1.5, 0.75, 2.0]) * 1e-3, [-0.02, 0.0125, 0.25])
    volume = haphe.Volume(values, affine, iso=0.25)
    assert volume.dims == (5, 7, 3) and volume.iso == 0.25
    np.testing.assert_array_equal(volume.values(), values)
    np.testing.assert_array_equal(volume.affine, affine)
    for name in ["v.nii", "v.nii.gz"]:
        path = tmp_path / name
        path.write_bytes(b"an older file")
        volume.save(path)
        assert (path.read_bytes()[:2] == b"\x1f\x8b") == name.endswith(".gz")
        back = haphe.Volume.from_nifti(path, iso=0.25)
        assert back.dims == volume.dims
        np.testing.assert_array_equal(back.values(), values)
        np.testing.assert_allclose(back.affine, affine, rtol=1e-12, atol=1e-15)
        # Without an iso: the midpoint of the values' range.
        default = haphe.Volume.from_nifti(path).iso
        assert default == pytest.approx(0.5 * (values.min() + values.max()), rel=1e-6)
    assert len(list(tmp_path.iterdir())) == 2, "no temporary file left beside"


def nibabel_files(nib, folder):
    """Three files written by nibabel: (path, metres per file unit)."""
    rng = np.random.default_rng(3)
    files = []

    # (a) little-endian int16 .nii placed by an sform: rotation, scaling, translation, mm.
    data = rng.integers(-300, 3000, size=(6, 5, 4)).astype("<i2")
    sform = affine_of(rotation([1, 2, 3], 0.4) @ np.diag([0.9, 1.1, 2.5]), [-12.0, 30.5, 7.25])
    img = nib.Nifti1Image(data, None)
    img.set_sform(sform, code=1)
    img.set_qform(None, code=0)
    img.header.set_xyzt_units("mm")
    path = folder / "sform-int16.nii"
    nib.save(img, path)
    assert path.read_bytes()[:4] == struct.pack("<i", 348)
    files.append((path, 1e-3))

    # (b) big-endian float32 .nii.gz placed only by a qform.
    data = rng.normal(100.0, 20.0, size=(4, 6, 5)).astype(">f4")
    header = nib.Nifti1Header(endianness=">")
    img = nib.Nifti1Image(data, None, header=header)
    img.set_data_dtype(">f4")
    qform = affine_of(rotation([0, 1, 1], -0.7) @ np.diag([1.25, 0.8, 1.5]), [5.0, -3.0, 40.0])
    img.set_qform(qform, code=1)
    img.set_sform(None, code=0)
    img.header.set_xyzt_units("mm")
    path = folder / "qform-float32-be.nii.gz"
    nib.save(img, path)
    assert gzip.decompress(path.read_bytes())[:4] == struct.pack(">i", 348)
    files.append((path, 1e-3))

    # (c) a file in metres.
    data = rng.random(size=(3, 4, 5)).astype(np.float32)
    img = nib.Nifti1Image(data, affine_of(np.diag([0.002, 0.003, 0.001]), [0.1, -0.2, 0.05]))
    img.header.set_xyzt_units("meter")
    path = folder / "metres.nii"
    nib.save(img, path)
    files.append((path, 1.0))
    return files


def test_nifti_files_read_as_nibabel_reads_them(tmp_path):
    nib = pytest.importorskip("nibabel")
    for path, metres_per_unit in nibabel_files(nib, tmp_path):
        img = nib.load(path)
        volume = haphe.Volume.from_nifti(path)
        assert volume.dims == img.shape, path.name
        assert volume.values().dtype == np.float32
        np.testing.assert_array_equal(volume.values(), img.get_fdata(), err_msg=path.name)
        expected = img.affine.copy()
        expected[:3, :] *= metres_per_unit
        scale = np.abs(expected).max()
        np.testing.assert_allclose(
            volume.affine, expected, rtol=1e-9, atol=1e-9 * scale, err_msg=path.name
        )


def test_a_voxelised_sphere_has_a_solid_iso_surface():
    sphere = haphe.Shape.from_file(ROOT / "meshes" / "models" / "sphere.ply", units="0.05")
    volume = haphe.Volume.from_mesh(sphere, 0.002)
    assert all(25 <= d <= 80 for d in volume.dims), volume.dims
    shape = volume.shape()
    assert shape.is_solid and shape.triangles > 100
    lo, hi = shape.bounds
    assert np.allclose(lo, -0.05, atol=0.004) and np.allclose(hi, 0.05, atol=0.004)
    inside = shape.inside([[0.0, 0.0, 0.0], [0.0, 0.0, 0.06]])
    assert list(inside) == [True, False]


def test_a_tool_drills_into_a_block_as_the_hand_goes_down():
    volume, top = block()
    cutter = haphe.Cutter(volume, TOOL_RADIUS)
    assert (cutter.tool_radius, cutter.cut_force) == (TOOL_RADIUS, 0.5)
    scene = haphe.Scene()
    oid = scene.add(cutter.shape)
    start = np.array([0.0, 0.0, top + TOOL_RADIUS + 3e-3])
    proxy = haphe.Proxy(position=start, tool_radius=TOOL_RADIUS)
    dt, ticks, speed = 1.0 / RATE_HZ, 1000, 0.01
    deepest, versions, touched = np.inf, 0, 0
    for tick in range(ticks):
        hip = start - [0.0, 0.0, speed * tick * dt]
        force, position, contact = proxy.tick(scene, hip)
        magnitude = np.linalg.norm(force)
        assert np.all(np.isfinite(force)) and magnitude <= haphe.DEFAULT_MAX_FORCE * (1 + 1e-12)
        if contact is not None:
            touched += 1
            # The block is placed at the origin: the world frame is the volume's.
            cutter.press(position, magnitude, dt)
        if tick % 10 == 9:
            shape = cutter.refresh()
            if shape is not None:
                scene.replace(oid, shape)
                versions += 1
        deepest = min(deepest, position[2])
    assert touched > 100 and versions >= 3, (touched, versions)
    assert cutter.removed > 0
    assert scene.shape(oid).version == cutter.shape.version
    print(
        f"drilled: {cutter.removed} voxels removed, {versions} versions, the tool's centre"
        f" {(top - deepest) * 1e3:.2f} mm below the top face"
    )
    assert deepest < top - 2e-3, f"the tool's centre reached {(top - deepest) * 1e3:.2f} mm deep"
    cut = cutter.volume
    assert (cut.values() < cut.iso).sum() > (volume.values() < volume.iso).sum()
    assert (volume.values() >= 0.5).sum() == 16**3, "the volume given was copied"


def felt_stiffness(scene, on, normal):
    """The stiffness a point proxy feels pressing at `on` along `-normal`: the change of
    force over a change of depth (the face may lie a fraction of a voxel off `on`)."""

    def force(depth):
        above = on + 2e-3 * normal
        proxy = haphe.Proxy(position=above)
        for t in range(101):
            hip = above + (on - depth * normal - above) * t / 100
            f, _, _ = proxy.tick(scene, hip)
        return float(np.dot(f, normal))

    return (force(4e-4) - force(2e-4)) / 2e-4


def test_layers_are_felt_where_the_surface_shows_them():
    """Enamel (2) over dentin (1): the top feels like enamel, the side below it like
    dentin, whatever the object's stiffness; the cutter reports its layers."""
    volume, top = block()
    values = volume.values()
    values[:, :, 12:][values[:, :, 12:] > 0.5] = 2.0
    tooth = haphe.Volume(values, volume.affine, iso=0.5)
    cutter = haphe.Cutter(tooth, 0.0, layers=["enamel:2:0.004:900:0.4", "dentin:1:0.02:300"])
    assert cutter.layers() == [
        ("dentin", 1.0, 0.02, 300.0, 0.0, 0.0),
        ("enamel", 2.0, 0.004, 900.0, 0.4, 0.4),
    ]
    scene = haphe.Scene()
    scene.add_volume(cutter, stiffness=5000.0)
    side = top  # the block is a cube centred on the origin
    enamel = felt_stiffness(scene, np.array([0.0, 0.0, top]), np.array([0.0, 0.0, 1.0]))
    dentin = felt_stiffness(scene, np.array([side, 0.0, -6e-3]), np.array([1.0, 0.0, 0.0]))
    assert abs(enamel - 900.0) < 1.0 and abs(dentin - 300.0) < 1.0, (enamel, dentin)
    # A volume added as it is: its iso-surface, the object's stiffness everywhere.
    plain = haphe.Scene()
    plain.add_volume(volume, position=[0.0, 0.0, 0.0], stiffness=5000.0)
    felt = felt_stiffness(plain, np.array([0.0, 0.0, top]), np.array([0.0, 0.0, 1.0]))
    assert abs(felt - 5000.0) < 5.0, felt
    with pytest.raises(haphe.HapheError, match="layers.*expected `NAME:FROM:RATE:STIFFNESS"):
        haphe.Cutter(tooth, 0.0, layers=["enamel:2"])
    with pytest.raises(TypeError, match="Cutter or a haphe.Volume"):
        scene.add_volume(cutter.shape)


def test_a_volume_pickles_bit_for_bit():
    import pickle

    volume, _ = block()
    affine = affine_of(rotation([1, 2, 3], 0.4) * VOXEL, [1e-3, 0, 0])
    tilted = haphe.Volume(volume.values(), affine, iso=0.25)
    back = pickle.loads(pickle.dumps(tilted))
    assert back.dims == tilted.dims and back.iso == tilted.iso
    assert np.array_equal(back.values(), tilted.values())
    assert np.array_equal(back.affine, tilted.affine)


def test_a_shape_that_is_not_a_version_of_the_object_is_refused():
    volume, _ = block()
    cutter = haphe.Cutter(volume, TOOL_RADIUS)
    scene = haphe.Scene()
    oid = scene.add(cutter.shape)
    other = haphe.Shape.from_file(ROOT / "meshes" / "models" / "sphere.ply", units="0.01")
    with pytest.raises(haphe.HapheError, match="not a new version"):
        scene.replace(oid, other)
    with pytest.raises(KeyError):
        scene.replace(oid + 1, cutter.shape)
    assert cutter.refresh() is None, "nothing was cut"


def test_bad_volumes_are_refused_naming_the_argument():
    values, affine = np.zeros((3, 3, 3)), np.eye(4) * 1e-3
    affine[3, 3] = 1.0
    bad = values.copy()
    bad[1, 2, 0] = np.nan
    with pytest.raises(haphe.HapheError, match=r"values.*\[1, 2, 0\] is NaN"):
        haphe.Volume(bad, affine)
    with pytest.raises(haphe.HapheError, match="affine.*4×4"):
        haphe.Volume(values, np.eye(3))
    with pytest.raises(haphe.HapheError, match="affine.*last row"):
        haphe.Volume(values, np.ones((4, 4)))
    with pytest.raises(haphe.HapheError, match="affine.*invertible"):
        haphe.Volume(values, np.diag([1e-3, 0.0, 1e-3, 1.0]))
    with pytest.raises(haphe.HapheError, match=r"values.*\(nx, ny, nz\)"):
        haphe.Volume(np.zeros((3, 3)), affine)
    with pytest.raises(haphe.HapheError, match="iso"):
        haphe.Volume(values, affine, iso=float("nan"))


def test_bad_files_are_refused_naming_the_file(tmp_path):
    missing = tmp_path / "missing.nii"
    with pytest.raises(FileNotFoundError, match="missing.nii"):
        haphe.Volume.from_nifti(missing)
    text = tmp_path / "notes.nii"
    text.write_bytes(b"not a volume\n" * 40)
    with pytest.raises(haphe.HapheError, match="notes.nii.*NIfTI"):
        haphe.Volume.from_nifti(text)
    nifti2 = tmp_path / "two.nii"
    nifti2.write_bytes(struct.pack("<i", 540) + b"n+2\0" + bytes(600))
    with pytest.raises(haphe.HapheError, match="two.nii.*NIfTI-2"):
        haphe.Volume.from_nifti(nifti2)
    with pytest.raises(haphe.HapheError, match="iso"):
        haphe.Volume.from_nifti(missing, iso=float("inf"))


def test_bad_voxel_sizes_and_tools_are_refused_naming_the_parameter():
    sphere = haphe.Shape.from_file(ROOT / "meshes" / "models" / "sphere.ply", units="0.05")
    for voxel in [0.0, -1e-3, float("nan"), float("inf"), 2.0, 1e-7]:
        with pytest.raises(haphe.HapheError, match="voxel") as e:
            haphe.Volume.from_mesh(sphere, voxel)
        message = str(e.value).lower()
        assert f"{voxel:g}" in message or "voxels" in message, message
    volume, top = block()
    for radius in [-1e-3, float("nan"), 1.0]:
        with pytest.raises(haphe.HapheError, match="tool_radius"):
            haphe.Cutter(volume, radius)
    for force in [-0.5, float("nan")]:
        with pytest.raises(haphe.HapheError, match="cut_force"):
            haphe.Cutter(volume, TOOL_RADIUS, cut_force=force)
    cutter = haphe.Cutter(volume, TOOL_RADIUS)
    with pytest.raises(haphe.HapheError, match="centre"):
        cutter.press([0.0, float("nan"), top], 1.0, 1e-3)
    with pytest.raises(haphe.HapheError, match="dt"):
        cutter.press([0.0, 0.0, top], 1.0, float("inf"))
    assert cutter.press([0.0, 0.0, top], 0.1, 1e-3) == 0, "below the cut force"
    empty = haphe.Volume(np.zeros((4, 4, 4)), np.diag([1e-3, 1e-3, 1e-3, 1.0]), iso=0.5)
    with pytest.raises(haphe.HapheError, match="no material"):
        haphe.Cutter(empty, TOOL_RADIUS)
