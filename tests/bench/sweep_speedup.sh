#!/usr/bin/env bash
# Speed-up of `masnet sweep` on one machine: the same 40-run sweep (the acoustic paper scenario,
# 4 s simulated, seeds 1..40, ≈ 0.4–0.8 s per run) with --jobs 1, --jobs 2 and
# `mpirun -np 2 … --jobs 1`, wall clock by /usr/bin/time -v; then checks that the three `runs`
# tables are identical apart from wall-clock columns. Results: docs/sweeps.md#performance.
#
#   tests/bench/sweep_speedup.sh [path/to/masnet]      (default: build/release/scenarios/masnet)
set -euo pipefail
cd "$(dirname "$0")/../.."
masnet=$(realpath "${1:-build/release/scenarios/masnet}")
work=$(mktemp -d /tmp/masnet-sweep-speedup.XXXXXX)
trap 'rm -rf "$work"' EXIT
cat > "$work/speedup.yaml" <<YAML
base: $(realpath scenarios/paper/acoustic_tracking.yaml)
seeds: 40
set: {duration: 4.0, output.snapshots: [], output.figures: false, output.report: false, output.updates: false}
YAML

wall() {  # wall-clock seconds of a command, from /usr/bin/time -v (its CPU share goes to cpu.log)
  /usr/bin/time -v "$@" > /dev/null 2> "$work/time.log" || true
  grep 'Percent of CPU' "$work/time.log" >> "$work/cpu.log"
  awk -F': ' '/Elapsed \(wall clock\)/ { n = split($2, p, ":"); s = 0; for (i = 1; i <= n; ++i) s = s * 60 + p[i]; print s }' "$work/time.log"
}

echo "masnet: $masnet; $(nproc) cores; load average: $(cut -d' ' -f1-3 /proc/loadavg)"
t1=$(wall "$masnet" sweep "$work/speedup.yaml" --quiet --jobs 1 --out "$work/j1")
echo "--jobs 1:                 ${t1} s"
t2=$(wall "$masnet" sweep "$work/speedup.yaml" --quiet --jobs 2 --out "$work/j2")
echo "--jobs 2:                 ${t2} s   speed-up $(echo "scale=2; $t1 / $t2" | bc)"
if command -v mpirun > /dev/null; then
  tm=$(wall mpirun --oversubscribe --allow-run-as-root -np 2 "$masnet" sweep "$work/speedup.yaml" --quiet --jobs 1 --out "$work/mpi")
  echo "mpirun -np 2 (--jobs 1):  ${tm} s   speed-up $(echo "scale=2; $t1 / $tm" | bc)"
fi

sed 's/^\s*/CPU share (1, 2, mpi): /' "$work/cpu.log"

# The same results whatever the parallelism (needs the sqlite3 shell).
if command -v sqlite3 > /dev/null; then
  for d in j1 j2 mpi; do
    [ -f "$work/$d/results.sqlite" ] || continue
    sqlite3 "$work/$d/results.sqlite" "SELECT run_id, fingerprint, messages_total_count, energy_j_total,
      protocol_cell_correctness, tracking_mean_error FROM runs ORDER BY run_index" | md5sum | sed "s/ .*/  $d/"
  done
fi
