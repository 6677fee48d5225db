#!/usr/bin/env python3
"""Where a render's time goes, by raytree function, through the inlined code.

The release build inlines most of the fast wing into a few large functions (each entry point
of the wing, in the copy for the processor's instructions), so `perf report --sort sym` names
little more than `<Avx as F64x4>::outlined::copy`. This script maps every sampled address
through `addr2line -i`, which lists the chain of functions inlined at that address, and
counts each sample twice over:

- self: for the innermost raytree function of the chain, passing over the lanes'
  one-instruction helpers (`fast/simd.rs`), the wing's `push_in_place` (`fast/mod.rs`), glam
  and core;
- inclusive: for every raytree function on the chain, once per sample: the share of the time
  spent in that step and everything it calls, as a flame graph would show it.

Usage (from the project's directory, with a release build):

    benches/profile.py [--top N] [--data FILE] -- RAYTREE_ARGS...
    benches/profile.py --top 30 -- render benches/peers/whitted.yaml -o /tmp/w.png --threads 2
    benches/profile.py --data perf.data          (an existing recording of target/release/raytree)

Needs perf (`-e cpu-clock`, 8 000 samples a second: virtual machines have no cycle counter)
and binutils' addr2line.

With `--instructions` it runs raytree under valgrind's callgrind instead and counts
instructions, not samples: exact and the same on every run whatever the machine's load, so
two builds' profiles can be compared row by row (about 50 times slower than the render; use a
smaller image, `--width 400 --height 300 --threads 1`, and a `.ppm`). Needs valgrind.
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
# Lane helpers, the wing's `push_in_place` (`fast/mod.rs`) and library code: a sample in them
# counts (for self) toward the raytree function that called them.
HELPER = re.compile(r"fast/simd\.rs|fast/mod\.rs|/glam-|/rustc/|/core_arch/|/arrayvec-|/wide-")


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


def instructions(args: list[str], out: Path) -> tuple[collections.Counter, int]:
    """Instructions run at each address of the binary (as addr2line takes them), and in all."""
    subprocess.run(
        ["valgrind", "--tool=callgrind", "--dump-instr=yes", f"--callgrind-out-file={out}",
         str(BINARY), *args],
        check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    # The file's names are compressed: "(7) name" the first time, "(7)" after, numbered
    # apart for objects and for functions.
    names: dict[tuple[str, str], str] = {}

    def named(kind: str, value: str) -> str:
        m = re.match(r"\((\d+)\)(?: (.*))?", value)
        if not m:
            return value
        if m.group(2) is not None:
            names[kind, m.group(1)] = m.group(2)
        return names[kind, m.group(1)]

    counts, total = collections.Counter(), 0
    obj, function, address, after_call = "", "", 0, False
    main_address = None
    for line in out.read_text().splitlines():
        key, _, value = line.partition("=")
        if key in ("ob", "cob"):
            # A called object's or function's name may be given for the first time there.
            read = named("ob", value)
            obj = read if key == "ob" else obj
            continue
        if key in ("fn", "cfn"):
            read = named("fn", value)
            function = read if key == "fn" else function
            continue
        if key == "calls":
            after_call = True
            continue
        if not line or not (line[0] in "+-*" or line.startswith("0x")):
            continue
        fields = line.split()
        step = fields[0]
        if step.startswith("0x"):
            address = int(step, 16)
        elif step[0] in "+-":
            address += int(step)
        if after_call:
            # The cost of a call, counted in the callee's own lines.
            after_call = False
            continue
        cost = int(fields[2]) if len(fields) > 2 else 0
        total += cost
        if obj.endswith("/" + BINARY.name):
            counts[address] += cost
            if function == "main":
                main_address = min(address, main_address or address)
    # callgrind gives the addresses where valgrind loaded the binary: `main` says where.
    symbols = subprocess.run(["nm", str(BINARY)], check=True, capture_output=True,
                             text=True).stdout.splitlines()
    main_symbol = next(int(s.split()[0], 16) for s in symbols if s.endswith(" main"))
    load = (main_address or main_symbol) - main_symbol
    return collections.Counter({a - load: n for a, n in counts.items()}), total


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
    parser.add_argument("--instructions", action="store_true",
                        help="count instructions under callgrind instead of sampling with perf")
    parser.add_argument("args", nargs="*", help="raytree's arguments (after --)")
    opts = parser.parse_args()
    tools = ("valgrind", "addr2line", "nm") if opts.instructions else ("perf", "addr2line", "readelf")
    packages = {"perf": "linux-perf", "valgrind": "valgrind"}
    for tool in tools:
        if shutil.which(tool) is None:
            sys.exit(f"{tool} not found (apt-get install -y {packages.get(tool, 'binutils')})")
    if not BINARY.exists():
        sys.exit(f"{BINARY} not found: cargo build --release first")
    if opts.instructions and (opts.data or not opts.args):
        parser.error("--instructions runs raytree itself: give its arguments after --")
    unit = "instructions" if opts.instructions else "samples"
    with tempfile.TemporaryDirectory() as tmp:
        data = opts.data
        if opts.instructions:
            counts, total = instructions(opts.args, Path(tmp) / "callgrind.out")
        else:
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
    print(f"{total} {unit}, {own} in raytree ({100 * own / max(total, 1):.1f} %)")
    for title, table in (("self", by_self), ("inclusive", inclusive)):
        print(f"\n{title} (share of raytree's {unit})")
        for function, n in table.most_common(opts.top):
            print(f"{100 * n / own:6.2f} %  {function.removeprefix('raytree::')}")


if __name__ == "__main__":
    main()
