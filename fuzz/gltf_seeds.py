#!/usr/bin/env python3
"""Writes seed files for the `read_gltf` fuzz target into the folder given (default
corpus/read_gltf): a cube as .glb and as .gltf with a data URI, in every primitive mode and
index type, with quantized positions, a sparse accessor and nested transforms. Standard
library only."""

import base64
import json
import struct
import sys
from pathlib import Path

CUBE = [(x, y, z) for x in (-0.5, 0.5) for y in (-0.5, 0.5) for z in (-0.5, 0.5)]
TRIANGLES = [0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
             2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5]


def document(mode=4, index_type=5123, quantized=False, sparse=False):
    if quantized:
        positions = b"".join(struct.pack("<3hxx", *(int(c * 2 * 32767) for c in p)) for p in CUBE)
        stride, component, normalized = 8, 5122, True
    else:
        positions = b"".join(struct.pack("<3f", *p) for p in CUBE)
        stride, component, normalized = 12, 5126, False
    fmt = {5121: "B", 5123: "H", 5125: "I"}[index_type]
    indices = struct.pack("<%d%s" % (len(TRIANGLES), fmt), *TRIANGLES)
    while len(indices) % 4:
        indices += b"\0"
    bin_ = indices + positions
    accessors = [
        {"bufferView": 0, "componentType": index_type, "count": len(TRIANGLES), "type": "SCALAR"},
        {"bufferView": 1, "componentType": component, "normalized": normalized, "count": 8,
         "type": "VEC3", "min": [-0.5] * 3, "max": [0.5] * 3},
    ]
    views = [
        {"buffer": 0, "byteOffset": 0, "byteLength": len(indices)},
        {"buffer": 0, "byteOffset": len(indices), "byteLength": len(positions), "byteStride": stride},
    ]
    if sparse:
        extra = struct.pack("<I3f", 7, 0.6, 0.6, 0.6)
        views.append({"buffer": 0, "byteOffset": len(bin_), "byteLength": 4})
        views.append({"buffer": 0, "byteOffset": len(bin_) + 4, "byteLength": 12})
        bin_ += extra
        accessors[1]["sparse"] = {"count": 1, "indices": {"bufferView": 2, "componentType": 5125},
                                  "values": {"bufferView": 3}}
    doc = {
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [
            {"translation": [1, 2, 3], "children": [1]},
            {"rotation": [0, 0.7071068, 0, 0.7071068], "children": [2], "mesh": 0, "name": "a"},
            {"scale": [1, 2, 0.5], "mesh": 0, "extras": {"stiffness": 700, "friction": 0.3}},
        ],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 1}, "indices": 0, "mode": mode}]}],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(bin_)}],
    }
    if quantized:
        doc["extensionsUsed"] = doc["extensionsRequired"] = ["KHR_mesh_quantization"]
    return doc, bin_


def glb(doc, bin_):
    text = json.dumps(doc).encode()
    text += b" " * (-len(text) % 4)
    bin_ += b"\0" * (-len(bin_) % 4)
    length = 12 + 8 + len(text) + 8 + len(bin_)
    return (b"glTF" + struct.pack("<II", 2, length) + struct.pack("<I", len(text)) + b"JSON"
            + text + struct.pack("<I", len(bin_)) + b"BIN\0" + bin_)


def main():
    out = Path(sys.argv[1] if len(sys.argv) > 1 else "corpus/read_gltf")
    out.mkdir(parents=True, exist_ok=True)
    variants = {
        "list": {}, "strip": {"mode": 5}, "fan": {"mode": 6}, "points": {"mode": 0},
        "bytes": {"index_type": 5121}, "ints": {"index_type": 5125},
        "quantized": {"quantized": True}, "sparse": {"sparse": True},
    }
    for name, options in variants.items():
        doc, bin_ = document(**options)
        (out / f"{name}.glb").write_bytes(glb(doc, bin_))
        doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64.b64encode(bin_).decode()
        (out / f"{name}.gltf").write_text(json.dumps(doc))
        doc["buffers"][0]["uri"] = "side.bin"
        (out / f"{name}_sidecar.gltf").write_text(json.dumps(doc))


if __name__ == "__main__":
    main()
