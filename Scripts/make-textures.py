#!/usr/bin/env python3
"""Writes the project's own textures: scenes/Textures/*.bmp.

24-bit uncompressed BMP, rows bottom-up, as the course's textures are; no
library needed. Run from anywhere: python3 Scripts/make-textures.py
"""
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "..", "scenes", "Textures")


def write_bmp(path, width, height, pixel):
    """pixel(column, row) -> (r, g, b) bytes, row 0 at the image's top."""
    stride = (width * 3 + 3) // 4 * 4
    data = bytearray()
    for row in reversed(range(height)):  # bottom-up
        line = bytearray()
        for column in range(width):
            r, g, b = pixel(column, row)
            line += bytes((b, g, r))
        line += b"\0" * (stride - len(line))
        data += line
    header = struct.pack("<2sIHHI", b"BM", 54 + len(data), 0, 0, 54)
    info = struct.pack(
        "<IiiHHIIiiII", 40, width, height, 1, 24, 0, len(data), 2835, 2835,
        0, 0)
    with open(path, "wb") as f:
        f.write(header + info + data)


def checker(column, row):
    """8×8 squares, warm and cool, shaded left to right and top to bottom
    so that any flip of u or v shows."""
    light = ((column // 8) + (row // 8)) % 2 == 0
    fade = 0.55 + 0.45 * column / 63
    top = 0.6 + 0.4 * (63 - row) / 63
    if light:
        return (int(250 * fade), int(210 * top), 90)
    return (40, int(90 * top), int(200 * fade))


def crate(column, row):
    """A wooden crate's face: planks, a frame and a cross brace."""
    x, y = column / 63, row / 63
    frame = min(x, y, 1 - x, 1 - y) < 0.1
    brace = abs(x - y) < 0.07 or abs(x + y - 1) < 0.07
    plank = int(y * 5) % 2 == 0
    if frame or brace:
        return (120, 72, 30)
    return (205, 150, 80) if plank else (185, 130, 65)


if __name__ == "__main__":
    os.makedirs(OUT, exist_ok=True)
    write_bmp(os.path.join(OUT, "checker.bmp"), 64, 64, checker)
    write_bmp(os.path.join(OUT, "crate.bmp"), 64, 64, crate)
