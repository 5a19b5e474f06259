#!/bin/sh
# Two simulate runs started together on one --out (other seeds, so their
# files differ), 20 times: exactly one exits 0 and leaves a directory equal,
# file for file, to a run of its seed alone; the other exits 2 naming the
# directory. Usage: output_race.sh SIMULATE SOURCE_DIR WORK_DIR
set -u
sim=$1 src=$2 work=$3
cfg=$src/tests/configs/tiny.json
rm -rf "$work" && mkdir -p "$work" || exit 1
run() {  # run SEED OUT
    "$sim" "$cfg" --quiet --threads 1 --set workload.width=16 --set workload.height=16 \
        --set output.rays=false --set output.hits=false --set scene.seed="$1" --out "$2"
}
for seed in 1 2; do run $seed "$work/solo$seed" >/dev/null || exit 1; done
i=0
while [ $i -lt 20 ]; do
    out=$work/race
    rm -rf "$out"
    run 1 "$out" >/dev/null 2>"$work/err1" & p1=$!
    run 2 "$out" >/dev/null 2>"$work/err2" & p2=$!
    wait $p1; r1=$?
    wait $p2; r2=$?
    case "$r1 $r2" in
        "0 2") win=1 lose=2 ;;
        "2 0") win=2 lose=1 ;;
        *) echo "trial $i: exit codes $r1 and $r2 (one 0 and one 2 expected)"; cat "$work/err1" "$work/err2"; exit 1 ;;
    esac
    if ! grep -q "^$out: output directory" "$work/err$lose"; then
        echo "trial $i: the refused run's message does not name $out:"; cat "$work/err$lose"; exit 1
    fi
    mv "$out" "$work/trial$i" && echo "$work/trial$i $work/solo$win" >>"$work/pairs"
    i=$((i + 1))
done
# Each winner's directory against the run of its seed alone, both ways (one
# Python process for all 20).
python3 - "$src/tests/sim" "$work/pairs" <<'PY' || exit 1
import sys
sys.path.insert(0, sys.argv[1])
from compare_outputs import main
bad = 0
for line in open(sys.argv[2]):
    got, solo = line.split()
    bad += main(got, solo) + main(solo, got)
sys.exit(1 if bad else 0)
PY
echo "output race test passed: 20 trials"
