#!/usr/bin/env python3
"""Writes the small models the reference-image tests render (tests/data/*). Run it from anywhere;
the files are committed, so this only needs running again when a model changes."""
import base64
import json
import math
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))


def png_rgba(width, height, pixel):
    """A PNG of width x height RGBA8 pixels, pixel(x, y) -> (r, g, b, a), row 0 at the top."""
    raw = b"".join(b"\0" + b"".join(bytes(pixel(x, y)) for x in range(width)) for y in range(height))
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0))
            + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def checker(x, y):
    return (230, 200, 40, 255) if (x // 2 + y // 2) % 2 else (40, 90, 200, 255)


def write(name, data):
    with open(os.path.join(HERE, name), "wb") as f:
        f.write(data)


def obj_model():
    # A textured, two-material box corner: a floor with the checker, two walls in Kd colours.
    write("checker.png", png_rgba(8, 8, checker))
    write("box_corner.mtl", b"newmtl floor\nKd 1 1 1\nmap_Kd checker.png\n"
          b"newmtl wall\nKd 0.8 0.3 0.2\n")
    write("box_corner.obj", b"mtllib box_corner.mtl\n"
          b"v -1 0 -1\nv 1 0 -1\nv 1 0 1\nv -1 0 1\nv -1 1.2 -1\nv 1 1.2 -1\nv -1 1.2 1\n"
          b"vt 0 0\nvt 2 0\nvt 2 2\nvt 0 2\n"
          b"usemtl floor\nf 4/1 3/2 2/3 1/4\n"
          b"usemtl wall\nf 1 2 6 5\nf 4 1 5 7\n")


def gltf_model():
    # Two nodes: a parent translated and rotated, with a child scaled; a quad with the checker
    # texture (nearest, repeat) and a triangle strip with vertex colours.
    positions = [(-1, 0, -1), (1, 0, -1), (-1, 0, 1), (1, 0, 1)]
    uvs = [(0, 0), (2, 0), (0, 2), (2, 2)]
    quad_indices = [0, 2, 1, 1, 2, 3]
    strip = [(-0.6, 0.2, 0), (-0.6, 1.0, 0), (0.0, 0.2, 0), (0.0, 1.1, 0), (0.6, 0.2, 0), (0.6, 1.0, 0)]
    colours = [(1, 0, 0, 1), (0, 1, 0, 1), (0, 0, 1, 1), (1, 1, 0, 1), (1, 0, 1, 1), (0, 1, 1, 1)]
    blob = b"".join(struct.pack("<3f", *p) for p in positions)
    blob += b"".join(struct.pack("<2f", *t) for t in uvs)
    blob += b"".join(struct.pack("<H", i) for i in quad_indices)
    blob += b"\0\0"  # align to 4
    strip_offset = len(blob)
    blob += b"".join(struct.pack("<3f", *p) for p in strip)
    colour_offset = len(blob)
    blob += b"".join(struct.pack("<4f", *c) for c in colours)
    image = png_rgba(8, 8, checker)
    half = math.sqrt(0.5)
    doc = {
        "asset": {"version": "2.0", "generator": "tessera tests/data/make_models.py"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [
            {"mesh": 0, "translation": [0, -0.2, 0], "rotation": [0, math.sin(0.3), 0, math.cos(0.3)],
             "children": [1]},
            {"mesh": 1, "translation": [0, 0, -0.3], "scale": [1.2, 1.0, 1.0]},
        ],
        "meshes": [
            {"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "indices": 2,
                             "material": 0}]},
            {"primitives": [{"attributes": {"POSITION": 3, "COLOR_0": 4}, "mode": 5,
                             "material": 1}]},
        ],
        "materials": [
            {"pbrMetallicRoughness": {"baseColorTexture": {"index": 0},
                                      "baseColorFactor": [1, 1, 1, 1]}, "doubleSided": True},
            {"pbrMetallicRoughness": {"baseColorFactor": [0.9, 0.9, 0.9, 1]}, "doubleSided": True},
        ],
        "textures": [{"source": 0, "sampler": 0}],
        "samplers": [{"magFilter": 9728, "minFilter": 9728, "wrapS": 10497, "wrapT": 10497}],
        "images": [{"uri": "data:image/png;base64," + base64.b64encode(image).decode()}],
        "buffers": [{"byteLength": len(blob),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 48},
            {"buffer": 0, "byteOffset": 48, "byteLength": 32},
            {"buffer": 0, "byteOffset": 80, "byteLength": 12},
            {"buffer": 0, "byteOffset": strip_offset, "byteLength": 72},
            {"buffer": 0, "byteOffset": colour_offset, "byteLength": 96},
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
             "min": [-1, 0, -1], "max": [1, 0, 1]},
            {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC2"},
            {"bufferView": 2, "componentType": 5123, "count": 6, "type": "SCALAR"},
            {"bufferView": 3, "componentType": 5126, "count": 6, "type": "VEC3",
             "min": [-0.6, 0.2, 0], "max": [0.6, 1.1, 0]},
            {"bufferView": 4, "componentType": 5126, "count": 6, "type": "VEC4"},
        ],
    }
    write("scene.gltf", json.dumps(doc, indent=1).encode())


def stl_model():
    # A binary STL whose 80-byte header starts with "solid" (as some exporters write): a
    # square pyramid standing on Z (a CAD file: --up +Z).
    apex = (0, 0, 1.2)
    base = [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)]
    facets = [(base[i], base[(i + 1) % 4], apex) for i in range(4)]
    facets += [(base[0], base[2], base[1]), (base[0], base[3], base[2])]
    header = b"solid pyramid exported as binary".ljust(80, b" ")
    body = b"".join(struct.pack("<3f", 0, 0, 0) + b"".join(struct.pack("<3f", *v) for v in f)
                    + b"\0\0" for f in facets)
    write("pyramid.stl", header + struct.pack("<I", len(facets)) + body)


if __name__ == "__main__":
    obj_model()
    gltf_model()
    stl_model()
