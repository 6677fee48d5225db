#!/usr/bin/env bash
# Renders each peer scene with POV-Ray 3.7 and with raytree at equal work (800×600, 16 samples
# per pixel, depth 5, 2 threads), alternating runs, and prints median wall times and the median
# of the runs' ratios (each raytree run against the POV-Ray run just before it, so that a change
# in the shared machine's load between runs cancels out), with their range.
# Usage: benches/peers/run.sh [runs] [scene...]   (default: 5 runs each, after one warm-up, of
# the whitted, csg and many scenes). RAYTREE=path/to/raytree measures that binary (another
# build of raytree) instead of building target/release/raytree.
set -euo pipefail
cd "$(dirname "$0")"
runs=${1:-5}
shift $(( $# > 0 ))
scenes=("${@:-whitted csg many}")
peers=../../../shared/peers
if ! command -v povray >/dev/null 2>&1; then
    echo "povray not found: install it with 'apt-get install -y povray' to compare (skipping)"
    exit 0
fi
if [ -n "${RAYTREE:-}" ]; then
    raytree=$(realpath "$RAYTREE")
else
    cargo build --release --quiet --manifest-path ../../Cargo.toml
    raytree=../../target/release/raytree
fi
[ -f many.yaml ] || python3 make_many.py many.yaml
out=$(mktemp -d)
wall() { /usr/bin/time -f %e "$@" 2>&1 >/dev/null | tail -1; }
median() { sort -n | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
# Rays per second count every ray, as the speed target does: primary, shadow, reflection and
# refraction. POV-Ray's are the rays and shadow-ray tests of its own statistics (the issue
# counts it that way), raytree's those of `--stats`, taken from the warm-up runs; each count
# is divided by that side's median wall time. POV-Ray's rate is the machine's yardstick: the
# target's 60 M rays/s was set where POV-Ray did 12–15 M.
rate() { awk -v rays="$1" -v s="$2" 'BEGIN {printf "%.1f", rays / s / 1e6}'; }
printf "%-8s %12s %12s %8s %14s %14s %14s\n" scene "POV-Ray s" "raytree s" ratio "ratio range" \
    "POV-Ray Mray/s" "raytree Mray/s"
for scene in ${scenes[*]}; do
    pov=(povray -D -V "+I$peers/$scene.pov" "+O$out/$scene-pov.png" +FN +W800 +H600 +A0.0 +AM1 +R4 -J +WT2)
    ray=("$raytree" render "$scene.yaml" -o "$out/$scene-raytree.png" --spp 16 --threads 2)
    # Warm-up, counting the rays (every run traces the same ones).
    pov_rays=$("${pov[@]}" 2>&1 |
        awk '/^Rays:/ {r = $2} /^Shadow Ray Tests:/ {s = $4} END {print r + s}')
    ray_rays=$("${ray[@]}" --stats 2>&1 | awk '/^rays traced/ {print $3}')
    : > "$out/p"; : > "$out/r"
    for _ in $(seq "$runs"); do
        wall "${pov[@]}" >> "$out/p"
        wall "${ray[@]}" >> "$out/r"
    done
    p=$(median < "$out/p"); r=$(median < "$out/r")
    paste "$out/r" "$out/p" | awk '{print $1 / $2}' > "$out/ratios"
    ratio=$(median < "$out/ratios")
    range=$(sort -n "$out/ratios" | awk 'NR == 1 {lo = $1} {hi = $1} END {printf "%.3f–%.3f", lo, hi}')
    printf "%-8s %12s %12s %8.3f %14s %14s %14s\n" "$scene" "$p" "$r" "$ratio" "$range" \
        "$(rate "$pov_rays" "$p")" "$(rate "$ray_rays" "$r")"
done
echo "images in $out"
