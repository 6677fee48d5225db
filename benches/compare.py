#!/usr/bin/env python3
"""Two or more builds of raytree on one scene, side by side: wall and user time, instructions.

The machines this project is measured on are shared and their load drifts between runs, so a
build is only ever compared with another in one batch: the builds take turns (the order
reversed every other round, so neither always runs first), and each round's times are divided
by the first build's in the same round. The medians of those ratios are what to quote.

Each build is copied into a fresh folder first and run from there (a binary run from where
the linker wrote it can run slower, docs/performance.md), and every build must render the
same image as the first to the byte: a faster build that draws something else is no faster.

Usage (from the project's directory):

    benches/compare.py [--runs N] [--instructions] SCENE BUILD BUILD... [-- RENDER_ARGS...]
    benches/compare.py --runs 15 benches/peers/csg.yaml /tmp/before target/release/raytree
    benches/compare.py benches/peers/whitted.yaml /tmp/a /tmp/b -- --threads 1

RENDER_ARGS go to `raytree render` after the scene and the output (default: `--threads 2`).
`--instructions` also counts each build's instructions under valgrind (cachegrind without
its cache model) at 400×300 on one thread, all builds at once: exact and free of the
machine's load, but not the same as time (docs/performance.md, "How to measure").
"""
import argparse
import filecmp
import re
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path


def render(binary: Path, scene: Path, out: Path, args: list[str]) -> tuple[float, float]:
    """One render: its wall and user time (the child's, from the kernel's accounting)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    subprocess.run([str(binary), "render", str(scene), "-o", str(out), *args], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, after.ru_utime - before.ru_utime


def instructions(binary: Path, scene: Path, out: Path) -> int:
    """Instructions of one render at 400×300 on one thread, as cachegrind counts them."""
    done = subprocess.run(
        ["valgrind", "--tool=cachegrind", "--cache-sim=no", "--cachegrind-out-file=/dev/null",
         str(binary), "render", str(scene), "-o", str(out), "--width", "400", "--height", "300",
         "--threads", "1"],
        check=True, capture_output=True, text=True)
    found = re.search(r"I\s+refs:\s+([\d,]+)", done.stderr)
    if found:
        return int(found.group(1).replace(",", ""))
    sys.exit(f"no instruction count from valgrind for {binary}:\n{done.stderr}")


def spread(values: list[float]) -> str:
    return f"{min(values):.3f}–{max(values):.3f}"


def main() -> None:
    argv = sys.argv[1:]
    extra = ["--threads", "2"]
    if "--" in argv:
        extra = argv[argv.index("--") + 1:]
        argv = argv[:argv.index("--")]
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--runs", type=int, default=11, help="rounds (default 11)")
    parser.add_argument("--instructions", action="store_true",
                        help="also count instructions under valgrind")
    parser.add_argument("scene", type=Path)
    parser.add_argument("builds", type=Path, nargs="+", metavar="build")
    opts = parser.parse_args(argv)
    if len(opts.builds) < 2:
        parser.error("give at least two builds to compare")
    if opts.runs < 1:
        parser.error("--runs must be at least 1")
    for build in opts.builds:
        if not build.is_file():
            parser.error(f"{build}: no such file")
    if not opts.scene.is_file():
        parser.error(f"{opts.scene}: no such file")
    if opts.instructions and shutil.which("valgrind") is None:
        sys.exit("valgrind not found (apt-get install -y valgrind)")

    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        copies = []
        for k, build in enumerate(opts.builds):
            folder = tmp / f"build{k}"
            folder.mkdir()
            copies.append(Path(shutil.copy2(build, folder / "raytree")))
        image = [tmp / f"image{k}.ppm" for k in range(len(copies))]

        # A warm-up round, which also checks that every build draws the first one's image.
        for k, binary in enumerate(copies):
            render(binary, opts.scene, image[k], extra)
        for k in range(1, len(copies)):
            if not filecmp.cmp(image[0], image[k], shallow=False):
                sys.exit(f"{opts.builds[k]} renders another image than {opts.builds[0]}: "
                         "not comparable")

        wall = [[] for _ in copies]
        user = [[] for _ in copies]
        for r in range(opts.runs):
            order = range(len(copies)) if r % 2 == 0 else reversed(range(len(copies)))
            for k in order:
                w, u = render(copies[k], opts.scene, image[k], extra)
                wall[k].append(w)
                user[k].append(u)

        counts = None
        if opts.instructions:
            with ThreadPoolExecutor(max_workers=len(copies)) as pool:
                counts = list(pool.map(
                    lambda k: instructions(copies[k], opts.scene, tmp / f"small{k}.ppm"),
                    range(len(copies))))

    print(f"{opts.scene}, {opts.runs} rounds, render {' '.join(extra)}; ratios are medians of "
          f"each round's time over {opts.builds[0]}'s in that round")
    print(f"{'build':<32} {'wall s':>8} {'ratio':>7} {'range':>13} {'user s':>8} {'ratio':>7}"
          f" {'range':>13}" + (f" {'instructions':>15} {'ratio':>7}" if counts else ""))
    for k, build in enumerate(opts.builds):
        rw = [a / b for a, b in zip(wall[k], wall[0])]
        ru = [a / b for a, b in zip(user[k], user[0])]
        row = (f"{str(build):<32} {statistics.median(wall[k]):>8.3f} {statistics.median(rw):>7.3f}"
               f" {spread(rw):>13} {statistics.median(user[k]):>8.3f}"
               f" {statistics.median(ru):>7.3f} {spread(ru):>13}")
        if counts:
            row += f" {counts[k]:>15,} {counts[k] / counts[0]:>7.4f}"
        print(row)


if __name__ == "__main__":
    main()
