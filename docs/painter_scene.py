#!/usr/bin/env python3
"""Writes the OBJ scenes of docs/images/painter.png and edges.png into a folder.

blade.obj: a quad-faced sphere pierced by a tilted blade (one quad): where they cross, the
z-buffer cuts the blade along the sphere and the painter's algorithm cannot.
shapes.obj: the same sphere beside a cube, for --edges (quads, triangles only at the poles).
"""
import math
import sys
from pathlib import Path


def sphere(out, first, cx, cy, cz, r, segments=16, rings=10):
    """Appends a latitude-longitude sphere of quads (triangles at the poles); returns the next
    vertex number."""
    ring_start = []
    n = first
    out.append(f"v {cx:.6f} {cy + r:.6f} {cz:.6f}")
    top = n
    n += 1
    for i in range(1, rings):
        phi = math.pi * i / rings
        ring_start.append(n)
        for j in range(segments):
            theta = 2 * math.pi * j / segments
            out.append(f"v {cx + r * math.sin(phi) * math.cos(theta):.6f} "
                       f"{cy + r * math.cos(phi):.6f} {cz - r * math.sin(phi) * math.sin(theta):.6f}")
            n += 1
    out.append(f"v {cx:.6f} {cy - r:.6f} {cz:.6f}")
    bottom = n
    n += 1
    for j in range(segments):
        k = (j + 1) % segments
        out.append(f"f {top} {ring_start[0] + j} {ring_start[0] + k}")
        for i in range(rings - 2):
            a, b = ring_start[i], ring_start[i + 1]
            out.append(f"f {a + j} {b + j} {b + k} {a + k}")
        last = ring_start[-1]
        out.append(f"f {last + j} {bottom} {last + k}")
    return n


def cube(out, first, cx, cy, cz, h):
    corners = [(x, y, z) for x in (-h, h) for y in (-h, h) for z in (-h, h)]
    for x, y, z in corners:
        out.append(f"v {cx + x:.6f} {cy + y:.6f} {cz + z:.6f}")
    # Counter-clockwise from outside; corner index = 4 * (x > 0) + 2 * (y > 0) + (z > 0).
    for face in ((0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)):
        out.append("f " + " ".join(str(first + c) for c in face))
    return first + 8


def main():
    folder = Path(sys.argv[1])
    folder.mkdir(parents=True, exist_ok=True)
    lines = []
    n = sphere(lines, 1, 0, 0, 0, 1)
    # The blade: a quad through the sphere's centre at 45 degrees, out of its front on the right.
    blade = [(-2, -0.3, -2), (2, -0.3, 2), (2, 0.3, 2), (-2, 0.3, -2)]
    for x, y, z in blade:
        lines.append(f"v {x} {y} {z}")
    lines.append(f"f {n} {n + 1} {n + 2} {n + 3}")
    (folder / "blade.obj").write_text("\n".join(lines) + "\n")
    lines = []
    n = sphere(lines, 1, -1.2, 0, 0, 1)
    cube(lines, n, 1.3, 0, 0, 0.8)
    (folder / "shapes.obj").write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
