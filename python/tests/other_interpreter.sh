#!/usr/bin/env bash
# Importing rtcsim under an interpreter it was not built for (one without
# NumPy, such as a pyenv python3 first on PATH) fails with one line naming the
# interpreter to use; build/rtcsim-python runs that one. Exit 77 (skipped)
# when this machine has no such other interpreter.
#   python/tests/other_interpreter.sh BUILD_DIR
set -euo pipefail
build=$1
built_for=$(sed -n 's/^BUILT_FOR = "\(.*\)"$/\1/p' "$build/python/rtcsim/_interpreter.py")
"$build/rtcsim-python" -c "import rtcsim" || { echo "build/rtcsim-python cannot import rtcsim"; exit 1; }
other=""
for py in $(type -ap python3 python) /root/.pyenv/shims/python3; do
  [ -x "$py" ] || continue
  [ "$(realpath "$py")" = "$(realpath "$built_for")" ] && continue
  if ! "$py" -c "import numpy" 2>/dev/null; then other=$py; break; fi
done
if [ -z "$other" ]; then echo "skipped: no interpreter without NumPy here"; exit 77; fi
if err=$(PYTHONPATH="$build/python" "$other" -c "import rtcsim" 2>&1); then
  echo "rtcsim imported under $other, which has no NumPy"; exit 1
fi
last=$(printf '%s\n' "$err" | tail -n 1)
case "$last" in
  "ImportError: rtcsim was built for $built_for"*"run $built_for instead"*) echo "ok: $other -> $last" ;;
  *) echo "unexpected last line under $other: $last"; exit 1 ;;
esac
