#!/bin/sh
# A ray file named relative to a config in a subdirectory is the one beside
# the config, whatever the working directory: `simulate sub/run.json` from
# the parent, `simulate run.json` from sub/ and the config by its path from
# the repository root trace the same rays. (It was resolved twice, so the
# first opened sub/sub/rays.bin: a decoy with other rays sits there.)
# usage: rays_file_relative.sh SIMULATE SOURCE_DIR WORK_DIR
set -eu
sim=$1 src=$2 work=$3
rm -rf "$work"
mkdir -p "$work/sub/sub"
cd "$src"
"$sim" tests/configs/tiny.json --quiet --force --out "$work/record" --set output.images=false > /dev/null
"$sim" tests/configs/tiny.json --quiet --force --out "$work/decoy" --set output.images=false \
    --set workload.width=16 --set workload.height=16 > /dev/null
cp "$work/record/rays.bin" "$work/sub/rays.bin"
cp "$work/decoy/rays.bin" "$work/sub/sub/rays.bin"
cat > "$work/sub/run.json" <<JSON
{
  "scene": {"type": "bundle", "count": 60, "radius": 0.01, "tilt_deg": 30, "seed": 2},
  "cost": ["turing-per-ray-guess"],
  "memory": "memory-optix7",
  "workload": {"type": "rays", "rays_file": "rays.bin"},
  "output": {"images": false, "hits": true}
}
JSON
cd "$work" && "$sim" sub/run.json --quiet --force --out "$work/from_parent" > /dev/null
cd "$work/sub" && "$sim" run.json --quiet --force --out "$work/from_sub" > /dev/null
cd "$src" && "$sim" "$work/sub/run.json" --quiet --force --out "$work/from_root" > /dev/null
for run in from_parent from_sub from_root; do
  for m in ref obb; do
    cmp "$work/$run/hits_$m.bin" "$work/record/hits_$m.bin"
  done
  grep -q "\"rays_file\": \"$work/sub/rays.bin\"" "$work/$run/report.json" ||
    { echo "$run/report.json does not name $work/sub/rays.bin"; exit 1; }
done
echo "relative rays_file test passed"
