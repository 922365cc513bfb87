"""glTF scenes written by another program (pygltflib): three meshes under nested
transforms read as one world-frame mesh (`haphe query --inside` and `Shape.from_file`
against a brute force on the analytic shapes) and as a scene of three named objects
(`haphe simulate --scene`, `Scene.from_gltf`)."""

import subprocess

import numpy as np
import pygltflib as g
import pytest

import haphe

# Three closed meshes, each given with an analytic inside test in its own frame.
CUBE = (
    np.array([(x, y, z) for x in (-0.5, 0.5) for y in (-0.5, 0.5) for z in (-0.5, 0.5)]),
    np.array([[0, 2, 1], [1, 2, 3], [4, 5, 6], [5, 7, 6], [0, 1, 4], [1, 5, 4],
              [2, 6, 3], [3, 6, 7], [0, 4, 2], [2, 4, 6], [1, 3, 5], [3, 7, 5]]),
    lambda p: np.all(np.abs(p) < 0.5, axis=1),
    lambda p: np.min(0.5 - np.abs(p), axis=1),
)
OCTAHEDRON = (
    np.array([[0.5, 0, 0], [-0.5, 0, 0], [0, 0.5, 0], [0, -0.5, 0], [0, 0, 0.5], [0, 0, -0.5]]),
    np.array([[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]]),
    lambda p: np.sum(np.abs(p), axis=1) < 0.5,
    lambda p: np.abs(0.5 - np.sum(np.abs(p), axis=1)) / np.sqrt(3),
)
TETRAHEDRON = (
    np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float),
    np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]),
    lambda p: np.all(p > 0, axis=1) & (np.sum(p, axis=1) < 1),
    lambda p: np.minimum(np.min(np.abs(p), axis=1), np.abs(1 - np.sum(p, axis=1)) / np.sqrt(3)),
)

# Nested nodes: base (translation) > arm (rotation, translation) > hand (non-uniform scale,
# translation); each holds one of the meshes.
NODES = [
    ("base", CUBE, {"translation": [0.2, 0.0, 0.0]}),
    ("arm", OCTAHEDRON, {"rotation": [0.0, 0.0, np.sin(0.35), np.cos(0.35)],
                         "translation": [0.0, 1.5, 0.0]}),
    ("hand", TETRAHEDRON, {"scale": [1.5, 0.5, 2.0], "translation": [1.2, 0.0, 0.3]}),
]


def quaternion_matrix(x, y, z, w):
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ])


def local_matrix(trs):
    m = np.eye(4)
    m[:3, :3] = quaternion_matrix(*trs.get("rotation", [0, 0, 0, 1])) @ np.diag(trs.get("scale", [1, 1, 1]))
    m[:3, 3] = trs.get("translation", [0, 0, 0])
    return m


def world_matrices():
    """Each node's world matrix: its ancestors' local matrices times its own."""
    out, world = [], np.eye(4)
    for _, _, trs in NODES:
        world = world @ local_matrix(trs)
        out.append(world)
    return out


def write_scene(path, nodes=NODES, copies=None):
    """Writes the nested scene (or `copies` root nodes sharing the first mesh) with
    pygltflib: a .glb, or a .gltf with its buffer in a side-car .bin file."""
    blob, accessors, views, meshes = b"", [], [], []
    for _, (vertices, faces, _, _) in nodes:
        for data, kind, component, target in (
            (faces.astype(np.uint16).tobytes(), g.SCALAR, g.UNSIGNED_SHORT, g.ELEMENT_ARRAY_BUFFER),
            (vertices.astype(np.float32).tobytes(), g.VEC3, g.FLOAT, g.ARRAY_BUFFER),
        ):
            blob += b"\0" * (-len(blob) % 4)
            views.append(g.BufferView(buffer=0, byteOffset=len(blob), byteLength=len(data), target=target))
            count = faces.size if kind == g.SCALAR else len(vertices)
            accessor = g.Accessor(bufferView=len(views) - 1, componentType=component, count=count, type=kind)
            if kind == g.VEC3:
                accessor.min = vertices.min(axis=0).tolist()
                accessor.max = vertices.max(axis=0).tolist()
            accessors.append(accessor)
            blob += data
        meshes.append(g.Mesh(primitives=[g.Primitive(
            attributes=g.Attributes(POSITION=len(accessors) - 1), indices=len(accessors) - 2)]))
    if copies is None:
        gltf_nodes = [g.Node(name=name, mesh=i, children=[i + 1] if i + 1 < len(nodes) else [], **trs)
                      for i, (name, _, trs) in enumerate(nodes)]
        roots = [0]
    else:
        gltf_nodes = [g.Node(name=f"copy {i}", mesh=0, translation=[2.0 * i, 0, 0]) for i in range(copies)]
        roots = list(range(copies))
    gltf = g.GLTF2(scene=0, scenes=[g.Scene(nodes=roots)], nodes=gltf_nodes, meshes=meshes,
                   accessors=accessors, bufferViews=views, buffers=[g.Buffer(byteLength=len(blob))])
    gltf.set_binary_blob(blob)
    if str(path).endswith(".glb"):
        gltf.save_binary(str(path))
    else:
        gltf.convert_buffers(g.BufferFormat.BINFILE)
        gltf.save(str(path))
    return path


