#!/bin/sh
# Saturation sweep of the 802.15.4 unslotted CSMA-CA star on ns-3 (csma_star_ns3.cc):
# n = 2..20 leaves, seeds 1-3, 20 s counted after 1 s of warm-up, 20-byte payload.
# Usage: sh csma_star_sweep.sh OUTDIR [EXTRA ARGS, e.g. --collisions=destroy]
#   builds the peers into OUTDIR, keeps the raw lines in OUTDIR/csma_star_runs.txt and prints one
#   RESULT line per n with the means over the seeds.
set -e
here="$(cd "$(dirname "$0")" && pwd)"
out="${1:?usage: sh csma_star_sweep.sh OUTDIR [EXTRA ARGS]}"
shift
sh "$here/build.sh" "$out" >/dev/null
runs="$out/csma_star_runs.txt"
: >"$runs"
for n in 2 4 6 8 10 12 14 16 18 20; do
    for seed in 1 2 3; do
        "$out/csma_star_ns3" --n="$n" --payload=20 --seconds=20 --seed="$seed" "$@" >>"$runs"
    done
    grep "^RESULT n=$n " "$runs" | awk -v n="$n" '
        { for (i = 2; i <= NF; ++i) { split($i, kv, "="); sum[kv[1]] += kv[2] } ++k }
        END {
            printf "RESULT n=%d payload=%d seconds=%g seeds=%d delivered_per_s=%.1f unique_per_s=%.1f " \
                   "success_confirms_per_s=%.1f channel_access_failures=%.0f no_ack=%.0f " \
                   "tx_attempts=%.0f psdu_bytes=%d ppdu_bytes=%d\n",
                   n, sum["payload"] / k, sum["seconds"] / k, k, sum["delivered_per_s"] / k,
                   sum["unique_per_s"] / k, sum["success_confirms_per_s"] / k,
                   sum["channel_access_failures"] / k, sum["no_ack"] / k, sum["tx_attempts"] / k,
                   sum["psdu_bytes"] / k, sum["ppdu_bytes"] / k
        }'
done
