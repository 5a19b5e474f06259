#!/bin/sh
# Every error of every sweep point is reported before anything is traced:
# a sweep whose second point has a bad scene key and whose third names a
# missing memory preset exits 2 with both messages, and its output directory
# holds nothing but simulate's mark (or does not exist).
# usage: plan_errors.sh SIMULATE WORK_DIR
set -u
sim=$1 work=$2
rm -rf "$work"
mkdir -p "$work"
cat > "$work/points.json" <<JSON
{
  "scene": {"type": "bundle", "count": 60, "radius": 0.01},
  "cost": ["turing-per-ray-guess"],
  "workload": {"width": 8, "height": 8, "spp": 1, "bounces": 0},
  "output": {"images": false},
  "sweep": {
    "memory": ["memory-optix7", "no-such-memory-preset"],
    "scene": [{"tilt_deg": 0}, {"tilt_deg": 30, "bogus_key": 1}]
  }
}
JSON
"$sim" "$work/points.json" --quiet --out "$work/out" > "$work/stdout" 2> "$work/stderr"
code=$?
cat "$work/stderr"
[ "$code" = 2 ] || { echo "exit $code, expected 2"; exit 1; }
grep -q "points.json: /scene/bogus_key: " "$work/stderr" || { echo "no message for the scene key"; exit 1; }
grep -q "points.json: /memory: no preset named \"no-such-memory-preset\"" "$work/stderr" ||
  { echo "no message for the memory preset"; exit 1; }
if [ -d "$work/out" ]; then
  left=$(ls -A "$work/out" | grep -v '^\.rtcsim-output$')
  [ -z "$left" ] || { echo "written before the errors were found: $left"; exit 1; }
fi
echo "plan errors test passed"
