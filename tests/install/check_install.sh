#!/usr/bin/env bash
# The protocol tutorial from scratch (docs/tutorial-protocol.md): install masnet into a fresh
# prefix, build docs/tutorial/ against it with find_package, and run the program it makes.
# Usage: check_install.sh SOURCE_DIR BUILD_DIR   (BUILD_DIR: a configured and built masnet)
set -euo pipefail
source_dir=$(cd "$1" && pwd)
build_dir=$(cd "$2" && pwd)
work=$(mktemp -d "${TMPDIR:-/tmp}/masnet-install.XXXXXX")
trap 'rm -rf "$work"' EXIT
prefix=$work/prefix
fail() { echo "check_install: FAILED: $*" >&2; exit 1; }
step() { echo "check_install: $*"; }

cmake --install "$build_dir" --prefix "$prefix" > "$work/install.log"
step "installed into a fresh prefix"

# Only the public headers: no ground truth, no radio, world or loader internals.
for internal in protocols/ground_truth.hpp protocols/oracle_protocol.hpp net/radio.hpp agents \
                scenarios/loader scenarios/run; do
  [ ! -e "$prefix/include/masnet/$internal" ] || fail "installed $internal"
done
[ -f "$prefix/include/masnet/protocols/registry.hpp" ] || fail "registry.hpp not installed"
[ -f "$prefix/lib/cmake/masnet/masnetConfigVersion.cmake" ] || fail "no package version file"
[ -f "$prefix/share/masnet/scenarios/paper/acoustic_tracking.yaml" ] || fail "no scenario files"
if grep -rl "ground_truth\|GroundTruth" "$prefix/include" > "$work/leaks.txt"; then
  fail "installed headers name ground truth: $(cat "$work/leaks.txt")"
fi
step "only public headers installed"

# A version the package must refuse: 0.1 is not 0.2 (0.x minor versions may break the API).
mkdir -p "$work/old" && cat > "$work/old/CMakeLists.txt" <<'CMAKE'
cmake_minimum_required(VERSION 3.25)
project(old LANGUAGES CXX)
find_package(masnet 0.1 QUIET)
if(masnet_FOUND)
  message(FATAL_ERROR "masnet 0.2 accepted a request for 0.1")
endif()
CMAKE
cmake -S "$work/old" -B "$work/old/build" -DCMAKE_PREFIX_PATH="$prefix" > "$work/old.log" 2>&1 \
  || fail "find_package(masnet 0.1): $(cat "$work/old.log")"

generator=()
command -v ninja > /dev/null && generator=(-G Ninja)
cmake -S "$source_dir/docs/tutorial" -B "$work/tutorial" "${generator[@]}" \
  -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release > "$work/configure.log" \
  || { cat "$work/configure.log"; fail "configuring the tutorial"; }
cmake --build "$work/tutorial" -j2 > "$work/build.log" || { cat "$work/build.log"; fail "building the tutorial"; }
step "built docs/tutorial with find_package(masnet 0.2)"

program=$work/tutorial/hello_cells
scenario=$prefix/share/masnet/scenarios/paper/acoustic_tracking.yaml
cd "$work"

"$program" protocols > protocols.txt
grep -q "^hello_cells" protocols.txt || fail "masnet protocols does not list hello_cells"
grep -q "hello_range" protocols.txt || fail "masnet protocols does not list hello_range"

"$program" run "$scenario" --set protocol.kind=hello_cells --out hello --quiet \
  2> run.err || { cat run.err; fail "hello_cells run"; }
python3 - hello <<'PY' || fail "a HELLO count is missing"
import json, sys
run = sys.argv[1]
hello = json.load(open(f"{run}/summary.json"))["messages"]["by_type"]["HELLO"]
assert hello["count"] > 0 and hello["bytes"] == 18 * hello["count"], hello
header = open(f"{run}/updates.csv").readline().strip().split(",")
assert "HELLO_count" in header and header[-1] == "robots_heard", header
assert "<td>HELLO</td>" in open(f"{run}/report.html").read()
PY
step "hello_cells ran: HELLO counted in summary.json, updates.csv and report.html"

expected="--set protocol.hello_range=20: protocol.hello_range: must be in [0.01, 10] (got 20)"
status=0
"$program" run "$scenario" --set protocol.kind=hello_cells --set protocol.hello_range=20 \
  --out bad --quiet 2> bad.err || status=$?
[ "$status" -eq 2 ] || fail "bad hello_range: exit status $status, not 2"
grep -qxF -- "$expected" bad.err || fail "bad hello_range: got $(cat bad.err)"
[ ! -e bad ] || fail "bad hello_range wrote its output folder"
sed 's/^  kind: radius_doubling$/  kind: hello_cells\n  hello_range: -1/' "$scenario" > bad.yaml
status=0
"$program" validate bad.yaml 2> bad_file.err || status=$?
line=$(grep -n "hello_range: -1" bad.yaml | cut -d: -f1)
[ "$status" -eq 2 ] || fail "bad hello_range in a file: exit status $status, not 2"
grep -qxF "bad.yaml:$line:16: protocol.hello_range: must be in [0.01, 10] (got -1)" bad_file.err \
  || fail "bad hello_range in a file: got $(cat bad_file.err)"
step "bad hello_range: file:line:col, exit status 2, nothing written"

sweep=$work/tutorial/compare.yaml
"$program" sweep "$sweep" --jobs 2 --out jobs --quiet > sweep.log 2>&1 || { cat sweep.log; fail "2-job sweep"; }
python3 - jobs <<'PY' || fail "the sweep's results lack hello_cells' HELLOs"
import csv, sys
rows = list(csv.DictReader(open(f"{sys.argv[1]}/results.csv")))
assert len(rows) == 20 and all(r["status"] == "ok" for r in rows), len(rows)
for r in rows:
    hellos = int(r["messages_by_type_hello_count"])
    assert (hellos > 0) == (r["p_variant"] == "hello_cells"), (r["p_variant"], hellos)
PY
step "2-job sweep: 20 runs, HELLO columns in results.csv"

if ! command -v mpirun > /dev/null; then
  step "skipped mpirun: not installed (apt-get install openmpi-bin)"
  exit 0
fi
if ! "$program" sweep --help | grep -q -- --no-mpi; then
  step "skipped mpirun: masnet was built without MPI"
  exit 0
fi
ASAN_OPTIONS=detect_leaks=0 mpirun -x ASAN_OPTIONS --oversubscribe --allow-run-as-root \
  --mca btl self,vader --mca oob_tcp_if_include lo -np 2 \
  "$program" sweep "$sweep" --out ranks --quiet > mpi.log 2>&1 || { cat mpi.log; fail "mpirun -np 2"; }
python3 - jobs ranks <<'PY' || fail "mpirun -np 2 gave other results than --jobs 2"
import csv, sys
def table(folder):
    keep = lambda k: k not in ("finished_at", "wall_time_s")
    return sorted(tuple(v for k, v in r.items() if keep(k))
                  for r in csv.DictReader(open(f"{folder}/results.csv")))
assert table(sys.argv[1]) == table(sys.argv[2])
PY
step "mpirun -np 2: the same 20 results as --jobs 2"
