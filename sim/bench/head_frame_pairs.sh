#!/bin/bash
# The head frame (configs/runs/head_1m.json, the paper's frame on 1 M
# capsules) timed with two simulate binaries in alternated pairs, A B A B ...,
# and their ratio per pair. On a VM whose speed drifts by tens of percent
# between minutes, only runs close in time compare; a ratio against the
# issue's baseline binary turns the issue's own figure for that binary
# (6.6 s on its machine, issue 19) into a projection for the other one.
#   sim/bench/head_frame_pairs.sh BIN_A BIN_B [PAIRS] [-- simulate options...]
# BIN_A: e.g. a build of the baseline commit (git worktree add /tmp/base
# c2fe590; cmake -S /tmp/base -B /tmp/build-base; cmake --build /tmp/build-base
# --target simulate). Each binary runs its own checkout's config when it sits
# in a build directory of one (CMakeCache.txt names the source), else this
# checkout's. Options after -- go to every run (e.g. --set
# workload.width=200). Environment: THREADS (default 2), BASE_SECONDS (the
# figure to project from, default 6.6). Prints, per pair, builds + traces
# (both methods' build_seconds and trace_seconds from report.json), the
# report's total and the process's wall time, then each measure's ratio A/B
# per pair and what BASE_SECONDS / ratio projects for B.
set -euo pipefail
if [ $# -lt 2 ]; then
    awk 'NR > 1 && /^#/ { sub(/^# ?/, ""); print; next } NR > 1 { exit }' "$0" >&2
    exit 2
fi
bin_a=$1 bin_b=$2
shift 2
pairs=3
if [ $# -gt 0 ] && [ "$1" != "--" ]; then pairs=$1; shift; fi
[ $# -gt 0 ] && [ "$1" = "--" ] && shift
for b in "$bin_a" "$bin_b"; do
    [ -x "$b" ] || { echo "head_frame_pairs: $b is not an executable" >&2; exit 2; }
done
case $pairs in '' | *[!0-9]* | 0) echo "head_frame_pairs: PAIRS must be a positive integer, got '$pairs'" >&2; exit 2 ;; esac
base_seconds=${BASE_SECONDS:-6.6}
if [[ ! $base_seconds =~ ^[0-9]+([.][0-9]+)?$ || $base_seconds =~ ^0+([.]0+)?$ ]]; then
    echo "head_frame_pairs: BASE_SECONDS must be a positive number of seconds, got '$base_seconds'" >&2
    exit 2
fi
here=$(cd "$(dirname "$0")/../.." && pwd)
config_for() {  # the config of the binary's own checkout when it has one
    local cache src
    cache="$(dirname "$1")/CMakeCache.txt"
    src=""
    if [ -f "$cache" ]; then src=$(sed -n 's/^CMAKE_HOME_DIRECTORY:INTERNAL=//p' "$cache"); fi
    if [ -n "$src" ] && [ -f "$src/configs/runs/head_1m.json" ]; then echo "$src/configs/runs/head_1m.json"
    else echo "$here/configs/runs/head_1m.json"; fi
}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for i in $(seq "$pairs"); do
    for x in A B; do
        if [ $x = A ]; then bin=$bin_a; else bin=$bin_b; fi
        start=$(date +%s.%N)
        "$bin" "$(config_for "$bin")" --threads "${THREADS:-2}" --force --quiet --out "$out/$x" "$@" >/dev/null
        end=$(date +%s.%N)
        python3 - "$out/$x/report.json" "$x" "$i" "$start" "$end" >>"$out/runs.txt" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
sims = [m["simulator"] for m in r["methods"].values() if "simulator" in m]
bt = sum(s["build_seconds"] + s["trace_seconds"] for s in sims)
print(sys.argv[2], sys.argv[3], "%.3f %.3f %.3f" % (bt, r["wall_seconds"]["total"], float(sys.argv[5]) - float(sys.argv[4])))
PY
        tail -n 1 "$out/runs.txt" | awk '{printf "pair %s %s  builds+traces %6.2f s  total %6.2f s  wall %6.2f s\n", $2, $1, $3, $4, $5}'
    done
done
python3 - "$out/runs.txt" "$base_seconds" <<'PY'
import statistics, sys
rows = [line.split() for line in open(sys.argv[1])]
base = float(sys.argv[2])
a = {r[1]: list(map(float, r[2:])) for r in rows if r[0] == "A"}
b = {r[1]: list(map(float, r[2:])) for r in rows if r[0] == "B"}
for k, name in enumerate(["builds+traces", "total", "wall"]):
    ratios = [a[p][k] / b[p][k] for p in a]
    print("%-13s A/B per pair: %s  median %.2f  -> B projected from %.2f s: %s s (median %.2f)"
          % (name, " ".join("%.2f" % q for q in ratios), statistics.median(ratios), base,
             " ".join("%.2f" % (base / q) for q in ratios), base / statistics.median(ratios)))
PY
