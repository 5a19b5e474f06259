#!/bin/bash
# Callgrind instructions per traced ray, per case and method, counting only the
# traces (the frame runner, BuiltMethod::run), not start-up, scene or build.
# Instruction counts do not drift with the machine's load, unlike wall time.
#   sim/bench/callgrind_per_ray.sh [BENCH] [CASE:METHOD:PIXELS[:EXECUTION] ...]
# Default: build/bench, cases 1-3 ref and obb (case 3 obb only) at small sizes.
# EXECUTION (per_ray, the default, or warp) is passed to bench's --execution.
# The toggle names run() exactly (its parameter list ends with FrameOptions):
# a pattern that also matches the lambdas inside run() toggles collection off
# again on entering them, which undercounted once the tracer lambda stopped
# being inlined.
# Prints one line per case: instructions per ray, rays, and the bench's event
# totals hash (identical hashes = identical counts).
set -euo pipefail
bench=${1:-build/bench}
shift || true
specs=("$@")
[ ${#specs[@]} -eq 0 ] && specs=(1:ref:64 1:obb:64 2:ref:100 2:obb:100 3:obb:30)
out=$(mktemp -d)
printf "%-4s %-8s %6s %-7s %10s %14s %12s  %s\n" case method pixels exec rays Ir Ir/ray events
for spec in "${specs[@]}"; do
    IFS=: read -r c m p x <<<"$spec"
    x=${x:-per_ray}
    run="$c.$m.$p.$x"
    valgrind --tool=callgrind --toggle-collect='rtc::BuiltMethodOf<*>::run(*rtc::FrameOptions const&) const' \
        --callgrind-out-file="$out/cg.$run" "$bench" --cases "$c" --methods "$m" \
        --pixels "$p" --repeat 1 --threads 1 --execution "$x" --json "$out/b.$run.json" >"$out/log.$run" 2>&1
    ir=$(callgrind_annotate "$out/cg.$run" 2>/dev/null | awk '/PROGRAM TOTALS/ {gsub(",", "", $1); print $1}')
    python3 - "$out/b.$run.json" "$c" "$m" "$p" "$ir" "$x" <<'PY'
import hashlib, json, sys
j = json.load(open(sys.argv[1]))
case, method, pixels, ir, execution = sys.argv[2], sys.argv[3], sys.argv[4], int(sys.argv[5]), sys.argv[6]
rays, traced, events = 0, 0, []
for c in j["cases"]:
    for r in c.get("runs", []):  # case 4 has two runs (capsules, phantom curves)
        for m in r["methods"]:
            # Older bench files time 1 thread and the "all threads" count: two traces.
            traces = len(m["rates"]) if "rates" in m else 2
            rays += m["rays"]
            traced += m["rays"] * traces * j.get("repeat", 1)
            events.append(m["events"])
h = hashlib.sha1(json.dumps(events, sort_keys=True).encode()).hexdigest()[:12]
print(f"{case:<4} {method:<8} {pixels:>6} {execution:<7} {rays:>10} {ir:>14,} {ir / max(traced, 1):>12,.0f}  {h}")
PY
done
rm -rf "$out"
