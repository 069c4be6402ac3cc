#!/usr/bin/env python3
# The CRC-32 that `tessera render --crc` prints, computed from a written PNG with the standard
# library alone: zlib.crc32 of the pixels as R, G, B, A bytes, rows top to bottom (alpha 255 for an
# RGB PNG). Usage: png_crc32.py FILE.png  (8-bit RGB or RGBA, not interlaced: what tessera writes).
import struct, sys, zlib

def png_rgba_crc(path):
    """zlib.crc32 of an 8-bit RGB or RGBA PNG's pixels as R, G, B, A bytes, rows top to bottom."""
    data = open(path, "rb").read()
    pos, idat = 8, b""
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour = struct.unpack(">IIBB", body[:10])
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    assert depth == 8 and colour in (2, 6), "tessera writes 8-bit RGB (or RGBA)"
    bpp = 3 if colour == 2 else 4
    raw, stride, prev, crc = zlib.decompress(idat), width * bpp, bytearray(width * bpp), 0
    for y in range(height):
        kind, row = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a, b = row[i - bpp] if i >= bpp else 0, prev[i]
            c = prev[i - bpp] if i >= bpp else 0
            p = a + b - c
            pred = [0, a, b, (a + b) // 2,
                    a if abs(p - a) <= abs(p - b) and abs(p - a) <= abs(p - c) else b if abs(p - b) <= abs(p - c) else c][kind]
            row[i] = (row[i] + pred) & 255
        rgba = row if bpp == 4 else bytearray(b for x in range(width) for b in (*row[3 * x:3 * x + 3], 255))
        crc, prev = zlib.crc32(rgba, crc), row
    return crc

print(f"{png_rgba_crc(sys.argv[1]):08x}")
