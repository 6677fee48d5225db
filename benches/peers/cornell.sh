#!/usr/bin/env bash
# Path tracing against Mitsuba 3 on its Cornell box, both sides in one run, 2 threads each:
# raytree's render time and error at each sample count (`raytree bench sweep`), Mitsuba
# `llvm_ad_rgb`'s (cornell_mitsuba.py), each side the median of 3 renders after one untimed
# render (Mitsuba's compiles its kernels, raytree's warms caches and threads), and the ratio of their
# efficiencies 1/(seconds·MSE), RMSE over every pixel and channel of linear radiance.
# Usage: benches/peers/cornell.sh [REFERENCE.exr] [SPP,SPP,...]
#   (default: the shipped 4096-spp reference of ../shared/peers, at 16 and 64 spp;
#    needs `pip install mitsuba numpy` and libLLVM, e.g. `apt-get install libllvm19`)
set -euo pipefail
cd "$(dirname "$0")"
reference=$(realpath "${1:-../../../shared/peers/cornell-mitsuba-4096spp.exr}")
spps=${2:-16,64}
if ! python3 -c "import mitsuba, numpy" 2>/dev/null; then
    echo "mitsuba or numpy not found: install them with 'pip install mitsuba numpy' to compare (skipping)"
    exit 0
fi
if [ -z "${DRJIT_LIBLLVM_PATH:-}" ]; then
    DRJIT_LIBLLVM_PATH=$(ls /usr/lib/x86_64-linux-gnu/libLLVM-1[89].so 2>/dev/null | tail -1 || true)
    export DRJIT_LIBLLVM_PATH
fi
cargo build --release --quiet --manifest-path ../../Cargo.toml
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
../../target/release/raytree bench sweep ../../lessons/examples/cornell.yaml --knob spp \
    --values "$spps" --reference "$reference" --threads 2 --runs 3 --csv "$out/raytree.csv" >/dev/null
python3 cornell_mitsuba.py --reference="$reference" llvm_ad_rgb ${spps//,/ } >"$out/mitsuba.txt"
python3 - "$out/raytree.csv" "$out/mitsuba.txt" <<'PY'
import csv, sys
ours = {int(float(r["spp"])): r for r in csv.DictReader(open(sys.argv[1]))}
theirs = {}
for line in open(sys.argv[2]):
    f = line.split()
    theirs[int(f[f.index("spp") + 1])] = (float(f[f.index("seconds") + 1]), float(f[f.index("rmse") + 1]))
print(f"{'spp':>5} {'raytree s':>10} {'RMSE':>8} {'1/(s·MSE)':>10} {'Mitsuba s':>10} {'RMSE':>8} {'1/(s·MSE)':>10} {'ratio':>6}")
for spp in sorted(ours):
    s, e = float(ours[spp]["seconds"]), float(ours[spp]["rmse"])
    ms, me = theirs[spp]
    a, b = 1 / (s * e * e), 1 / (ms * me * me)
    print(f"{spp:>5} {s:>10.3f} {e:>8.5f} {a:>10.0f} {ms:>10.3f} {me:>8.5f} {b:>10.0f} {a / b:>6.2f}")
PY
