#!/usr/bin/env python3
"""A second reference for the Cornell box, and the light's edges in any of its images.

    python3 benches/peers/cornell_reference.py render OUT.exr [RUNS]
        Mitsuba 3 llvm_ad_rgb, RUNS (default 4) independent runs of 4096 samples per pixel
        (seeds 1 … RUNS, each in 16 passes of 256), averaged: RUNS·4096 spp, written as EXR.
        About a minute a run on 2 cores. pip install mitsuba numpy; needs libLLVM (apt-get install
        libllvm19; DRJIT_LIBLLVM_PATH=/usr/lib/x86_64-linux-gnu/libLLVM-19.so).

    python3 benches/peers/cornell_reference.py edges IMAGE.exr [IMAGE.exr ...]
        The rows across the light's near (upper) and far (lower) edges, each averaged along
        the edge, beside the value a Gaussian-filtered step predicts there (Mitsuba's filter:
        σ = 0.5 px, radius 2 px; the edges' rows from the camera: eye (0, 0, 3.9), vertical
        field of view 39.3077°, the light at y = 0.99 from z = −0.18 to 0.20).

    python3 benches/peers/cornell_reference.py errors REFERENCE.exr IMAGE.exr [IMAGE.exr ...]
        Where each image's squared error against the reference lies: its RMSE, the shares of
        the squared error in the light (pixels the reference shows brighter than 2), in the
        light and the 4 pixels around it, and in the worst 0.1 % and 1 % of pixels, and the
        mean signed error of each channel (a bias shows there; noise averages out).
"""
import math
import sys

import mitsuba as mi
import numpy as np

SIZE = 256
TAN = math.tan(math.radians(39.3077) / 2)
LIGHT = 13.154  # the light's mean radiance over r, g, b, as the images show it


def edge_row(y, z):
    """The image row (continuous, 0 at the top) where the point (·, y, z) projects."""
    return (1 - y / (3.9 - z) / TAN) * SIZE / 2


def filtered_step(c, lo, hi, inside, outside):
    """A pixel centred at row c under the Gaussian filter, the light covering rows lo..hi."""
    sigma, r = 0.5, 2.0
    x = np.linspace(-r, r, 400001)
    f = np.exp(-x * x / (2 * sigma * sigma)) - math.exp(-r * r / (2 * sigma * sigma))
    y = c + x
    lit = (y > lo) & (y < hi)
    return float((f * np.where(lit, inside, outside)).sum() / f.sum())


def render(out, runs):
    mi.set_variant("llvm_ad_rgb")
    scene = mi.load_dict(mi.cornell_box())
    total = None
    for seed in range(1, runs + 1):
        for k in range(16):
            image = np.array(mi.render(scene, spp=256, seed=seed * 1000 + k), dtype=np.float64)
            total = image[..., :3] if total is None else total + image[..., :3]
        print(f"run {seed} of {runs}", flush=True)
    mean = (total / (16 * runs)).astype(np.float32)
    mi.Bitmap(mean, pixel_format=mi.Bitmap.PixelFormat.RGB).write(out)


def edges(paths):
    mi.set_variant("scalar_rgb")
    near, far = edge_row(0.99, 0.20), edge_row(0.99, -0.18)
    rows = list(range(int(near) - 2, int(near) + 2)) + list(range(int(far) - 1, int(far) + 3))
    columns = slice(110, 146)  # well inside the light's width, away from its corners
    images = [np.array(mi.Bitmap(p), dtype=np.float64)[..., :3].mean(-1) for p in paths]
    print(f"near edge at row {near:.3f}, far edge at row {far:.3f} (pixel k spans k .. k+1)")
    print("row  filtered step  " + "  ".join(p.rsplit("/", 1)[-1][:18].rjust(18) for p in paths))
    for row in rows:
        # The ceiling's own brightness beside each edge, from rows the filter does not reach.
        beside = int(near) - 3 if abs(row - near) < abs(row - far) else int(far) + 3
        outside = images[0][beside, columns].mean()
        step = filtered_step(row + 0.5, near, far, LIGHT, outside)
        values = "  ".join(f"{im[row, columns].mean():18.3f}" for im in images)
        print(f"{row:3d}  {step:13.3f}  {values}")


def errors(reference_path, paths):
    mi.set_variant("scalar_rgb")
    reference = np.array(mi.Bitmap(reference_path), dtype=np.float64)[..., :3]
    light = reference.mean(-1) > 2
    # The light and every pixel within 4 of it (a 9 × 9 neighbourhood touches the light).
    padded = np.pad(light, 4)
    around = np.zeros_like(light)
    for dy in range(9):
        for dx in range(9):
            around |= padded[dy:dy + SIZE, dx:dx + SIZE]
    print(f"light: {light.sum()} pixels; light and 4 around: {around.sum()} pixels")
    print(f"{'image':>18} {'RMSE':>8} {'light':>6} {'+4 px':>6} {'0.1 %':>6} {'1 %':>6}  mean error r, g, b")
    for path in paths:
        image = np.array(mi.Bitmap(path), dtype=np.float64)[..., :3]
        squared = ((image - reference) ** 2).mean(-1)
        total = squared.sum()
        worst = np.sort(squared.ravel())[::-1]
        share = lambda k: worst[:k].sum() / total
        bias = ", ".join(f"{b:+.1e}" for b in (image - reference).mean((0, 1)))
        print(f"{path.rsplit('/', 1)[-1][:18]:>18} {math.sqrt(squared.mean()):8.5f} "
              f"{squared[light].sum() / total:6.2f} {squared[around].sum() / total:6.2f} "
              f"{share(squared.size // 1000):6.2f} {share(squared.size // 100):6.2f}  {bias}")


if __name__ == "__main__":
    if len(sys.argv) >= 3 and sys.argv[1] == "render":
        render(sys.argv[2], int(sys.argv[3]) if len(sys.argv) > 3 else 4)
    elif len(sys.argv) >= 3 and sys.argv[1] == "edges":
        edges(sys.argv[2:])
    elif len(sys.argv) >= 4 and sys.argv[1] == "errors":
        errors(sys.argv[2], sys.argv[3:])
    else:
        sys.exit(__doc__)
