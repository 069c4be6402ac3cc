#!/usr/bin/env python3
"""Writes the room that docs/make_images.sh renders as a 360-degree panorama and a fisheye: an OBJ
and its MTL (a checkered floor, four coloured walls open to the sky, pillars and, when a bunny OBJ is
given, the Stanford bunny on a plinth).

    docs/projection_room.py OUT_DIR [BUNNY_OBJ]
"""
import os
import sys

COLOURS = {
    "floor_a": (0.8, 0.8, 0.78), "floor_b": (0.15, 0.15, 0.17), "north": (0.75, 0.25, 0.2),
    "south": (0.2, 0.35, 0.75), "east": (0.25, 0.6, 0.3), "west": (0.85, 0.7, 0.25),
"pillar": (0.55, 0.5, 0.6), "bunny": (0.95, 0.95, 0.95),
}


class Obj:
    def __init__(self):
        self.lines, self.count = [], 0

    def quad(self, material, corners):
        """A quad, corners counter-clockwise as seen from the side it faces."""
        self.lines.append(f"usemtl {material}")
        for x, y, z in corners:
            self.lines.append(f"v {x:.4f} {y:.4f} {z:.4f}")
        n = self.count
        self.lines.append(f"f {n + 1} {n + 2} {n + 3} {n + 4}")
        self.count += 4

    def box(self, material, x0, y0, z0, x1, y1, z1):
        """An axis-aligned box facing out."""
        q = self.quad
        q(material, [(x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)])  # +Z
        q(material, [(x1, y0, z0), (x0, y0, z0), (x0, y1, z0), (x1, y1, z0)])  # -Z
        q(material, [(x1, y0, z1), (x1, y0, z0), (x1, y1, z0), (x1, y1, z1)])  # +X
        q(material, [(x0, y0, z0), (x0, y0, z1), (x0, y1, z1), (x0, y1, z0)])  # -X
        q(material, [(x0, y1, z1), (x1, y1, z1), (x1, y1, z0), (x0, y1, z0)])  # +Y


def room(obj, half=5.0, height=4.0, tiles=10):
    step = 2 * half / tiles
    for i in range(tiles):
        for j in range(tiles):
            x0, z0 = -half + i * step, -half + j * step
            x1, z1 = x0 + step, z0 + step
            obj.quad("floor_a" if (i + j) % 2 == 0 else "floor_b",
                     [(x0, 0, z1), (x1, 0, z1), (x1, 0, z0), (x0, 0, z0)])
    h, t = half, height
    obj.quad("north", [(-h, 0, -h), (h, 0, -h), (h, t, -h), (-h, t, -h)])  # faces +Z
    obj.quad("south", [(h, 0, h), (-h, 0, h), (-h, t, h), (h, t, h)])
    obj.quad("east", [(h, 0, -h), (h, 0, h), (h, t, h), (h, t, -h)])
    obj.quad("west", [(-h, 0, h), (-h, 0, -h), (-h, t, -h), (-h, t, h)])
    for x, z in ((-3, -3), (3, -3), (-3, 3), (3, 3)):
        obj.box("pillar", x - 0.3, 0, z - 0.3, x + 0.3, t, z + 0.3)


def bunny(obj, path, at=(0.0, 0.6, -2.0), size=1.6):
    obj.box("pillar", at[0] - 0.6, 0, at[2] - 0.6, at[0] + 0.6, at[1], at[2] + 0.6)
    vertices, faces = [], []
    with open(path) as f:
        for line in f:
            parts = line.split()
            if parts and parts[0] == "v":
                vertices.append(tuple(float(p) for p in parts[1:4]))
            elif parts and parts[0] == "f":
                faces.append([int(p.split("/")[0]) for p in parts[1:]])
    lo = [min(v[k] for v in vertices) for k in range(3)]
    hi = [max(v[k] for v in vertices) for k in range(3)]
    scale = size / max(hi[k] - lo[k] for k in range(3))
    centre = [(lo[k] + hi[k]) / 2 for k in range(3)]
    obj.lines.append("usemtl bunny")
    base = obj.count
    for v in vertices:
        x = (v[0] - centre[0]) * scale + at[0]
        y = (v[1] - lo[1]) * scale + at[1]
        z = (v[2] - centre[2]) * scale + at[2]
        obj.lines.append(f"v {x:.5f} {y:.5f} {z:.5f}")
    for face in faces:
        obj.lines.append("f " + " ".join(str(base + i) for i in face))
    obj.count += len(vertices)


def main():
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    obj = Obj()
    obj.lines.append("mtllib room.mtl")
    room(obj)
    if len(sys.argv) > 2 and os.path.exists(sys.argv[2]):
        bunny(obj, sys.argv[2])
    with open(os.path.join(out, "room.obj"), "w") as f:
        f.write("\n".join(obj.lines) + "\n")
    with open(os.path.join(out, "room.mtl"), "w") as f:
        for name, (r, g, b) in COLOURS.items():
            f.write(f"newmtl {name}\nKd {r} {g} {b}\n\n")


if __name__ == "__main__":
    main()
