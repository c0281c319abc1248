#!/bin/sh
# CSMA-CA saturation on a star, masnet against ns-3's LR-WPAN (csma_star_ns3.cc), n = 2..20
# leaves, seeds 1-3 each: fails when masnet's frames per second at the coordinator (duplicates
# excluded) differ from ns-3's by more than 10 % at any n.
# Usage: sh compare_csma_star.sh MASNET_BENCH_CSMA_STAR OUTDIR
set -e
here="$(cd "$(dirname "$0")" && pwd)"
masnet="${1:?usage: sh compare_csma_star.sh MASNET_BENCH_CSMA_STAR OUTDIR}"
out="${2:?usage: sh compare_csma_star.sh MASNET_BENCH_CSMA_STAR OUTDIR}"
sh "$here/csma_star_sweep.sh" "$out" >"$out/ns3_sweep.txt"
status=0
printf '%4s %10s %10s %8s\n' n ns-3 masnet ratio
for n in 2 4 6 8 10 12 14 16 18 20; do
    peer=$(grep "^RESULT n=$n " "$out/ns3_sweep.txt" | sed 's/.*unique_per_s=\([0-9.]*\).*/\1/')
    ours=$(for seed in 1 2 3; do "$masnet" --n="$n" --seconds=20 --seed="$seed"; done |
        sed 's/.*unique_per_s=\([0-9.]*\).*/\1/' | awk '{ s += $1 } END { printf "%.1f", s / NR }')
    ratio=$(awk -v a="$ours" -v b="$peer" 'BEGIN { printf "%.3f", a / b }')
    printf '%4d %10s %10s %8s\n' "$n" "$peer" "$ours" "$ratio"
    awk -v r="$ratio" 'BEGIN { exit !(r < 0.9 || r > 1.1) }' && status=1
done
exit $status
