"""Ctrl-C (SIGINT) stops a run promptly: rtcsim.run raises KeyboardInterrupt
within a fraction of a second while it traces, writes no report.json (so
rtcsim.load_report and `python3 -m rtcsim.plot` accept nothing), and the
interpreter runs again afterwards; the `simulate` CLI exits 130 with its
output directory marked unfinished and no temporaries left. The runs are
made long (a 1200 x 1200 image on one thread, tens of seconds) and stopped
a second into tracing (sim/util/interrupt.h)."""
import os
import signal
import subprocess
import sys
import time

import pytest

import rtcsim
from conftest import ROOT, TINY

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


def interrupt_after_start(args, delay=1.0):
    p = subprocess.Popen(args, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    assert p.stdout.readline().strip() == "tracing"
    time.sleep(delay)
    sent = time.monotonic()
    p.send_signal(signal.SIGINT)
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
    with pytest.raises((rtcsim.InputError, OSError)):
        rtcsim.load_report(out)
    assert rtcsim.load_reports(out) == []
    plot = subprocess.run([sys.executable, "-m", "rtcsim.plot", out, "--out", tmp_path / "figures"],
                          capture_output=True, text=True, env=dict(os.environ, MPLBACKEND="Agg"))
    assert plot.returncode == 2 and "no report.json found" in plot.stderr


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
