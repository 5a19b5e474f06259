#!/bin/sh
# The issue's "done when": `cmake --install` into a temporary prefix, a config
# in a temporary directory outside the repository naming presets by name and
# a scene file by a path relative to the config, run from / with the
# installed binary. Checks that the installed presets were the ones used.
# Usage: install_and_run.sh BUILD_DIR
set -eu
build=$(cd "$1" && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
prefix="$tmp/prefix"
cmake --install "$build" --prefix "$prefix" > "$tmp/install.log"
test -x "$prefix/bin/simulate"
test -x "$prefix/bin/bench"
test -f "$prefix/share/rtcsim/hw/turing-calibrated.json"
test -f "$prefix/share/rtcsim/runs/quickstart.json"

mkdir -p "$tmp/project/data"
# Three strands of a few points: x y z r per line, a blank line between strands.
cat > "$tmp/project/data/curves.txt" <<'CURVES'
# three small strands
0 0 0 0.02
0 0.3 0 0.02
0.05 0.6 0 0.01

0.2 0 0 0.02
0.2 0.3 0.05 0.02

-0.2 0 0 0.02
-0.2 0.3 -0.05 0.02
-0.25 0.6 0 0.01
CURVES
cat > "$tmp/project/run.json" <<'CONFIG'
{
  "scene": {"type": "file", "curves": {"path": "data/curves.txt"}},
  "cost": ["turing-calibrated", "turing-per-ray-guess"],
  "memory": "memory-dxr",
  "workload": {"type": "camera", "width": 16, "height": 16, "spp": 1, "bounces": 1},
  "output": {"images": false}
}
CONFIG
cd /
# Without RTCSIM_PRESET_DIR the installed program looks beside itself
# (<bin>/../share/rtcsim/hw) before the source tree compiled in as a fallback.
env -u RTCSIM_PRESET_DIR "$prefix/bin/simulate" "$tmp/project/run.json" --quiet --threads 2 --out "$tmp/out" > "$tmp/stdout"
test -f "$tmp/out/report.json"
# The presets came from the installed preset directory (provenance).
grep -q "\"file\": \"$prefix/share/rtcsim/hw/turing-calibrated.json\"" "$tmp/out/report.json"
grep -q "\"file\": \"$prefix/share/rtcsim/hw/memory-dxr.json\"" "$tmp/out/report.json"
# The scene file was found beside the config.
grep -q "\"path\": \"data/curves.txt\"" "$tmp/out/report.json"
grep -q "\"strands\": 3" "$tmp/out/report.json"
# A second run into the same directory is refused, --force clears it.
if "$prefix/bin/simulate" "$tmp/project/run.json" --quiet --out "$tmp/out" 2> "$tmp/stderr"; then
  echo "second run into a non-empty output directory was not refused" >&2; exit 1
fi
grep -q -- "--force" "$tmp/stderr"
touch "$tmp/out/stale_plot.svg"
"$prefix/bin/simulate" "$tmp/project/run.json" --quiet --force --out "$tmp/out" > /dev/null
test ! -e "$tmp/out/stale_plot.svg"
test -f "$tmp/out/report.json"
echo "install test passed: $prefix"
