"""A run killed (SIGKILL) at any moment, writing included, leaves nothing a
reader takes for a finished run: rtcsim.load_report / load_reports raise
rtcsim.InputError and `python3 -m rtcsim.plot` exits 2, naming the
directory, and `simulate merge` refuses a killed shard. (Killed after making
its directory but before marking it, a run leaves it empty: load_report
names the missing report.json, load_reports finds no report.) A kill that came too
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
        if not (out / ".rtcsim-output").exists():
            # Killed between making its directory and marking it: empty, and
            # nothing says it was simulate's. Refused as a missing report
            # (simulate merge's words for a shard's missing file).
            assert not any(out.iterdir()), f"{out}: files without simulate's mark"
            with pytest.raises(rtcsim.InputError, match=f"{out}/report.json: not found"):
                rtcsim.load_report(out)
            assert rtcsim.load_reports(out) == []
            continue
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


def test_an_unmarked_empty_directory_is_a_missing_report(tmp_path):
    # What a kill between simulate's mkdir and its mark leaves (rare in the
    # kills above): an InputError naming the file, not a FileNotFoundError.
    with pytest.raises(rtcsim.InputError, match=f"{tmp_path}/report.json: not found"):
        rtcsim.load_report(tmp_path)
    assert rtcsim.load_reports(tmp_path) == []


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


# -- Ctrl-C ----------------------------------------------------------------------
# Ctrl-C (SIGINT) stops a run promptly: rtcsim.run raises KeyboardInterrupt
# within a fraction of a second while it traces, writes no report.json (so
# rtcsim.load_report and `python3 -m rtcsim.plot` accept nothing), and the
# interpreter runs again afterwards; the `simulate` CLI exits 130 with its
# output directory marked unfinished and no temporaries left. The runs are
# made long (a 1200 x 1200 image on one thread, tens of seconds) and stopped
# a second into tracing (sim/execution/interrupt.h).
LONG = {"workload.width": 1200, "workload.height": 1200, "workload.spp": 4, "output.images": False,
        "output.rays": False, "output.hits": False}
PROMPT = 3.0  # seconds from SIGINT to the exception; a row of the long run takes milliseconds

CHILD = r"""
import sys, time, rtcsim
sets, out = eval(sys.argv[1]), sys.argv[2]
print("tracing", flush=True)
try:
    rtcsim.run(sys.argv[3], threads=1, progress=False, sets=sets, out=out)
    print("finished", flush=True)
except KeyboardInterrupt:
    print("KeyboardInterrupt at %.3f" % time.monotonic(), flush=True)
# Interrupted once, the interpreter and the module run again (the stop request was cleared).
r = rtcsim.run(sys.argv[3], threads=1, progress=False, sets={"workload.width": 8, "workload.height": 8,
                                                            "output.images": False})
