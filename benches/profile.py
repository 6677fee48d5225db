#!/usr/bin/env python3
"""Where a render's time goes, by raytree function, through the inlined code.

The release build inlines most of the fast wing into a few large functions (each entry point
of the wing, in the copy for the processor's instructions), so `perf report --sort sym` names
little more than `<Avx as F64x4>::outlined::copy`. This script maps every sampled address
through `addr2line -i`, which lists the chain of functions inlined at that address, and
counts each sample twice over:

- self: for the innermost raytree function of the chain, passing over the lanes'
  one-instruction helpers (`fast/simd.rs`, glam, core);
- inclusive: for every raytree function on the chain, once per sample: the share of the time
  spent in that step and everything it calls, as a flame graph would show it.

Usage (from the project's directory, with a release build):

    benches/profile.py [--top N] [--data FILE] -- RAYTREE_ARGS...
    benches/profile.py --top 30 -- render benches/peers/whitted.yaml -o /tmp/w.png --threads 2
    benches/profile.py --data perf.data          (an existing recording of target/release/raytree)

Needs perf (`-e cpu-clock`, 8 000 samples a second: virtual machines have no cycle counter)
and binutils' addr2line.
"""
import argparse
import collections
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

BINARY = Path(__file__).resolve().parent.parent / "target" / "release" / "raytree"
# Lane helpers and library code: a sample in them counts (for self) toward the raytree
# function that called them.
HELPER = re.compile(r"fast/simd\.rs|/glam-|/rustc/|/core_arch/|/arrayvec-|/wide-")


def record(args: list[str], data: Path) -> None:
    subprocess.run(
        ["perf", "record", "-q", "-F", "8000", "-e", "cpu-clock", "-o", str(data), "--",
         str(BINARY), *args],
        check=True, stdout=subprocess.DEVNULL)


def samples(data: Path) -> tuple[collections.Counter, int]:
    """Sampled addresses inside the binary (as offsets addr2line takes), and all samples."""
    script = subprocess.run(
        ["perf", "script", "-i", str(data), "-F", "ip,dso", "--show-mmap-events"],
        check=True, capture_output=True, text=True).stdout
    load = None
    for line in script.splitlines():
        if "PERF_RECORD_MMAP" in line and "r-xp" in line and line.rstrip().endswith(BINARY.name):
            start, pgoff = re.search(r"\[0x([0-9a-f]+)\(0x[0-9a-f]+\) @ 0x([0-9a-f]+)", line).groups()
            load = int(start, 16) - int(pgoff, 16)
            break
    if load is None:
        sys.exit(f"no samples of {BINARY} in {data}")
    # Addresses in the file are the segment's virtual addresses, not its file offsets.
    for line in subprocess.run(["readelf", "-lW", str(BINARY)], check=True,
                               capture_output=True, text=True).stdout.splitlines():
        f = line.split()
        if f and f[0] == "LOAD" and "E" in f[-2]:
            load -= int(f[2], 16) - int(f[1], 16)
            break
    counts, total = collections.Counter(), 0
    for line in script.splitlines():
        parts = line.split()
        if len(parts) != 2 or "PERF_RECORD" in line:
            continue
        total += 1
        if BINARY.name in parts[1]:
            counts[int(parts[0], 16) - load] += 1
    return counts, total


def chains(addresses: list[int]) -> list[list[tuple[str, str]]]:
    """For each address, its inlined chain, innermost first: (function, file:line)."""
    # A zero address after each one marks where its chain ends (addr2line answers "??").
    query = "".join(f"0x{a:x}\n0x0\n" for a in addresses)
    out = subprocess.run(["addr2line", "-i", "-f", "-C", "-e", str(BINARY)], input=query,
                         check=True, capture_output=True, text=True).stdout.splitlines()
    result, chain = [], []
    for function, place in zip(out[::2], out[1::2]):
        if function == "??" and place.startswith("??:"):
            result.append(chain)
            chain = []
        else:
            chain.append((function, place))
    return result


def name(function: str) -> str:
    """A function's path without generic arguments, its closures counted as itself:
    `raytree::fast::light_lanes::toward`."""
    while True:
        shorter = re.sub(r"<[^<>]*>", "", function)
        if shorter == function:
            function = function.replace("::{{closure}}", "")
            return re.sub(r"::+", "::", function).strip(":")
        function = shorter


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--top", type=int, default=25, help="rows of each table")
    parser.add_argument("--data", type=Path, help="an existing perf.data to read")
    parser.add_argument("args", nargs="*", help="raytree's arguments (after --)")
    opts = parser.parse_args()
    for tool in ("perf", "addr2line", "readelf"):
        if shutil.which(tool) is None:
            sys.exit(f"{tool} not found (apt-get install -y linux-perf binutils)")
    if not BINARY.exists():
        sys.exit(f"{BINARY} not found: cargo build --release first")
    with tempfile.TemporaryDirectory() as tmp:
        data = opts.data
        if data is None:
            if not opts.args:
                parser.error("give raytree's arguments after --, or --data")
            data = Path(tmp) / "perf.data"
            record(opts.args, data)
        counts, total = samples(data)
    addresses = list(counts)
    own = sum(counts.values())
    by_self, inclusive = collections.Counter(), collections.Counter()
    for address, chain in zip(addresses, chains(addresses)):
        # The copies' own frames (`<Avx as F64x4>::outlined`) name no step of the tracer.
        ours = [(name(f), p) for f, p in chain if "raytree::" in f and "F64x4" not in f]
        innermost = next((f for f, p in ours if not HELPER.search(p)), "(library code)")
        by_self[innermost] += counts[address]
        # The lanes' operators (`<Avx as Mul>::mul`) are helpers, not steps.
        steps = {name(f) for f, p in chain if "raytree::" in f and "::simd::" not in f}
        for function in steps:
            inclusive[function] += counts[address]
    print(f"{total} samples, {own} in raytree ({100 * own / max(total, 1):.1f} %)")
    for title, table in (("self", by_self), ("inclusive", inclusive)):
        print(f"\n{title} (share of raytree's samples)")
        for function, n in table.most_common(opts.top):
            print(f"{100 * n / own:6.2f} %  {function.removeprefix('raytree::')}")


if __name__ == "__main__":
    main()
