"""Speedup intervals from a preset's covariance (docs/calibration.md): the
CLI's report.json and results.csv carry them, `speedup_interval` reads
them, a preset without a covariance has none (and says why), and the plots
show them (table text, a band on the sweep curve)."""
import csv
import json
import os

import rtcsim
from conftest import ROOT, TINY
from rtcsim import plot


def preset_with_covariance(tmp_path):
    with open(os.path.join(ROOT, "configs/hw/turing-per-ray-guess.json")) as f:
        j = json.load(f)
    j["name"] = "guess-with-covariance"
    j["uncertainty"] = {
        "source": "test",
        "parameters": [
            {"events": ["context_switch"], "tie": "value", "value": j["cycles"]["context_switch"]["value"],
             "min": 50, "max": 1000, "free": True},
            {"events": ["tlas_box_test", "blas_box_test"], "tie": "scale", "value": 1.0, "min": 0.25, "max": 4,
             "free": True}],
        "covariance": [[0.04, -0.01], [-0.01, 0.09]]}
    path = tmp_path / "guess-with-covariance.json"
    path.write_text(json.dumps(j))
    return str(path)


def test_intervals_through_the_cli(simulate, tmp_path):
    preset = preset_with_covariance(tmp_path)
    out = tmp_path / "out"
    sets = {"cost": [preset, "turing-per-ray-guess"], "uncertainty": {"draws": 16, "seed": 2},
            "workload.width": 16, "workload.height": 16, "output.images": False, "output.arrays": False,
            "sweep": {"scene.tilt_deg": [0, 45]}}
    args = [a for k, v in sets.items() for a in ("--set", f"{k}={json.dumps(v)}")]
    cli = simulate(TINY, "--quiet", "--threads", "2", "--out", out, *args)
    assert cli.returncode == 0, cli.stderr
    reports = rtcsim.load_reports(out)
    assert len(reports) == 2
    for r in reports:
        s = r.speedup("obb")
        low, high = r.speedup_interval("obb")
        assert low <= s <= high and low < high
        assert r.speedup_interval("obb", preset="turing-per-ray-guess") is None
        assert "no covariance" in r.uncertainty_note("turing-per-ray-guess")
        assert "16 draws" in r.uncertainty_note(0)
    rows = list(csv.DictReader(open(out / "results.csv")))
    obb = [row for row in rows if row["method"] == "obb"]
    with_interval = [row for row in obb if row["cost_preset"] == "guess-with-covariance"]
    assert all(float(row["speedup_low"]) <= float(row["speedup"]) <= float(row["speedup_high"])
               for row in with_interval)
    assert all(row["speedup_low"] == "" for row in obb if row["cost_preset"] == "turing-per-ray-guess")
    assert " [" in (out / "summary.md").read_text()
    assert "fill-opacity" in (out / "speedup_vs_scene.tilt_deg.svg").read_text()  # the band
    fig = plot.speedup_vs_axis(reports, "scene.tilt_deg")
    assert len(fig.axes[0].collections) == 1  # one shaded band, around the one curve
    fig = plot.speedup_table(reports)
    texts = [c.get_text().get_text() for c in fig.axes[0].tables[0].get_celld().values()]
    assert any(t.endswith("]") and "x [" in t for t in texts)


def test_sampling_intervals_through_the_cli(simulate, tmp_path):
    """A sampled run (docs/sampling.md): `sampling_interval` reads each
    speedup's 95 % sampling interval, report.json says the fraction and
    seed; an unsampled run has none."""
    sets = {"workload.width": 32, "workload.height": 32, "output.images": False, "output.arrays": False}
    args = [a for k, v in sets.items() for a in ("--set", f"{k}={json.dumps(v)}")]
    for sample in (["--sample", "0.25", "--sample-seed", "3"], []):
        out = tmp_path / ("sampled" if sample else "full")
        cli = simulate(TINY, "--quiet", "--threads", "2", "--out", out, *args, *sample)
        assert cli.returncode == 0, cli.stderr
        r = rtcsim.load_report(out)
        if not sample:
            assert r.sampling_interval("obb") is None and "sampling" not in r.data
            continue
        assert r.data["sampling"]["fraction"] == 0.25 and r.data["sampling"]["seed"] == 3
        low, high = r.sampling_interval("obb")
        assert low <= r.speedup("obb") <= high and low < high
        row = [row for row in csv.DictReader(open(out / "results.csv")) if row["method"] == "obb"][0]
        assert float(row["sampling_low"]) == low and float(row["sampling_high"]) == high
