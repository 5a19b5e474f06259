#!/bin/bash
# Under a file-size limit (ulimit -f) a write fails: simulate exits 2 naming
# the file, whether SIGXFSZ is ignored by the caller (the write returns EFBIG,
# which stb's PNG writer alone would not notice) or not (simulate ignores it
# itself). Usage: write_limit.sh SIMULATE SOURCE_DIR WORK_DIR
set -u
sim=$1 src=$2 work=$3
rm -rf "$work" && mkdir -p "$work" || exit 1
run() {  # run OUT: only PNGs to write, the first larger than the limit
    "$sim" "$src/tests/configs/tiny.json" --quiet --threads 1 --set workload.width=64 --set workload.height=64 \
        --set output.arrays=false --set output.rays=false --set output.hits=false --out "$1"
}
for mode in ignored default; do
    out=$work/$mode
    (
        ulimit -f 2  # KiB: report.json, the tables and the mark fit, not a 64 x 64 PNG
        [ $mode = ignored ] && trap '' XFSZ
        run "$out"
    ) >/dev/null 2>"$work/err"
    rc=$?
    echo "SIGXFSZ $mode: exit $rc: $(cat "$work/err")"
    if [ $rc -ne 2 ] || ! grep -Eq "^$out/[a-z_]+\.png: write failed \(File too large\)$" "$work/err"; then
        echo "expected exit 2 and one line naming the PNG"; exit 1
    fi
    for f in "$out"/*; do  # no cut file: a PNG written before the limit ends with its IEND chunk
        case "$f" in
            *.partial) echo "$f left behind"; exit 1 ;;
            *.png) [ "$(tail -c 8 "$f" | od -An -tx1 | tr -d ' \n')" = 49454e44ae426082 ] || { echo "$f is cut"; exit 1; } ;;
        esac
    done
done
echo "write limit test passed"
