#!/usr/bin/env python3
"""Independent counts for the shared test models, computed with trimesh and numpy.

The pinned reports in crates/haphe/tests/models.rs were checked against this script's
output: a different parser (trimesh's) and a different implementation (numpy) of the same
definitions: exact welding, edges shared by one (boundary) or three or more (non-manifold)
triangles, edge-connected components, orientation conflicts, signed volume.

    pip install trimesh numpy scipy networkx pillow
    python3 tools/crosscheck_models.py ../shared/meshes/models
"""
import json
import sys
from pathlib import Path

import numpy as np
import trimesh
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components


def counts(path):
    loaded = trimesh.load(str(path), force="mesh", process=False)
    v = np.asarray(loaded.vertices, dtype=np.float64)
    f = np.asarray(loaded.faces, dtype=np.int64)
    # Exact weld (folding -0.0 into 0.0), keeping only referenced vertices.
    v = v + 0.0
    _, inverse = np.unique(v, axis=0, return_inverse=True)
    f = inverse.reshape(-1)[f]
    used, f = np.unique(f, return_inverse=True)
    f = f.reshape(-1, 3)
    ok = (f[:, 0] != f[:, 1]) & (f[:, 1] != f[:, 2]) & (f[:, 0] != f[:, 2])
    fi = np.nonzero(ok)[0]
    directed = np.concatenate([f[ok][:, [1, 2]], f[ok][:, [2, 0]], f[ok][:, [0, 1]]])
    owner = np.concatenate([fi, fi, fi])
    forward = directed[:, 0] < directed[:, 1]
    undirected = np.sort(directed, axis=1)
    keys, first, inv, uses = np.unique(
        undirected, axis=0, return_index=True, return_inverse=True, return_counts=True
    )
    inv = inv.reshape(-1)
    boundary = int((uses == 1).sum())
    nonmanifold = int((uses >= 3).sum())
    # Orientation conflicts: edges used twice, both in the same direction.
    fwd_count = np.bincount(inv, weights=forward, minlength=len(keys))
    conflicts = int(((uses == 2) & ((fwd_count == 0) | (fwd_count == 2))).sum())
    # Components: triangles joined through shared edges.
    order = np.argsort(inv, kind="stable")
    sorted_inv = inv[order]
    same = sorted_inv[1:] == sorted_inv[:-1]
    a, b = owner[order][:-1][same], owner[order][1:][same]
    n = len(f)
    graph = coo_matrix((np.ones(len(a)), (a, b)), shape=(n, n))
    ncomp, labels = connected_components(graph, directed=False)
    ncomp -= int((~ok).sum())  # triangles with a repeated vertex belong to no component
    # Degenerate: smallest altitude <= 1e-9 of the longest edge, or a repeated vertex.
    verts = np.unique(v, axis=0)[used]
    A, B, C = verts[f[:, 0]], verts[f[:, 1]], verts[f[:, 2]]
    lo, hi = verts.min(axis=0), verts.max(axis=0)
    centre = 0.5 * (lo + hi)
    A, B, C = A - centre, B - centre, C - centre
    cross = np.cross(B - A, C - A)
    twice_area = np.linalg.norm(cross, axis=1)
    longest2 = np.max(
        [((B - A) ** 2).sum(1), ((C - B) ** 2).sum(1), ((A - C) ** 2).sum(1)], axis=0
    )
    rel = np.where(longest2 > 0, twice_area / np.where(longest2 > 0, longest2, 1), 0)
    rel[~ok] = 0
    degenerate = int((rel <= 1e-9).sum())
    duplicates = len(f) - len(np.unique(np.sort(f, axis=1), axis=0))
    volume = float((A * np.cross(B, C)).sum() / 6.0)
    # Non-manifold vertices: the triangles around a vertex, joined where they share one of
    # its edges used by exactly two triangles, form more than one fan.
    manifold_edge = uses[inv] == 2
    incident = [[] for _ in range(len(verts))]
    for t in fi:
        for x in f[t]:
            incident[x].append(t)
    edge_faces = {}
    for k in np.nonzero(manifold_edge)[0]:
        edge_faces.setdefault(tuple(undirected[k]), []).append(int(owner[k]))
    parent = {}

    def root(x):
        while parent[x] != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        return x

    nm_vertices = 0
    for (a, b), (t1, t2) in edge_faces.items():
        for x in (a, b):
            for t in (t1, t2):
                parent.setdefault((x, t), (x, t))
            ra, rb = root((x, t1)), root((x, t2))
            if ra != rb:
                parent[ra] = rb
    for x in range(len(verts)):
        roots = set()
        for t in incident[x]:
            parent.setdefault((x, t), (x, t))
            roots.add(root((x, t)))
        if len(roots) > 1:
            nm_vertices += 1
    # Genus of each closed, conflict-free component without non-manifold vertices.
    genus = None
    labels_ok = labels[fi]
    for comp in np.unique(labels_ok):
        faces_c = fi[labels_ok == comp]
        edge_ids = np.unique(inv[np.isin(owner, faces_c)])
        if (uses[edge_ids] != 2).any():
            continue
        fwd = fwd_count[edge_ids]
        if ((fwd == 0) | (fwd == 2)).any():
            continue
        vs = np.unique(f[faces_c])
        chi = len(vs) - len(edge_ids) + len(faces_c)
        genus = (genus or 0) + (2 - chi) // 2
    return {
        "file": path.name,
        "triangles": len(f),
        "vertices": len(verts),
        "edges": len(keys),
        "components": int(ncomp),
        "closed": boundary == 0 and nonmanifold == 0,
        "boundary_edges": boundary,
        "nonmanifold_edges": nonmanifold,
        "orientation_conflicts": conflicts,
        "nonmanifold_vertices": nm_vertices,
        "genus_sum_if_manifold_components": genus,
        "degenerate_triangles": degenerate,
        "duplicate_faces": int(duplicates),
        "area": float(twice_area.sum() / 2),
        "signed_volume": volume,
    }


def main():
    folder = Path(sys.argv[1] if len(sys.argv) > 1 else "../shared/meshes/models")
    for path in sorted(folder.iterdir()):
        try:
            print(json.dumps(counts(path)))
        except Exception as error:  # report and go on with the next file
            print(json.dumps({"file": path.name, "error": repr(error)}))


if __name__ == "__main__":
    main()
