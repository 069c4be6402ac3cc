#!/usr/bin/env python3
"""Writes a small equirectangular sky as a Radiance .hdr (flat RGBE scanlines), for the docs'
environment-light pictures: a blue sky brightening to the horizon, a warm low sun, and a grey
ground. Usage: sky_hdr.py OUT.hdr [WIDTH]"""
import math
import struct
import sys


def rgbe(r, g, b):
    top = max(r, g, b)
    if top < 1e-32:
        return b"\0\0\0\0"
    mantissa, exponent = math.frexp(top)
    scale = mantissa * 256.0 / top
    return bytes((int(r * scale), int(g * scale), int(b * scale), exponent + 128))


def radiance(direction, sun):
    x, y, z = direction
    if y < 0:  # the ground: a grey that darkens a little towards the nadir
        shade = 0.15 + 0.05 * (1 + y)
        return (shade * 0.9, shade * 0.85, shade * 0.8)
    horizon = (1 - y) ** 3
    sky = (0.12 + 0.3 * horizon, 0.22 + 0.25 * horizon, 0.45 + 0.1 * horizon)
    cosine = x * sun[0] + y * sun[1] + z * sun[2]
    glow = 60.0 if cosine > math.cos(math.radians(3)) else 0.0
    return (sky[0] + glow, sky[1] + glow * 0.92, sky[2] + glow * 0.8)


def main():
    out = sys.argv[1]
    width = int(sys.argv[2]) if len(sys.argv) > 2 else 256
    height = width // 2
    elevation, azimuth = math.radians(30), math.radians(40)
    sun = (math.cos(elevation) * math.sin(azimuth), math.sin(elevation),
           -math.cos(elevation) * math.cos(azimuth))
    rows = []
    for j in range(height):
        theta = math.pi * (j + 0.5) / height  # 0 at the zenith
        for i in range(width):
            phi = 2 * math.pi * (i + 0.5) / width - math.pi
            direction = (math.sin(theta) * math.sin(phi), math.cos(theta),
                         -math.sin(theta) * math.cos(phi))
            rows.append(rgbe(*radiance(direction, sun)))
    with open(out, "wb") as f:
        f.write(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n")
        f.write(f"-Y {height} +X {width}\n".encode())
        f.write(b"".join(rows))


if __name__ == "__main__":
    main()
