#!/usr/bin/env python3
"""Writes a UV sphere as a Wavefront OBJ with normals: the triangle-count sweep of run_all.sh.

usage: bench/sphere_obj.py K PATH    (2K segments, K + 1 rings: 4 K^2 triangles, as makeUvSphere)
"""
import math
import sys


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    k, path = int(sys.argv[1]), sys.argv[2]
    segments, rings = 2 * k, k + 1
    with open(path, "w") as f:
        for r in range(rings + 1):
            theta = math.pi * r / rings
            for s in range(segments + 1):
                phi = 2 * math.pi * s / segments
                n = (math.sin(theta) * math.sin(phi), math.cos(theta),
                     math.sin(theta) * math.cos(phi))
                f.write("v %.6f %.6f %.6f\nvn %.6f %.6f %.6f\n" % (n + n))
        stride = segments + 1
        for r in range(rings):
            for s in range(segments):
                a = r * stride + s + 1  # OBJ indices start at 1
                b, c = a + 1, a + stride
                d = c + 1
                # Counter-clockwise seen from outside; no slivers at the poles.
                if r != 0:
                    f.write("f %d//%d %d//%d %d//%d\n" % (a, a, c, c, b, b))
                if r != rings - 1:
                    f.write("f %d//%d %d//%d %d//%d\n" % (b, b, c, c, d, d))


if __name__ == "__main__":
    main()
