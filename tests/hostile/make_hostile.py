#!/usr/bin/env python3
"""Writes tessera's hostile corpus into a folder: one sub-folder per case, holding the model and
whatever it names (FIFOs, folders, short buffers, PNG bombs), and cases.json, which says for each
case how `tessera render` and `tessera info` must behave (exit status, words the message must and
must not hold, whether the picture must show the model).

Every case is one class of failure from issue 22 ("Hostile input, round two"): hangs on FIFOs,
memory bombs, integers past 32 bits, NaN and infinity in OBJ, extreme but finite coordinates, and
messages that mislead. Nothing here is committed as a binary: the test (hostile_test.cpp) runs this
script into a fresh temporary folder.

Usage: make_hostile.py OUT_FOLDER
"""

import base64
import json
import os
import struct
import sys
import zlib

CASES = []


def case(name, model, exit, err_has=(), err_lacks=(), out_has=(), drawn=False,
         commands=("render", "info"), args=(), render_args=()):
    """Registers a case, run with each of `commands` and `args` (and `render_args` for render).
    exit: the expected status. err_has, err_lacks: words the messages must and must not hold
    (stderr; for info, its report of warnings on stdout too). out_has: words info's stdout must
    hold. drawn: the rendered image must show the model with shading (many colours)."""
    CASES.append({
        "name": name, "model": model, "exit": exit, "err_has": list(err_has),
        "err_lacks": list(err_lacks), "out_has": list(out_has), "drawn": drawn,
        "commands": list(commands), "args": list(args), "render_args": list(render_args),
    })


def write(folder, name, data):
    path = os.path.join(folder, name)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "wb" if isinstance(data, bytes) else "w") as f:
        f.write(data)
    return path


# ---- Building blocks ----

def png(width, height, rows=None, claimed=None):
    """A grey 8-bit PNG, its pixel rows streamed through zlib (a 16384 x 16384 image of zeros is
    about 260 KB). claimed: (w, h) to write into the header instead, with no pixel data."""
    def chunk(kind, body):
        return (struct.pack(">I", len(body)) + kind + body +
                struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF))
    w, h = claimed or (width, height)
    header = chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 0, 0, 0, 0))
    if claimed:
        data = zlib.compress(b"\0" * 64)
    else:
        z = zlib.compressobj(9)
        row = b"\0" + bytes(width)
        parts = [z.compress(row) for _ in range(height)]
        parts.append(z.flush())
        data = b"".join(parts)
    return b"\x89PNG\r\n\x1a\n" + header + chunk(b"IDAT", data) + chunk(b"IEND", b"")


def tiny_png():
    return png(2, 2)


CUBE_V = [(x, y, z) for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]
CUBE_F = [(1, 3, 4, 2), (5, 6, 8, 7), (1, 2, 6, 5), (3, 7, 8, 4), (1, 5, 7, 3), (2, 4, 8, 6)]


def sphere_obj(scale, segments=24, rings=12):
    """A UV sphere of radius `scale`, so shading shows as many colours when lit."""
    import math
    lines = []
    for r in range(rings + 1):
        phi = math.pi * r / rings
        for s in range(segments):
            theta = 2 * math.pi * s / segments
            lines.append("v %r %r %r" % (scale * math.sin(phi) * math.cos(theta),
                                         scale * math.cos(phi),
                                         scale * math.sin(phi) * math.sin(theta)))
    for r in range(rings):
        for s in range(segments):
            a = r * segments + s + 1
            b = r * segments + (s + 1) % segments + 1
            c, d = a + segments, b + segments
            lines.append("f %d %d %d" % (a, c, d))
            lines.append("f %d %d %d" % (a, d, b))
    return "\n".join(lines) + "\n"


def textured_obj(texture_line):
    mtl = "newmtl m\nKd 1 1 1\n" + texture_line + "\n"
    obj = ("mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
           "usemtl m\nf 1/1 2/2 3/3\n")
    return obj, mtl


