#!/usr/bin/env bash
# `masnet run` started by mpirun: one run in one tile per rank (docs/decisions/0012-partitioned-
# runs.md). Every file of the run directory equals the run in one piece but for what the run cost
# (summary.json's events and wall time), with a fault too, and with the robots in the first rank;
# --tiles other than the number of ranks is refused, and a
# scenario file one rank cannot read stops every rank (exit 2, the message once, never a hang).
# Usage: run_over_ranks.sh <masnet> <mpiexec> <source dir> <ranks>
set -euo pipefail
masnet=$1 mpiexec=$2 source=$3 ranks=$4
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
scenario=(run "$source/scenarios/paper/acoustic_tracking.yaml" --set tie_order=origin
  --set duration=1 --set output.snapshots=[0.5] --set output.figures=false
  --set output.report=false --quiet)
mpi=("$mpiexec" --oversubscribe --allow-run-as-root -n "$ranks")

# The run, the run with a fault (whose fault-free twin only the first rank runs), and the run
# whose robots act a window late (the first rank runs them all), over ranks and in one piece.
with_fault=(--set 'faults=[{at: 0.5, kill: robots, ids: [0]}]')
late=(--set robots.actuation_delay=0.0001 --set 'faults=[{at: 0.5, until: 0.7, kill: robots, ids: [2]}]')
for variant in plain fault late; do
  extra=()
  [ "$variant" = fault ] && extra=("${with_fault[@]}")
  [ "$variant" = late ] && extra=("${late[@]}")
  "$masnet" "${scenario[@]}" "${extra[@]}" --out "$work/whole-$variant"
  "${mpi[@]}" "$masnet" "${scenario[@]}" "${extra[@]}" --out "$work/ranks-$variant" \
    2> "$work/ranks.stderr"
  # More ranks than processors is warned of, once; as many or fewer, not.
  if [ "$ranks" -gt "$(nproc)" ]; then
    [ "$(grep -c '^masnet run: warning: more MPI ranks than processors on a host' "$work/ranks.stderr")" = 1 ]
  else
    [ ! -s "$work/ranks.stderr" ]
  fi
  for f in "$work/whole-$variant"/*; do
    name=$(basename "$f")
    if [ "$name" = summary.json ]; then
      diff <(grep -v '"events"\|"wall_time_s"' "$f") \
        <(grep -v '"events"\|"wall_time_s"' "$work/ranks-$variant/$name")
    else
      cmp "$f" "$work/ranks-$variant/$name"
    fi
  done
  [ "$(ls "$work/whole-$variant")" = "$(ls "$work/ranks-$variant")" ]
done
grep -q '"twin"' "$work/ranks-fault/summary.json"

# One tile per rank: another count is refused before anything runs.
status=0
"${mpi[@]}" "$masnet" "${scenario[@]}" --out "$work/refused" --tiles $((ranks + 1)) \
  2> "$work/stderr" || status=$?
[ "$status" -ne 0 ]
grep -q "^masnet run: --tiles $((ranks + 1)) under $ranks MPI ranks: each rank runs one tile (give --tiles $ranks or leave it out)$" "$work/stderr"
[ ! -e "$work/refused" ]
# A file only the last rank cannot read: every rank stops (exit 2, nothing written, no hang),
# and the message is printed once.
cat > "$work/last_rank_misses.sh" <<EOF
#!/usr/bin/env bash
file="$source/scenarios/paper/acoustic_tracking.yaml"
[ "\$OMPI_COMM_WORLD_RANK" = $((ranks - 1)) ] && file="$work/missing.yaml"
exec "$masnet" run "\$file" --set tie_order=origin --set duration=1 --set output.snapshots=[] \
  --out "$work/missing" --quiet
EOF
status=0
timeout 120 "${mpi[@]}" bash "$work/last_rank_misses.sh" 2> "$work/stderr" || status=$?
[ "$status" -ne 0 ] && [ "$status" -ne 124 ]
[ "$(grep -c "^$work/missing.yaml:1:1: cannot read the scenario file (No such file or directory)$" "$work/stderr")" = 1 ]
[ ! -e "$work/missing" ]
echo "run over $ranks ranks: every output equals the run in one piece"
