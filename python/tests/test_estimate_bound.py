"""The work estimate bounds the measured peak of the run it estimates: the
cluster method at size 2 on a small procedural fur (50,000 capsules in
25,000 clusters, each its own BLAS: the term the estimate lacked when the
20 M fur was killed at 24.3 GB against an estimate of 7.82 GiB). The peak is
the child's own maximum resident set (os.wait4), not the test's."""
import json
import os
import subprocess

from conftest import ROOT

FUR = "configs/runs/cluster_fur20m.json"
SMALL = ["--set", "sweep={}", "--set", "scene.strands=12500", "--set", "cluster.size=2",
         "--set", "workload.width=32", "--set", "workload.height=32", "--set", "workload.spp=1",
         "--set", "cost=[\"turing-per-ray-guess\"]"]


def peak_bytes(args):
    p = subprocess.Popen(args, cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    _, status, usage = os.wait4(p.pid, 0)
    p.returncode = os.waitstatus_to_exitcode(status)
    err = p.stderr.read().decode()
    p.stderr.close()
    assert p.returncode == 0, err
    return usage.ru_maxrss * 1024  # kB on Linux


def test_the_estimate_bounds_the_peak_of_small_clusters(simulate, tmp_path):
    exe = os.environ.get("RTCSIM_SIMULATE") or os.path.join(ROOT, "build", "simulate")
    estimate = simulate(FUR, "--estimate", *SMALL)
    assert estimate.returncode == 0, estimate.stderr
    memory = json.loads(estimate.stdout.strip().splitlines()[-1])["memory_bytes"]
    measured = peak_bytes([exe, FUR, *SMALL, "--quiet", "--threads", "2", "--out", str(tmp_path / "out")])
    assert measured <= memory, f"peak {measured / 2**20:.0f} MiB above the estimate {memory / 2**20:.0f} MiB"
    # Not a bound by a mile: within 4x (measured 13.5 KB per cluster at scale, 16 KiB estimated).
    assert memory < 4 * measured
