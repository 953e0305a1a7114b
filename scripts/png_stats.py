#!/usr/bin/env python3
"""Checks that a screenshot is a WIDTHxHEIGHT 8-bit RGB PNG with real content: the standard
deviation of its luminance (on 0-255, sampled every 8th row and column) is above 8, well above
that of a uniform or nearly uniform image (a sky-and-sea frame has about 40).

usage: png_stats.py FILE WIDTH HEIGHT LABEL   (standard library only: CI runs it as it is)"""
import struct, sys, zlib

path, want_width, want_height, label = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4]
data = open(path, "rb").read()
assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
pos, idat, header = 8, b"", None
while pos < len(data):
    length, kind = struct.unpack(">I4s", data[pos:pos + 8])
    body = data[pos + 8:pos + 8 + length]
    if kind == b"IHDR":
        header = struct.unpack(">IIBBBBB", body)
    elif kind == b"IDAT":
        idat += body
    pos += 12 + length
width, height, depth, colour = header[:4]
assert (width, height, depth, colour) == (want_width, want_height, 8, 2), header
raw = zlib.decompress(idat)
stride = 3 * width
rows, previous = [], bytearray(stride)
for y in range(height):
    kind = raw[y * (stride + 1)]
    line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
    for x in range(stride):
        a = line[x - 3] if x >= 3 else 0
        b = previous[x]
        c = previous[x - 3] if x >= 3 else 0
        if kind == 1: line[x] = (line[x] + a) & 255
        elif kind == 2: line[x] = (line[x] + b) & 255
        elif kind == 3: line[x] = (line[x] + (a + b) // 2) & 255
        elif kind == 4:
            p = a + b - c
            pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
            line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
    rows.append(line)
    previous = line
lum = [0.299 * r[x] + 0.587 * r[x + 1] + 0.114 * r[x + 2] for r in rows[::8] for x in range(0, stride, 24)]
mean = sum(lum) / len(lum)
sd = (sum((v - mean) ** 2 for v in lum) / len(lum)) ** 0.5
print(f"{label} screenshot: {width}x{height}, luminance mean {mean:.1f}, standard deviation {sd:.1f}")
assert sd > 8.0, "the screenshot is (nearly) uniform"
