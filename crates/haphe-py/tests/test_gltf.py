"""glTF files written by another program (pygltflib): the Khronos sample `Box` validated
by `haphe validate` as a closed solid of volume 1; three meshes under nested
transforms read as one world-frame mesh (`haphe query --inside` and `Shape.from_file`
against a brute force on the analytic shapes) and as a scene of three named objects
(`haphe simulate --scene`, `Scene.from_gltf`)."""

import json
import subprocess

import numpy as np
import pygltflib as g
import pytest

import haphe

# Three closed meshes (counter-clockwise seen from outside), each given with an analytic
# inside test in its own frame and a lower bound of the distance to its surface (the
# distance to the nearest plane of a face).
CUBE = (
    np.array([(x, y, z) for x in (-0.5, 0.5) for y in (-0.5, 0.5) for z in (-0.5, 0.5)]),
    np.array([[0, 1, 2], [1, 3, 2], [4, 6, 5], [5, 6, 7], [0, 4, 1], [1, 4, 5],
              [2, 3, 6], [3, 7, 6], [0, 2, 4], [2, 6, 4], [1, 5, 3], [3, 5, 7]]),
    lambda p: np.all(np.abs(p) < 0.5, axis=1),
    lambda p: np.min(np.abs(0.5 - np.abs(p)), axis=1),
)
# The eight sign patterns (±1, ±1, ±1): the octahedron's face normals, unnormalised.
SIGNS = np.array([(x, y, z) for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)])
OCTAHEDRON = (
    np.array([[0.5, 0, 0], [-0.5, 0, 0], [0, 0.5, 0], [0, -0.5, 0], [0, 0, 0.5], [0, 0, -0.5]]),
    np.array([[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]]),
    lambda p: np.sum(np.abs(p), axis=1) < 0.5,
    lambda p: np.min(np.abs(p @ SIGNS.T - 0.5), axis=1) / np.sqrt(3),
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
    for _, (vertices, faces, _, _), _ in nodes:
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
        write_side_car(gltf, path, blob)
    return path


def write_side_car(gltf, path, blob, name=None):
    """Saves `gltf` as the JSON file `path` with its buffer `blob` in the file `name`
    beside it (default: `path` with the suffix .bin)."""
    side_car = path.with_name(name) if name else path.with_suffix(".bin")
    side_car.write_bytes(blob)
    gltf.buffers[0].uri = side_car.name
    gltf.destroy_binary_blob()
    gltf.save_json(str(path))


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


def sample_points(n=6000, seed=7):
    rng = np.random.default_rng(seed)
    placed = np.concatenate([
        (world @ np.c_[vertices, np.ones(len(vertices))].T).T[:, :3]
        for (_, (vertices, _, _, _), _), world in zip(NODES, world_matrices())
    ])
    lo, hi = placed.min(axis=0) - 0.2, placed.max(axis=0) + 0.2
    points = rng.uniform(lo, hi, size=(n, 3))
    inside, margin = brute_force_inside(points)
    keep = margin > 1e-4
    return points[keep], inside[keep]


def write_khronos_box(path):
    """The Khronos sample `Box`, rebuilt: a unit cube of 24 vertices (split per face, as
    its normals need), normals then positions in one buffer view (positions from byte
    288), 36 unsigned-short indices, a mesh node under a root whose matrix turns it -90°
    about x (z up to y up); a .glb, or a .gltf with its buffer in `Box0.bin` beside it."""
    normals, positions, indices = [], [], []
    for axis in range(3):
        for sign in (1.0, -1.0):
            n, u, v = np.zeros(3), np.zeros(3), np.zeros(3)
            n[axis], u[(axis + 1) % 3], v[(axis + 2) % 3] = sign, 1.0, sign
            base = len(positions)
            for a, b in ((-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)):
                positions.append(0.5 * n + a * u + b * v)
                normals.append(n)
            indices += [base, base + 1, base + 2, base, base + 2, base + 3]
    index_bytes = np.array(indices, dtype=np.uint16).tobytes()
    vertex_bytes = np.array(normals + positions, dtype=np.float32).tobytes()
    blob = index_bytes + vertex_bytes
    gltf = g.GLTF2(
        scene=0, scenes=[g.Scene(nodes=[0])],
        nodes=[g.Node(children=[1], matrix=[1, 0, 0, 0, 0, 0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1]),
               g.Node(mesh=0)],
        meshes=[g.Mesh(name="Mesh", primitives=[g.Primitive(
            attributes=g.Attributes(NORMAL=1, POSITION=2), indices=0, mode=g.TRIANGLES)])],
        accessors=[
            g.Accessor(bufferView=0, componentType=g.UNSIGNED_SHORT, count=36, type=g.SCALAR,
                       max=[23], min=[0]),
            g.Accessor(bufferView=1, byteOffset=0, componentType=g.FLOAT, count=24, type=g.VEC3,
                       max=[1, 1, 1], min=[-1, -1, -1]),
            g.Accessor(bufferView=1, byteOffset=288, componentType=g.FLOAT, count=24, type=g.VEC3,
                       max=[0.5] * 3, min=[-0.5] * 3),
        ],
        bufferViews=[
            g.BufferView(buffer=0, byteOffset=0, byteLength=len(index_bytes), target=g.ELEMENT_ARRAY_BUFFER),
            g.BufferView(buffer=0, byteOffset=len(index_bytes), byteLength=len(vertex_bytes),
                         byteStride=12, target=g.ARRAY_BUFFER),
        ],
        buffers=[g.Buffer(byteLength=len(blob))],
    )
    gltf.set_binary_blob(blob)
    if str(path).endswith(".glb"):
        gltf.save_binary(str(path))
    else:
        write_side_car(gltf, path, blob, "Box0.bin")
    return path


def test_the_khronos_box_validates_as_a_closed_solid_of_volume_one(tmp_path, haphe_cli):
    for path in (write_khronos_box(tmp_path / "Box.glb"), write_khronos_box(tmp_path / "Box.gltf")):
        out = subprocess.run([haphe_cli, "validate", "--json", str(path)], capture_output=True, text=True)
        assert out.returncode == 0, out.stdout + out.stderr
        record = json.loads(out.stdout)
        assert record["format"] == "gltf"
        assert (record["triangles"], record["vertices"]) == (12, 8), "24 split vertices welded to 8"
        assert record["closed"] and record["usable_as"] == "solid", record
        assert abs(record["volume"] - 1.0) < 1e-12, record["volume"]
        # The matrix turns z up into y up: the unit cube stays centred at the origin.
        assert record["bounds_min"] == [-0.5] * 3 and record["bounds_max"] == [0.5] * 3
        [node] = record["gltf"]["nodes"]
        assert (node["node"], node["mesh"], node["name"], node["triangles"], node["closed"]) == (
            1, 0, "Mesh", 12, True)
        # -90° about x: the quaternion (-sin 45°, 0, 0, cos 45°), up to sign.
        q = np.array(node["rotation"]) * np.sign(node["rotation"][3])
        assert np.allclose(q, [-np.sqrt(0.5), 0, 0, np.sqrt(0.5)], atol=1e-12), q
        text = subprocess.run([haphe_cli, "validate", str(path)], capture_output=True, text=True)
        assert "verdict: a valid closed solid" in text.stdout, text.stdout
        assert "node 1 'Mesh': mesh 0, 12 triangles, closed" in text.stdout, text.stdout
    (tmp_path / "Box0.bin").unlink()
    out = subprocess.run([haphe_cli, "validate", str(tmp_path / "Box.gltf")], capture_output=True, text=True)
    assert out.returncode == 2
    assert "Box.gltf: buffer 0: cannot read the file 'Box0.bin'" in out.stdout, out.stdout


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