def gltf_triangle(extra_top=None, buffer_uri=None, image=None, mesh_index=0, node_count=1):
    """A glTF with one triangle (positions and indices in one buffer), `node_count` nodes all
    drawing mesh `mesh_index`; extra_top is merged into the top-level object."""
    positions = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
    indices = struct.pack("<3H", 0, 1, 2) + b"\0\0"
    data = positions + indices
    uri = buffer_uri or "data:application/octet-stream;base64," + base64.b64encode(data).decode()
    doc = {
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": list(range(node_count))}],
        "nodes": [{"mesh": mesh_index} for _ in range(node_count)],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "buffers": [{"uri": uri, "byteLength": len(data)}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                        {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
             "min": [0, 0, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}],
    }
    if image is not None:
        doc["meshes"][0]["primitives"][0]["material"] = 0
        doc["materials"] = [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]
        doc["textures"] = [{"source": 0}]
        doc["images"] = [{"uri": image}]
    if extra_top:
        doc.update(extra_top)
    return doc, data


def grid_mesh_buffers(quads):
    """A flat grid of quads x quads (2 quads^2 triangles), as glTF buffer bytes."""
    n = quads + 1
    pos = bytearray()
    for j in range(n):
        for i in range(n):
            pos += struct.pack("<3f", i / quads, j / quads, 0)
    idx = bytearray()
    for j in range(quads):
        for i in range(quads):
            a = j * n + i
            idx += struct.pack("<6I", a, a + 1, a + n + 1, a, a + n + 1, a + n)
    return bytes(pos), bytes(idx), n * n, quads * quads * 6


def instancing_gltf(folder, nodes, quads=181):
    """`nodes` nodes instancing one grid mesh of 2 * quads^2 triangles (181: 65,522)."""
    pos, idx, vertex_count, index_count = grid_mesh_buffers(quads)
    write(folder, "grid.bin", pos + idx)
    doc = {
        "asset": {"version": "2.0"}, "scene": 0,
        "scenes": [{"nodes": list(range(nodes))}],
        "nodes": [{"mesh": 0, "translation": [0, 0, -0.001 * k]} for k in range(nodes)],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "buffers": [{"uri": "grid.bin", "byteLength": len(pos) + len(idx)}],
        "bufferViews": [{"buffer": 0, "byteLength": len(pos)},
                        {"buffer": 0, "byteOffset": len(pos), "byteLength": len(idx)}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": vertex_count, "type": "VEC3",
             "min": [0, 0, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5125, "count": index_count, "type": "SCALAR"}],
    }
    write(folder, "model.gltf", json.dumps(doc))


def glb(doc, binary):
    text = json.dumps(doc).encode()
    text += b" " * (-len(text) % 4)
    out = struct.pack("<4sII", b"glTF", 2, 0)
    out += struct.pack("<I4s", len(text), b"JSON") + text
    if binary is not None:
        out += struct.pack("<I4s", len(binary), b"BIN\0") + binary
    return out[:8] + struct.pack("<I", len(out)) + out[12:]


# ---- The cases ----

def not_a_file(root, name, files, special, kind, exit, message):
    """A case whose model folder holds `files` ({name: content}) and `special`, a FIFO nobody
    writes to or a folder (`kind`) where a file is expected. The model is the first of `files`,
    or `special` itself when `files` is empty."""
    d = os.path.join(root, name)
    os.makedirs(d)
    for file_name, content in files.items():
        write(d, file_name, content)
    if kind == "fifo":
        os.mkfifo(os.path.join(d, special))
    else:
        os.makedirs(os.path.join(d, special))
    model = next(iter(files), special)
    case(name, model, exit, err_has=[special + ": " + message],
         err_lacks=["no such file", "not found"])


def hangs(root):
    # Each named where a file is expected; a FIFO must never block render or info.
    obj, mtl = textured_obj("map_Kd tex.png")
    buffer_doc, _ = gltf_triangle(buffer_uri="b.bin")
    image_doc, _ = gltf_triangle(image="img.png")
    not_a_file(root, "fifo_obj_texture", {"model.obj": obj, "m.mtl": mtl}, "tex.png", "fifo", 0,
               "is a FIFO")
    not_a_file(root, "fifo_mtl", {"model.obj": obj}, "m.mtl", "fifo", 0, "is a FIFO")
    not_a_file(root, "directory_obj_texture", {"model.obj": obj, "m.mtl": mtl}, "tex.png", "dir",
               0, "is a directory")
    not_a_file(root, "fifo_gltf_buffer", {"model.gltf": json.dumps(buffer_doc)}, "b.bin", "fifo",
               1, "is a FIFO")
    not_a_file(root, "directory_gltf_image", {"model.gltf": json.dumps(image_doc)}, "img.png",
               "dir", 0, "is a directory")
    not_a_file(root, "fifo_model", {}, "model.stl", "fifo", 1, "is a FIFO")


def bombs(root):
    # 16384 x 16384 grey pixels in a few hundred KB: over the per-texture budget, refused from
    # the header.
    d = os.path.join(root, "png_bomb_obj")
    obj, mtl = textured_obj("map_Kd big.png")
    write(d, "model.obj", obj)
    write(d, "m.mtl", mtl)
    write(d, "big.png", png(16384, 16384))
    case("png_bomb_obj", "model.obj", 1,
         err_has=["big.png: image is 16384x16384", "--max-texture-pixels"])

    # Two textures each at the per-texture budget: together over the budget for all.
    d = os.path.join(root, "two_png_bombs_gltf")
    doc, _ = gltf_triangle(image="a.png")
    doc["images"].append({"uri": "b.png"})
    doc["textures"].append({"source": 1})
    doc["materials"].append({"pbrMetallicRoughness": {"baseColorTexture": {"index": 1}}})
    prim = dict(doc["meshes"][0]["primitives"][0])
    prim["material"] = 1
    doc["meshes"][0]["primitives"].append(prim)
    write(d, "model.gltf", json.dumps(doc))
    big = png(8192, 8192)
    write(d, "a.png", big)
    write(d, "b.png", big)
    case("two_png_bombs_gltf", "model.gltf", 1,
         err_has=["b.png", "texture pixels in all of the model's textures", "--memory-limit"])

    # A header claiming 100000 x 100000: over the budget, not "unknown image type".
    d = os.path.join(root, "png_claims_huge")
    obj, mtl = textured_obj("map_Kd huge.png")
    write(d, "model.obj", obj)
    write(d, "m.mtl", mtl)
    write(d, "huge.png", png(0, 0, claimed=(100000, 100000)))
    case("png_claims_huge", "model.obj", 1, err_has=["image is 100000x100000", "over the budget"],
         err_lacks=["unknown image type"])

    # 600 nodes instancing a 65,522-triangle mesh: 39 million triangles, refused before flattening.
    d = os.path.join(root, "gltf_instancing_bomb")
    instancing_gltf(d, 600)
    case("gltf_instancing_bomb", "model.gltf", 1,
         err_has=["39313200 triangles (after instancing), over the budget of 2097152",
                  "--max-triangles"])

    # 32 of them: 2,096,704 triangles, just inside the budget: drawn within the memory bound.
    d = os.path.join(root, "gltf_instancing_at_budget")
    instancing_gltf(d, 32)
    case("gltf_instancing_at_budget", "model.gltf", 0, render_args=["--resolution", "320,240"])

    # The triangle budget is a flag.
    d = os.path.join(root, "obj_over_max_triangles")
    write(d, "model.obj", sphere_obj(1.0))
    case("obj_over_max_triangles", "model.obj", 1, args=["--max-triangles", "100"],
         err_has=["576 triangles, over the budget of 100", "--max-triangles"])

    d = os.path.join(root, "stl_over_max_triangles")
    facets = 2000
    stl = bytes(80) + struct.pack("<I", facets) + (struct.pack("<12fH", *([0.0] * 3),
                                                               0, 0, 0, 1, 0, 0, 0, 1, 0, 0)
                                                   * facets)
    write(d, "model.stl", stl)
    case("stl_over_max_triangles", "model.stl", 1, args=["--max-triangles", "1000"],
         err_has=["2000 facets, over the budget of 1000"])


def misreads(root):
    for name, index in (("obj_index_2pow32_plus_3", "4294967299"),
                        ("obj_index_20_digits", "99999999999999999999")):
        d = os.path.join(root, name)
        write(d, "model.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 " + index + "\n")
        case(name, "model.obj", 1, err_has=["model.obj:4: face index " + index +
                                            " is out of range"])

    d = os.path.join(root, "obj_nan_inf")
    write(d, "model.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv nan 0 0\nv 0 inf 0\nv 1 1 0\n"
          "f 1 2 3\nf 1 2 4\nf 2 3 5\nf 2 6 3\n")
    case("obj_nan_inf", "model.obj", 0,
         err_has=["2 triangles have a NaN or infinite vertex position"],
         out_has=["triangles:  4"])

    gltf_cases = {
        "gltf_node_mesh_2pow32": ({"nodes": [{"mesh": 4294967296}]}, "nodes[0].mesh is 4294967296"),
        "gltf_scene_node_2pow32": ({"scenes": [{"nodes": [4294967296]}]},
                                   "scenes[0].nodes[0] is 4294967296"),
        "gltf_view_buffer_2pow32": (None, "bufferViews[0].buffer is 4294967296"),
        "gltf_indices_2pow32": (None, "meshes[0].primitives[0].indices is 4294967297"),
        "gltf_sparse_count_2pow31": (None, "accessors[0].sparse.count is 2147483648"),
        "gltf_sparse_offset_2pow32": (None, "accessors[0].sparse.indices.byteOffset is 4294967296"),
    }
    for name, (top, message) in gltf_cases.items():
        doc, _ = gltf_triangle(extra_top=top)
        if name == "gltf_view_buffer_2pow32":
            doc["bufferViews"][0]["buffer"] = 4294967296
        if name == "gltf_indices_2pow32":
            doc["meshes"][0]["primitives"][0]["indices"] = 4294967297
        if name.startswith("gltf_sparse"):
            doc["accessors"][0]["sparse"] = {
                "count": 2147483648 if "count" in name else 1,
                "indices": {"bufferView": 1, "componentType": 5123,
                            "byteOffset": 4294967296 if "offset" in name else 0},
                "values": {"bufferView": 0}}
        write(os.path.join(root, name), "model.gltf", json.dumps(doc))
        case(name, "model.gltf", 1, err_has=[message, "out of range"],
             err_lacks=["-2147483648"])


def extremes(root):
    # Drawn with shading (not background, not one flat colour); info prints the true bounds.
    for name, scale, bound in (("obj_scale_1e10", 1e10, "max 1e+10,1e+10,"),
                               ("obj_scale_3e38", 3e38, "max 3e+38,3e+38,"),
                               ("obj_scale_1e-42", 1e-42, "e-42  size")):
        d = os.path.join(root, name)
        write(d, "model.obj", sphere_obj(scale))
        case(name, "model.obj", 0, drawn=True, out_has=[bound], err_lacks=["warning"],
             render_args=["--resolution", "160,120"])
    # With camera flags the model stays at its scale: a warning says why it may not be drawn.
    d = os.path.join(root, "obj_scale_3e38_camera")
    write(d, "model.obj", sphere_obj(3e38))
    case("obj_scale_3e38_camera", "model.obj", 0, commands=("render",),
         render_args=["--resolution", "160,120", "--camera-position", "0,0,1e30"],
         err_has=["the model spans", "cannot draw it reliably"])


def messages(root):
    # A buffer file shorter than its byteLength.
    d = os.path.join(root, "gltf_short_buffer")
    doc, data = gltf_triangle(buffer_uri="c.bin")
    write(d, "model.gltf", json.dumps(doc))
    write(d, "c.bin", data[:20])
    case("gltf_short_buffer", "model.gltf", 1,
         err_has=["buffer file 'c.bin' is 20 bytes, but the buffer's byteLength is 44"],
         err_lacks=["<tessera-model-folder>", "requestedBytes", "File size mismatch"])

    # An empty GLB binary chunk.
    d = os.path.join(root, "glb_empty_bin")
    doc, _ = gltf_triangle()
    doc["buffers"] = [{"byteLength": 44}]
    write(d, "model.glb", glb(doc, b""))
    case("glb_empty_bin", "model.glb", 1, err_has=["the binary chunk holds 0 bytes"],
         err_lacks=["Chunk1", "Must have"])

    # A malformed 1 MB data: URI: the message shows its start only.
    d = os.path.join(root, "gltf_huge_bad_data_uri")
    doc, _ = gltf_triangle(buffer_uri="data:application/octet-stream;base64," + "!" * (1 << 20))
    write(d, "model.gltf", json.dumps(doc))
    case("gltf_huge_bad_data_uri", "model.gltf", 1, err_has=["data:application/octet-stream"],
         err_lacks=["!" * 100])


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: make_hostile.py OUT_FOLDER")
    root = sys.argv[1]
    os.makedirs(root, exist_ok=True)
    for make in (hangs, bombs, misreads, extremes, messages):
        make(root)
    for c in CASES:
        c.setdefault("dir", c["name"])
    with open(os.path.join(root, "cases.json"), "w") as f:
        json.dump(CASES, f, indent=1)


if __name__ == "__main__":
    main()
