"""A run from Python is the CLI's run: report.json identical but for the
wall-clock timings, the same summary table, the same files when asked to
write them; the thread count changes nothing; tracing releases the GIL."""
import json
import threading
import time

import pytest

import rtcsim
from conftest import TINY

TIMINGS = ("build_seconds", "trace_seconds", "rays_per_second")


def without_timings(report):
    report = json.loads(json.dumps(report))
    report.pop("wall_seconds", None)
    report.pop("provenance", None)  # date, threads, command line
    for m in report["methods"].values():
        for key in TIMINGS:
            m.get("simulator", {}).pop(key, None)
    return report


def test_report_identical_to_cli(simulate, tiny, tmp_path):
    cli = simulate(TINY, "--quiet", "--threads", 2, "--set", "output.images=false", "--out", tmp_path)
    assert cli.returncode == 0, cli.stderr
    with open(tmp_path / "report.json") as f:
        expected = json.load(f)
    assert without_timings(tiny.data) == without_timings(expected)
    # The terminal table too.
    assert rtcsim.summary_table(tiny) in cli.stdout
    # And the speedup printed from Python is the CLI's.
    assert tiny.speedup("obb") == expected["speedup_over_ref"]["obb"]["turing-per-ray-guess"]


def test_sweep_identical_to_cli(simulate, tmp_path):
    sets = ["workload.width=16", "workload.height=16", "output.images=false",
            'sweep={"scene.tilt_deg": [0, 45], "scene.count": [10, 30]}']
    cli = simulate(TINY, "--quiet", "--out", tmp_path, *[a for s in sets for a in ("--set", s)])
    assert cli.returncode == 0, cli.stderr
    expected = rtcsim.load_reports(tmp_path)
    runs = rtcsim.sweep(TINY, progress=False, sets=sets)
    assert [r.label for r in runs] == [r.label for r in expected] == [  # the first key written varies slowest
        "scene.tilt_deg=0 scene.count=10", "scene.tilt_deg=0 scene.count=30",
        "scene.tilt_deg=45 scene.count=10", "scene.tilt_deg=45 scene.count=30"]
    for got, want in zip(runs, expected):
        assert without_timings(got.data) == without_timings(want.data)
    assert runs[0]["obb"].pixel_counts.size == 0  # sweeps drop per-pixel data, as the CLI does
    assert rtcsim.summary_table(runs) in cli.stdout


def test_writes_the_cli_files(simulate, tmp_path):
    result = rtcsim.run(TINY, threads=2, progress=False, out=tmp_path / "py")
    cli = simulate(TINY, "--quiet", "--threads", 2, "--out", tmp_path / "cli")
    assert cli.returncode == 0, cli.stderr
    py_files = sorted(p.name for p in (tmp_path / "py").iterdir())
    # The same files but the tables over runs (and the mark, which Python writes too: issue 56).
    assert py_files == sorted(p.name for p in (tmp_path / "cli").iterdir() if p.suffix not in (".csv", ".md"))
    assert "state: complete" in (tmp_path / "py" / ".rtcsim-output").read_text()
    for name in ("rays.bin", "hits_ref.bin", "hits_obb.bin", "heat_cycles_obb.png"):
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name
    # Rays are recorded once (every method traces the same) when written to files.
    assert len(result["ref"].rays) == result["ref"].rays_traced
    assert len(result["obb"].hits) == result["obb"].rays_traced


def test_thread_count_changes_nothing(tiny):
    one = rtcsim.run(TINY, threads=1, progress=False, sets={"output.images": False})
    assert without_timings(one.data) == without_timings(tiny.data)
    for name in ("ref", "obb"):
        assert (one[name].pixel_counts == tiny[name].pixel_counts).all()


def test_tracing_releases_the_gil():
    # A Python thread keeps counting while another thread traces.
    ticks = []
    stop = threading.Event()

    def tick():
        while not stop.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.001)

    sets = {"workload.width": 320, "workload.height": 320, "output": {"images": False}}
    ticker = threading.Thread(target=tick)
    ticker.start()
    try:
        start = time.perf_counter()
        result = rtcsim.run(TINY, threads=1, progress=False, sets=sets)
        end = time.perf_counter()
    finally:
        stop.set()
        ticker.join()
    during = [t for t in ticks if start < t < end]
    trace = sum(m.trace_seconds for m in result.methods.values())
    if trace < 0.05:
        pytest.skip(f"tracing took {trace:.3f} s: too short to tell")
    assert len(during) >= 10, f"{len(during)} ticks in {end - start:.3f} s of tracing"


def test_simulate_entry_point(tmp_path):
    assert rtcsim.simulate(TINY, "--quiet", "--set", "output.images=false", "--set", "workload.width=8",
                           "--out", tmp_path) == 0
    assert (tmp_path / "report.json").exists()
    assert rtcsim.simulate(["--help"]) == 0
    assert rtcsim.simulate(TINY, "--quiet", "--set", "workload.spp=-4", "--out", tmp_path) == 2
