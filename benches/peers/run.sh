#!/usr/bin/env bash
# Renders each peer scene with POV-Ray 3.7 and with raytree at equal work (800×600, 16 samples
# per pixel, depth 5, 2 threads), alternating runs, and prints median wall times and the median
# of the runs' ratios (each raytree run against the POV-Ray run just before it, so that a change
# in the shared machine's load between runs cancels out), with their range.
# Usage: benches/peers/run.sh [runs] [scene...]   (default: 5 runs each, after one warm-up, of
# the whitted, csg and many scenes)
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
cargo build --release --quiet --manifest-path ../../Cargo.toml
raytree=../../target/release/raytree
[ -f many.yaml ] || python3 make_many.py many.yaml
out=$(mktemp -d)
wall() { /usr/bin/time -f %e "$@" 2>&1 >/dev/null | tail -1; }
median() { sort -n | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}'; }
printf "%-8s %12s %12s %8s %14s\n" scene "POV-Ray s" "raytree s" ratio "ratio range"
for scene in ${scenes[*]}; do
    pov=(povray -D -V "+I$peers/$scene.pov" "+O$out/$scene-pov.png" +FN +W800 +H600 +A0.0 +AM1 +R4 -J +WT2)
    ray=("$raytree" render "$scene.yaml" -o "$out/$scene-raytree.png" --spp 16 --threads 2)
    wall "${pov[@]}" >/dev/null; wall "${ray[@]}" >/dev/null   # warm-up
    : > "$out/p"; : > "$out/r"
    for _ in $(seq "$runs"); do
        wall "${pov[@]}" >> "$out/p"
        wall "${ray[@]}" >> "$out/r"
    done
    p=$(median < "$out/p"); r=$(median < "$out/r")
    paste "$out/r" "$out/p" | awk '{print $1 / $2}' > "$out/ratios"
    ratio=$(median < "$out/ratios")
    range=$(sort -n "$out/ratios" | awk 'NR == 1 {lo = $1} {hi = $1} END {printf "%.3f–%.3f", lo, hi}')
    printf "%-8s %12s %12s %8.3f %14s\n" "$scene" "$p" "$r" "$ratio" "$range"
done
echo "images in $out"
