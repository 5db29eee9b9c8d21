#!/usr/bin/env python3
"""Checks a `raytrace report --plot` picture as a browser drew it.

Usage: check-plot.py PLOT.svg ROWS.csv SCREENSHOT.png

PLOT.svg and ROWS.csv come from one `raytrace report --plot --csv` run;
SCREENSHOT.png is headless Chromium's rendering of PLOT.svg at its size.
The SVG must be well formed XML; every CSV row must have one mark, placed
where the panel's stated axes put the row's numbers (time in ms across,
largest relative error of t up, 0 on the panel's "0" line); and the
screenshot must show the mark's colour there. A mark hidden under a later
mark drawn within 9 pixels counts as covered, not missing."""
import csv
import math
import struct
import sys
import xml.etree.ElementTree as ET
import zlib

NS = "{http://www.w3.org/2000/svg}"
COLOURS = {"course": (0x1B, 0x9E, 0x77), "float": (0x1F, 0x77, 0xB4),
           "double": (0xD9, 0x5F, 0x02)}


def read_png(path):
    """(width, height, rows of (r, g, b)) of an 8-bit, non-interlaced PNG."""
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
    width, height, depth, colour, _, _, interlace = header
    assert depth == 8 and interlace == 0 and colour in (2, 6), header
    channels = 3 if colour == 2 else 4
    raw = zlib.decompress(idat)
    stride = width * channels
    rows, previous = [], bytearray(stride)
    for y in range(height):
        start = y * (stride + 1)
        kind, line = raw[start], bytearray(raw[start + 1:start + 1 + stride])
        for i in range(stride):
            a = line[i - channels] if i >= channels else 0
            b = previous[i]
            c = previous[i - channels] if i >= channels else 0
            if kind == 1:
                line[i] = (line[i] + a) & 255
            elif kind == 2:
                line[i] = (line[i] + b) & 255
            elif kind == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                pred = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                line[i] = (line[i] + pred) & 255
        rows.append([tuple(line[x * channels:x * channels + 3])
                     for x in range(width)])
        previous = line
    return width, height, rows


def axis(text):
    lowest, highest, start, end = (float(v) for v in text.split())
    return lambda value: start + (end - start) * (
        (math.log10(value) - lowest) / (highest - lowest))


def main(svg_path, csv_path, png_path):
    root = ET.parse(svg_path).getroot()  # raises on malformed XML
    panel = next(
        g for g in root.iter(NS + "g")
        if g.get("data-panel") == "error" and g.get("class") == "panel")
    to_x, to_y = axis(panel.get("data-x-axis")), axis(panel.get("data-y-axis"))
    zero_y = panel.get("data-zero-y")
    marks = {}
    for g in root.iter(NS + "g"):
        if g.get("class") == "mark" and g.get("data-panel") == "error":
            key = (g.get("data-scene"), g.get("data-precision"),
                   g.get("data-method"))
            x, y = g.get("transform")[len("translate("):-1].split()
            marks[key] = (float(x), float(y))
    rows = list(csv.DictReader(open(csv_path)))
    width, height, pixels = read_png(png_path)
    expected = []
    for row in rows:
        key = (row["scene"], row["precision"], row["method"])
        error = float(row["max_rel_error"])
        x = to_x(float(row["seconds"]) * 1000)
        y = float(zero_y) if error == 0 else to_y(error)
        assert key in marks, f"no mark for {key}"
        mx, my = marks[key]
        assert abs(mx - x) <= 0.01 and abs(my - y) <= 0.01, (
            f"{key}: mark at ({mx}, {my}), its numbers put it at ({x}, {y})")
        colour = COLOURS["course" if row["method"] == "course"
                         else row["precision"]]
        expected.append((key, x, y, colour))
    assert len(marks) == len(rows), f"{len(marks)} marks for {len(rows)} rows"
    drawn_order = [k for k in marks]  # document order: later ones on top
    seen = covered = 0
    for key, x, y, colour in expected:
        found = False
        for dy in range(-3, 4):
            for dx in range(-3, 4):
                px, py = round(x) + dx, round(y) + dy
                inside = 0 <= px < width and 0 <= py < height
                if inside and all(abs(a - b) <= 40
                                  for a, b in zip(pixels[py][px], colour)):
                    found = True
        if found:
            seen += 1
            continue
        later = drawn_order[drawn_order.index(key) + 1:]
        near = [k for k in later if math.dist(marks[k], (x, y)) <= 9]
        assert near, f"{key}: no mark of its colour near ({x:.1f}, {y:.1f})"
        covered += 1
    print(f"plot: {len(rows)} rows, {seen} marks seen where their numbers put "
          f"them, {covered} covered by later marks")
    assert seen >= len(rows) // 2, "most marks should be visible"


if __name__ == "__main__":
    main(*sys.argv[1:4])
