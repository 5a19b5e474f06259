#!/usr/bin/env bash
# `pip install .` as a Python user does it, offline: into a venv made with
# --system-site-packages (NumPy, setuptools and wheel from Debian), with
# --no-build-isolation and --no-index (nothing downloaded). The module is
# taken from this build (RTCSIM_BUILD_DIR: setup.py builds the _rtcsim target
# there, a no-op when it is up to date) instead of a second CMake build.
# Then, from a directory outside the repository, the installed package
# imports, finds its presets, runs the quickstart config through the API and
# through `python -m rtcsim`, and writes a report. Exit 77 (skipped) when the
# interpreter has no venv module.
#   tests/packaging/pip_install_venv.sh PYTHON SOURCE_DIR BUILD_DIR
set -euo pipefail
python=$1 src=$2 build=$3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
if ! "$python" -m venv --system-site-packages "$work/V" >"$work/venv.log" 2>&1; then
  cat "$work/venv.log"; echo "skipped: $python -m venv failed (python3-venv missing?)"; exit 77
fi
cd "$work"
if ! RTCSIM_BUILD_DIR="$build" V/bin/pip install --no-build-isolation --no-index -q "$src" >pip.log 2>&1; then
  cat pip.log; echo "pip install failed"; exit 1
fi
cp "$src/configs/runs/quickstart.json" "$work/quickstart.json"  # a config outside the repository
unset RTCSIM_PRESET_DIR PYTHONPATH
V/bin/python - "$work" <<'PY'
import os, sys
work = sys.argv[1]
import rtcsim
assert rtcsim.__file__.startswith(os.path.join(work, "V")), rtcsim.__file__  # the installed package
assert os.path.isfile(os.path.join(rtcsim.PRESET_DIR, "turing-calibrated.json")), rtcsim.PRESET_DIR
r = rtcsim.run("quickstart.json", threads=2, progress=False,
               sets={"workload.width": 48, "workload.height": 48, "workload.spp": 1})
s = r.speedup("obb")
assert s and s > 1, s
print(f"ok: import rtcsim from {os.path.dirname(rtcsim.__file__)}, quickstart at 48 x 48: obb {s:.2f}x")
PY
V/bin/python -m rtcsim quickstart.json --out out --quiet --threads 2 \
  --set workload.width=48 --set workload.height=48 --set workload.spp=1 --set output.images=false
test -s out/report.json
echo "ok: python -m rtcsim wrote out/report.json"
# The installed package's own presets are searched, wherever the source went.
err=$(V/bin/python -m rtcsim quickstart.json --estimate --set 'cost=["no-such-preset"]' 2>&1 || true)
case "$err" in
  *"$work/V/lib/"*"/site-packages/rtcsim/configs/hw"*) echo "ok: presets searched in the installed package" ;;
  *) echo "the installed package's presets are not searched: $err"; exit 1 ;;
esac
