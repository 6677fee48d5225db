#!/usr/bin/env python3
"""Whitted's picture by raytree and by POV-Ray 3.7: are the same checker cells in the same
places, in the same colours?

Renders lessons/examples/whitted-1980.yaml with raytree and benches/peers/whitted-1980.pov
with POV-Ray (640x480, one ray per pixel), projects the centre of every cell of the board into
the image, and where raytree's ray tree says the pixel sees the board directly, compares the
cell's colour in both images (yellow or red: which of the two the pixel is nearer in hue) with
the cell raytree's checker gives it. Cells in the spheres' shadows are listed apart: POV-Ray
lets light through the glass sphere (a filtered shadow), raytree's shadow rays stop at it.

Usage: python3 benches/peers/whitted_1980.py   (from anywhere; needs povray and a release
build: cargo build --release)
"""
import json
import math
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
RAYTREE = os.path.join(ROOT, "target", "release", "raytree")
SCENE = os.path.join(ROOT, "lessons", "examples", "whitted-1980.yaml")
POV = os.path.join(HERE, "whitted-1980.pov")
W, H = 640, 480
# The camera of both files: POV-Ray's horizontal angle 52 is a vertical fov of 40.185°.
EYE, LOOK_AT, FOV = (0.0, 2.4, -5.5), (0.3, 0.9, 3.0), 40.185
YELLOW, RED = (0.95, 0.85, 0.15), (0.85, 0.12, 0.1)


def sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def unit(a):
    n = math.sqrt(dot(a, a))
    return tuple(x / n for x in a)


def project(p):
    """The pixel whose centre's ray passes through p (left-handed: +x right, looking +z)."""
    w = unit(sub(LOOK_AT, EYE))
    u = unit(cross((0.0, 1.0, 0.0), w))
    v = cross(w, u)
    d = sub(p, EYE)
    half = math.tan(math.radians(FOV) / 2)
    x = dot(d, u) / dot(d, w) / (half * W / H)
    y = dot(d, v) / dot(d, w) / half
    return round((x + 1) / 2 * W - 0.5), round((1 - y) / 2 * H - 0.5)


def read_ppm(path):
    """A binary PPM (P6, 8 bits): a function (x, y) -> (r, g, b) in 0..255."""
    data = open(path, "rb").read()
    fields, i = [], 0
    while len(fields) < 4:
        while data[i:i + 1].isspace():
            i += 1
        if data[i:i + 1] == b"#":
            while data[i:i + 1] != b"\n":
                i += 1
            continue
        j = i
        while not data[j:j + 1].isspace():
            j += 1
        fields.append(data[i:j])
        i = j
    assert fields[0] == b"P6" and int(fields[3]) == 255, fields
    width = int(fields[1])
    pixels = data[i + 1:]
    return lambda x, y: tuple(pixels[3 * (y * width + x):3 * (y * width + x) + 3])


def hue_class(rgb):
    """Yellow or red: the board's two colours differ most in green against red."""
    r, g, _ = rgb
    return "yellow" if g > 0.5 * r else "red"


def main():
    out = tempfile.mkdtemp()
    ours, theirs = os.path.join(out, "raytree.ppm"), os.path.join(out, "povray.ppm")
    subprocess.run([RAYTREE, "render", SCENE, "-o", ours, "--spp", "1"], check=True)
    subprocess.run(["povray", "-D", "-V", "+I" + POV, "+O" + theirs, "+FP", f"+W{W}",
                    f"+H{H}", "-A", "+WT2"], check=True, capture_output=True)
    a, b = read_ppm(ours), read_ppm(theirs)
    lit, shadowed, disagree = [], [], []
    for i in range(-4, 4):
        for j in range(-1, 9):
            centre = (i + 0.5, 0.0, j + 0.5)
            x, y = project(centre)
            if not (0 <= x < W and 0 <= y < H):
                continue
            tree = json.loads(subprocess.run(
                [RAYTREE, "inspect", SCENE, "--pixel", f"{x},{y}", "--format", "json"],
                check=True, capture_output=True, text=True).stdout)["tree"]
            hit = tree["hit"]
            if hit is None or hit["object"] != "board":
                continue
            assert math.dist(hit["point"], centre) < 0.1, (centre, hit["point"])
            color = tree["local"]["color"]
            cell = "yellow" if math.dist(color, YELLOW) < 1e-9 else "red"
            assert cell == ("yellow" if (i + j) % 2 == 0 else "red"), (i, j, color)
            shadow = tree["local"]["lights"][0]["shadow"]
            pa, pb = a(x, y), b(x, y)
            row = (i, j, x, y, cell, hue_class(pa), hue_class(pb), pa, pb)
            (lit if shadow == 1 else shadowed).append(row)
            if not (cell == hue_class(pa) == hue_class(pb)):
                disagree.append(row)
    print(f"{'cell':>8} {'pixel':>10} {'checker':>8} {'raytree':>16} {'POV-Ray':>16}")
    for rows, label in ((lit, "lit"), (shadowed, "in shadow")):
        for i, j, x, y, cell, _, _, pa, pb in rows:
            print(f"{i:>3},{j:>3}  {x:>4},{y:>4} {cell:>8} {str(pa):>16} {str(pb):>16}  {label}")
    diff = lambda rows: max((max(abs(p - q) for p, q in zip(r[7], r[8])) for r in rows), default=0)
    print(f"{len(lit)} lit cells and {len(shadowed)} in shadow compared: "
          f"{len(lit) + len(shadowed) - len(disagree)} in the same colour in both images and "
          f"raytree's checker; largest difference of a channel (0..255): lit {diff(lit)}, "
          f"in shadow {diff(shadowed)}")
    print(f"images in {out}")
    return 1 if disagree else 0


if __name__ == "__main__":
    sys.exit(main())
