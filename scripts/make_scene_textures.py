#!/usr/bin/env python3
"""Writes the image textures of the example scenes (scenes/textures/*.png).

Pure standard library (zlib + struct), so the PNGs can be regenerated anywhere:
    python3 scripts/make_scene_textures.py
porcelain.png: 256 x 256 sRGB, a blue-on-white tile pattern (rings, a border and a diamond) that
shows the (u, v) parametrisation of each patch and its orientation (the corner u = v = 0 gets
a small red square).
"""
import math
import os
import struct
import zlib


def png(path, width, height, rows):
    raw = b"".join(b"\x00" + bytes(r) for r in rows)

    def chunk(tag, data):
        c = struct.pack(">I", len(data)) + tag + data
        return c + struct.pack(">I", zlib.crc32(tag + data) & 0xFFFFFFFF)

    data = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
    data += chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")
    tmp = path + ".tmp"
    with open(tmp, "wb") as f:
        f.write(data)
    os.replace(tmp, path)


def porcelain(n=256):
    white, blue, red = (245, 243, 236), (28, 60, 150), (200, 30, 30)
    rows = []
    for y in range(n):
        row = []
        v = (y + 0.5) / n  # image rows are top first: v = 1 at the top row
        v = 1.0 - v
        for x in range(n):
            u = (x + 0.5) / n
            du, dv = u - 0.5, v - 0.5
            r = math.hypot(du, dv)
            c = white
            if min(u, v, 1 - u, 1 - v) < 0.04:
                c = blue
            elif abs(abs(du) + abs(dv) - 0.42) < 0.025:
                c = blue
            elif abs(r - 0.22) < 0.02 or abs(r - 0.12) < 0.012 or r < 0.04:
                c = blue
            elif abs(math.sin(8 * math.atan2(dv, du)) * 0.05 + 0.30 - r) < 0.012:
                c = blue
            if u < 0.12 and v < 0.12 and min(u, v) >= 0.04:
                c = red
            row.extend(c)
        rows.append(row)
    return rows


if __name__ == "__main__":
    here = os.path.dirname(os.path.abspath(__file__))
    out = os.path.join(here, "..", "scenes", "textures")
    os.makedirs(out, exist_ok=True)
    png(os.path.join(out, "porcelain.png"), 256, 256, porcelain())
