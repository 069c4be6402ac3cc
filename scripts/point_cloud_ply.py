#!/usr/bin/env python3
"""Writes a binary little-endian PLY point cloud (x y z float, red green blue uchar, no faces):
the input of the point-cloud load timing in docs/perf.md.

    scripts/point_cloud_ply.py OUT.ply [POINTS]     (default 10,000,000 points, 150 MB)
    time build/tessera info OUT.ply

The points fill a unit sphere's surface on a golden-angle spiral, coloured by position.
"""
import math
import struct
import sys


def main():
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    path = sys.argv[1]
    count = int(sys.argv[2]) if len(sys.argv) == 3 else 10_000_000
    header = (
        "ply\nformat binary_little_endian 1.0\n"
        f"element vertex {count}\n"
        "property float x\nproperty float y\nproperty float z\n"
        "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n"
    )
    record = struct.Struct("<fffBBB")
    golden = math.pi * (3 - math.sqrt(5))
    with open(path, "wb") as out:
        out.write(header.encode("ascii"))
        chunk = bytearray()
        for i in range(count):
            y = 1 - 2 * (i + 0.5) / count
            r = math.sqrt(max(0.0, 1 - y * y))
            x, z = r * math.cos(golden * i), r * math.sin(golden * i)
            chunk += record.pack(x, y, z, int(127.5 * (x + 1)), int(127.5 * (y + 1)),
                                 int(127.5 * (z + 1)))
            if len(chunk) > 1 << 22:
                out.write(chunk)
                chunk.clear()
        out.write(chunk)


if __name__ == "__main__":
    main()