def brute_force_inside(points):
    """Inside the union of the three meshes, each tested analytically in its own frame,
    and the distance (in local units) to the nearest boundary, to leave out points too
    close to a surface for the mesh's float32 coordinates to decide."""
    inside = np.zeros(len(points), dtype=bool)
    margin = np.full(len(points), np.inf)
    homogeneous = np.c_[points, np.ones(len(points))]
    for (_, (_, _, is_inside, distance), _), world in zip(NODES, world_matrices()):
        local = (np.linalg.inv(world) @ homogeneous.T).T[:, :3]
        inside |= is_inside(local)
        margin = np.minimum(margin, distance(local))
    return inside, margin


def sample_points(n=3000, seed=7):
    rng = np.random.default_rng(seed)
    corners = np.array([w[:3, 3] for w in world_matrices()])
    lo, hi = corners.min(axis=0) - 1.5, corners.max(axis=0) + 1.5
    points = rng.uniform(lo, hi, size=(n, 3))
    inside, margin = brute_force_inside(points)
    keep = margin > 1e-4
    return points[keep], inside[keep]


def test_query_inside_agrees_with_brute_force_on_the_world_frame_union(tmp_path, haphe_cli):
    path = write_scene(tmp_path / "arm.glb")
    points, expected = sample_points()
    assert 100 < expected.sum() < len(points) - 100, "both answers are sampled"
    csv = tmp_path / "points.csv"
    np.savetxt(csv, points, delimiter=",", header="x,y,z", comments="", fmt="%.17g")
    out = subprocess.run([haphe_cli, "query", str(path), "--inside", str(csv)],
                         capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    got = np.array([line == "inside" for line in out.stdout.split()])
    assert len(got) == len(points)
    assert (got == expected).all(), np.flatnonzero(got != expected)[:10]
    # The Python package reads the same world-frame mesh.
    shape = haphe.Shape.from_file(path)
    assert shape.is_solid
    assert (shape.inside(points) == expected).all()


def test_a_side_car_gltf_reads_like_the_glb(tmp_path):
    glb = haphe.Shape.from_file(write_scene(tmp_path / "arm.glb"))
    gltf_path = write_scene(tmp_path / "arm.gltf")
    bins = list(tmp_path.glob("*.bin"))
    assert len(bins) == 1, "pygltflib wrote the buffer beside the .gltf"
    gltf = haphe.Shape.from_file(gltf_path)
    assert (gltf.triangles, gltf.vertices, gltf.bounds) == (glb.triangles, glb.vertices, glb.bounds)
    bins[0].unlink()
    with pytest.raises(haphe.HapheError, match=r"arm\.gltf: buffer 0: cannot read the file '.*\.bin'"):
        haphe.Shape.from_file(gltf_path)


def test_simulate_loads_one_object_per_mesh_node(tmp_path, haphe_cli):
    path = write_scene(tmp_path / "arm.glb")
    out = subprocess.run([haphe_cli, "simulate", "--scene", str(path), "--path", "press",
                          "--seconds", "0.2"], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert "scene: 3 object(s)" in out.stdout, out.stdout
    for name, _, _ in NODES:
        assert f"  {name} (id " in out.stdout, out.stdout


def test_scene_from_gltf_names_and_places_the_objects(tmp_path):
    scene = haphe.Scene.from_gltf(write_scene(tmp_path / "arm.glb"))
    assert len(scene) == 3
    assert scene.names == {0: "base", 1: "arm", 2: "hand"}


def test_a_hundred_nodes_sharing_a_mesh_make_a_hundred_objects(tmp_path):
    path = write_scene(tmp_path / "copies.glb", nodes=NODES[:1], copies=100)
    scene = haphe.Scene.from_gltf(path)
    assert len(scene) == 100
    assert scene.names[99] == "copy 99"