print("again %.3f" % r.speedup("obb"), flush=True)
"""


def interrupt_after_start(args, delay=1.0, sig=signal.SIGINT):
    p = subprocess.Popen(args, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    assert p.stdout.readline().strip() == "tracing"
    time.sleep(delay)
    sent = time.monotonic()
    p.send_signal(sig)
    out, err = p.communicate(timeout=60)
    return p.returncode, out, err, sent


def test_ctrl_c_stops_rtcsim_run_with_keyboard_interrupt(tmp_path):
    out = tmp_path / "run"
    code, stdout, stderr, sent = interrupt_after_start(
        [sys.executable, "-c", CHILD, repr(LONG), str(out), TINY])
    assert code == 0, stderr
    assert "finished" not in stdout, "the long run ended before the interrupt: make it longer"
    line = next(s for s in stdout.splitlines() if s.startswith("KeyboardInterrupt"))
    assert float(line.split()[-1]) - sent < PROMPT
    assert any(s.startswith("again ") for s in stdout.splitlines())
    # Nothing finished-looking: no report.json, so no reader takes it for a run.
    assert not (out / "report.json").exists()
    # Marked unfinished as the CLI's directory is (issue 56: out= took no mark).
    assert "state: running" in (out / ".rtcsim-output").read_text()
    with pytest.raises(rtcsim.InputError, match="an unfinished simulate run"):
        rtcsim.load_report(out)
    with pytest.raises(rtcsim.InputError, match="an unfinished simulate run"):
        rtcsim.load_reports(out)
    plot = subprocess.run([sys.executable, "-m", "rtcsim.plot", out, "--out", tmp_path / "figures"],
                          capture_output=True, text=True, env=dict(os.environ, MPLBACKEND="Agg"))
    assert plot.returncode == 2 and "an unfinished simulate run" in plot.stderr, plot.stderr


def test_ctrl_c_stops_the_cli_with_its_directory_unfinished(simulate, tmp_path):
    exe = os.environ.get("RTCSIM_SIMULATE") or os.path.join(ROOT, "build", "simulate")
    out = tmp_path / "cli"
    sets = [a for k, v in LONG.items() for a in ("--set", f"{k}={str(v).lower()}")]
    # `echo tracing` marks the start, as the Python child prints it.
    code, stdout, stderr, sent = interrupt_after_start(
        ["sh", "-c", 'echo tracing; exec "$0" "$@"', exe, TINY, "--quiet", "--threads", "1", "--out", str(out),
         *sets])
    assert time.monotonic() - sent < PROMPT + 1
    assert code == 130, stderr
    assert "simulate: interrupted" in stderr
    mark = (out / ".rtcsim-output").read_text()
    assert "state: running" in mark
    assert not (out / "report.json").exists()
    assert not [p.name for p in out.rglob("*.partial")]  # unwound: OutputFile removed its temporary
    with pytest.raises(rtcsim.InputError, match="an unfinished simulate run"):
        rtcsim.load_report(out)
    merge = simulate("merge", out, "--out", tmp_path / "merged")
    assert merge.returncode == 2 and "an unfinished simulate run" in merge.stderr, merge.stderr


def test_sigterm_stops_the_cli_as_ctrl_c_does(simulate, tmp_path):
    # Issue 56: SIGTERM (what Slurm sends at a time limit) was not handled: it
    # killed the run with .partial files left and the mark saying running.
    exe = os.environ.get("RTCSIM_SIMULATE") or os.path.join(ROOT, "build", "simulate")
    out = tmp_path / "cli"
    sets = [a for k, v in LONG.items() for a in ("--set", f"{k}={str(v).lower()}")]
    code, stdout, stderr, sent = interrupt_after_start(
        ["sh", "-c", 'echo tracing; exec "$0" "$@"', exe, TINY, "--quiet", "--threads", "1", "--out", str(out),
         *sets], sig=signal.SIGTERM)
    assert time.monotonic() - sent < PROMPT + 1
    assert code == 143, stderr
    assert "simulate: terminated (SIGTERM)" in stderr
    assert "state: running" in (out / ".rtcsim-output").read_text()
    assert not (out / "report.json").exists()
    assert not [p.name for p in out.rglob("*.partial")]
    with pytest.raises(rtcsim.InputError, match="an unfinished simulate run"):
        rtcsim.load_report(out)


# -- Python writes outputs under the CLI's rules (issue 56) ------------------------
SMALL = {"workload.width": 8, "workload.height": 8, "output.images": False}


def test_python_out_is_refused_in_a_finished_cli_directory(simulate, tmp_path):
    # rtcsim.run(out=) wrote its report.json among a CLI run's files and left
    # the mark saying complete, so load_report trusted the mix.
    out = tmp_path / "cli"
    done = simulate(TINY, "--quiet", "--out", out, *[a for k, v in SMALL.items()
                                                     for a in ("--set", f"{k}={str(v).lower()}")])
    assert done.returncode == 0, done.stderr
    before = sorted(p.name for p in out.iterdir())
    with pytest.raises(rtcsim.InputError, match="output directory exists and is not empty"):
        rtcsim.run(TINY, progress=False, sets=SMALL, out=out)
    assert sorted(p.name for p in out.iterdir()) == before
    assert "state: complete" in (out / ".rtcsim-output").read_text()
    # With force, as the CLI's --force: emptied, written, marked complete.
    r = rtcsim.run(TINY, progress=False, sets=SMALL, out=out, limits={"force": True})
    assert rtcsim.load_report(out).data["name"] == r.name
    assert not (out / "results.csv").exists()  # the CLI's files are gone, not mixed in
    # Result.write_outputs follows the same rules.
    with pytest.raises(rtcsim.InputError, match="not empty"):
        r.write_outputs(out)
    r.write_outputs(out, force=True)
    fresh = tmp_path / "fresh"
    r.write_outputs(fresh)
    assert "state: complete" in (fresh / ".rtcsim-output").read_text()
    assert rtcsim.load_report(fresh).data["name"] == r.name
