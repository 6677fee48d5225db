#!/usr/bin/env python3
"""Mitsuba 3's Cornell box at several sample counts: in-process render time and RMSE against
the 4096-spp reference in ../shared/peers (linear RGB, all pixels and channels).

Usage: python3 benches/peers/cornell_mitsuba.py [--reference=EXR] VARIANT SPP [SPP ...]
(pip install mitsuba numpy; llvm_ad_rgb also needs an LLVM shared library.) --reference compares
against another image, such as the one cornell_reference.py renders."""
import sys
import time

import mitsuba as mi
import numpy as np

args = sys.argv[1:]
ref_path = __file__.rsplit("/", 3)[0] + "/../shared/peers/cornell-mitsuba-4096spp.exr"
if args and args[0].startswith("--reference="):
    ref_path = args.pop(0).split("=", 1)[1]
variant = args[0]
mi.set_variant(variant)
reference = np.array(mi.Bitmap(ref_path), dtype=np.float64)[..., :3]
scene = mi.load_dict(mi.cornell_box())
for spp in map(int, args[1:]):
    mi.render(scene, spp=spp, seed=1)  # warm-up (JIT compilation for llvm variants)
    times = []
    for run in range(3):
        start = time.perf_counter()
        image = np.array(mi.render(scene, spp=spp, seed=run + 2), dtype=np.float64)[..., :3]
        times.append(time.perf_counter() - start)
    seconds = sorted(times)[1]
    rmse = float(np.sqrt(np.mean((image - reference) ** 2)))
    print(f"mitsuba {variant} spp {spp} seconds {seconds:.3f} rmse {rmse:.5f} "
          f"efficiency {1.0 / (seconds * rmse * rmse):.0f}", flush=True)
