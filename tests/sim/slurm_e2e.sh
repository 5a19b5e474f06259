#!/usr/bin/env bash
# Issue 17's "done when", through a real Slurm: starts a single-node cluster
# on this machine (scripts/slurm-local: munged, slurmctld, slurmd), submits a
# 4-shard array of a small sweep and of one frame split by rows with
# scripts/slurm-submit, waits, and checks that the merged outputs equal a
# single run's (report.json without provenance and timings, .npy arrays,
# images, tables byte for byte). In the frame run one shard is cancelled
# before it starts: the merge job is dropped by Slurm, and
# `slurm-submit --resume` reruns only that shard and completes the merge.
# Exits 77 (ctest: skipped) with the reason when the daemons cannot start.
#   slurm_e2e.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
src=$(cd "$1" && pwd)
build=$(cd "$2" && pwd)
tmp=$(mktemp -d /tmp/rtcsim-slurm.XXXXXX)
cluster=$tmp/cluster
cleanup() {
  "$src/scripts/slurm-local" stop "$cluster" >/dev/null 2>&1 || true
  rm -rf "$tmp" 2>/dev/null || true
}
trap cleanup EXIT

if ! started=$("$src/scripts/slurm-local" start "$cluster" 2>&1); then
  echo "SKIPPED: cannot start a single-node Slurm here:"
  echo "$started"
  echo "(the shard/merge equality without a scheduler is tests/sim/test_shard.cpp)"
  exit 77
fi
eval "$started"  # export SLURM_CONF=...
echo "slurm: $(sinfo -h -o '%P %a %D %T' | head -n 1)"

sim=$build/simulate
config=$src/tests/configs/tiny.json
small=(--set output.rays=false --set output.hits=false --set workload.width=32 --set workload.height=32)
sweep=("${small[@]}" --set 'sweep={"scene.tilt_deg":[0,15,30,45],"scene.count":[5,20]}')
frame=("${small[@]}" --set workload.height=40)

# Waits until FILE exists, or fails after SECONDS with the queue and logs.
wait_for() {
  local file=$1 seconds=$2 t=0
  while [ ! -f "$file" ]; do
    if [ "$t" -ge "$((seconds * 2))" ]; then
      echo "timed out after ${seconds} s waiting for $file" >&2
      squeue >&2 || true
      tail -n 20 "$(dirname "$(dirname "$file")")"/logs/* >&2 2>/dev/null || true
      exit 1
    fi
    sleep 0.5
    t=$((t + 1))
  done
}
# Waits until no job of ours is queued or running.
wait_idle() {
  local t=0
  while [ -n "$(squeue -h -o %i 2>/dev/null)" ]; do
    [ "$t" -lt 240 ] || { echo "jobs still queued after 120 s" >&2; squeue >&2; exit 1; }
    sleep 0.5
    t=$((t + 1))
  done
}

echo "== sweep: 12 points, 4 shards"
"$sim" "$config" "${sweep[@]}" --quiet --threads 1 --out "$tmp/sweep-single"
"$src/scripts/slurm-submit" "$config" "${sweep[@]}" --shards 4 --cpus 1 --mem 1G --time 10 \
  --simulate "$sim" --out "$tmp/sweep"
wait_for "$tmp/sweep/merged/summary.csv" 120
wait_idle
python3 "$src/tests/sim/compare_outputs.py" "$tmp/sweep-single" "$tmp/sweep/merged"

echo "== one frame in 4 bands of rows, shard 2 cancelled and resumed"
"$sim" "$config" "${frame[@]}" --quiet --threads 1 --out "$tmp/frame-single"
# Held, so that shard 2 can be cancelled before it runs.
"$src/scripts/slurm-submit" "$config" "${frame[@]}" --shards 4 --cpus 1 --mem 1G --time 10 \
  --simulate "$sim" --out "$tmp/frame" -- --hold | tee "$tmp/submit.log"
array=$(sed -n 's/^array job \([0-9]*\):.*/\1/p' "$tmp/submit.log")
merge=$(sed -n 's/^merge job \([0-9]*\).*/\1/p' "$tmp/submit.log")
scancel "${array}_2"
scontrol release "$array" "$merge" 2>/dev/null || true
wait_idle  # the other shards run; the merge job can never start and is dropped
[ ! -e "$tmp/frame/merged/summary.csv" ] || { echo "merged without shard 2" >&2; exit 1; }
[ ! -e "$tmp/frame/shards/2/shard.json" ] || { echo "shard 2 ran although cancelled" >&2; exit 1; }
for i in 0 1 3; do [ -f "$tmp/frame/shards/$i/shard.json" ] || { echo "shard $i did not finish" >&2; exit 1; }; done
"$src/scripts/slurm-submit" --resume "$tmp/frame" | tee "$tmp/resume.log"
grep -q "shards 2 of 4" "$tmp/resume.log"
# --resume keeps the first submission's sbatch options, --hold included.
scontrol release "$(sed -n 's/^array job \([0-9]*\):.*/\1/p' "$tmp/resume.log")" \
  "$(sed -n 's/^merge job \([0-9]*\).*/\1/p' "$tmp/resume.log")"
wait_for "$tmp/frame/merged/summary.csv" 120
wait_idle
python3 "$src/tests/sim/compare_outputs.py" "$tmp/frame-single" "$tmp/frame/merged"
echo "slurm e2e: passed"
