"""A run killed (SIGKILL) at any moment, writing included, leaves nothing a
reader takes for a finished run: rtcsim.load_report / load_reports raise
rtcsim.InputError and `python3 -m rtcsim.plot` exits 2, naming the
directory, and `simulate merge` refuses a killed shard. A kill that came too
late (the run had finished) leaves a directory equal to an undisturbed run's.
The output directory's mark (.rtcsim-output) says `state: complete` only
after the last file (sim/app/output_dir.h)."""
import os
import signal
import subprocess
import sys
import time

import pytest

import rtcsim
from conftest import ROOT, TINY

SETS = ["--quiet", "--threads", "1", "--set", "workload.width=128", "--set", "workload.height=128",
        "--set", "workload.spp=1", "--set", "output.rays=false", "--set", "output.hits=false"]
KILLS = 8


def exe():
    path = os.environ.get("RTCSIM_SIMULATE") or os.path.join(ROOT, "build", "simulate")
    if not os.path.exists(path):
        pytest.skip("no simulate executable (set RTCSIM_SIMULATE)")
    return path


def finished(directory):
    try:
        with open(os.path.join(directory, ".rtcsim-output")) as f:
            return "state: complete\n" in f.read()
    except OSError:
        return False


def timed_run(args):
    start = time.monotonic()
    subprocess.run([exe(), *map(str, args)], cwd=ROOT, check=True, capture_output=True)
    return time.monotonic() - start


def killed_run(args, after):
    p = subprocess.Popen([exe(), *map(str, args)], cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    time.sleep(after)
    p.send_signal(signal.SIGKILL)
    p.wait()


def same_outputs(a, b):
    compare = os.path.join(ROOT, "tests", "sim", "compare_outputs.py")
    return all(subprocess.run([sys.executable, compare, x, y], capture_output=True).returncode == 0
               for x, y in ((a, b), (b, a)))


def test_a_killed_run_is_refused_by_python_and_plot(tmp_path):
    solo = tmp_path / "solo"
    seconds = timed_run([TINY, *SETS, "--out", solo])
    refused = written = 0
    for k in range(KILLS):
        out = tmp_path / f"kill{k}"
        killed_run([TINY, *SETS, "--out", out], seconds * (k + 0.5) / KILLS)
        if not out.exists():
            continue  # killed before it made its directory
        if finished(out):
            assert same_outputs(out, solo), f"{out}: finished, but not as the undisturbed run"
            continue
        refused += 1
        message = f"{out}: an unfinished simulate run"
        with pytest.raises(rtcsim.InputError, match=message):
            rtcsim.load_report(out)
        with pytest.raises(rtcsim.InputError, match=message):
            rtcsim.load_reports(out)
        if (out / "report.json").exists() or any(p.suffix in (".npy", ".png") for p in out.iterdir()):
            written += 1  # killed while writing
            with pytest.raises(rtcsim.InputError, match=message):
                rtcsim.load_report(out / "report.json")
            plot = subprocess.run([sys.executable, "-m", "rtcsim.plot", out, "--out", tmp_path / "figures"],
                                  capture_output=True, text=True)
            assert plot.returncode == 2, plot.stderr
            assert plot.stderr.strip() == f"python3 -m rtcsim.plot: {message} (.rtcsim-output does not say " \
                "complete: it failed, was killed, or is still running)"
    print(f"{refused} of {KILLS} kills before the end, {written} while writing")
    assert refused > 0


def test_a_killed_shard_is_refused_by_merge(simulate, tmp_path):
    solo = tmp_path / "solo"
    seconds = timed_run([TINY, *SETS, "--shard", "0/1", "--out", solo])
    for k in range(4):
        shard = tmp_path / f"shard{k}"
        killed_run([TINY, *SETS, "--shard", "0/1", "--out", shard], seconds * (k + 0.5) / 4)
        merge = simulate("merge", shard, "--quiet", "--out", tmp_path / f"merged{k}")
        if finished(shard):
            assert merge.returncode == 0, merge.stderr
        else:
            assert merge.returncode == 2, merge.stderr
            # The directory's mark, or (killed before it made one) shard.json missing.
            assert merge.stderr.startswith(f"{shard}: an unfinished simulate run") or \
                merge.stderr.startswith(f"{shard}/shard.json: not found"), merge.stderr
