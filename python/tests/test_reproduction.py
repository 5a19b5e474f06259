"""scripts/make_reproduction.py on small reproduction runs: the tables of
docs/reproduction.md from the runs' reports, and its figures."""
import os
import subprocess
import sys

import rtcsim
from conftest import ROOT, TINY

SMALL = ["--set", "workload.width=8", "--set", "workload.height=8", "--set", "output.images=false"]
CALIBRATED = ["--set", 'cost=["turing-calibrated"]']


def test_make_reproduction(simulate, tmp_path):
    runs = tmp_path / "runs"
    steps = [
        ("configs/runs/fig3_bundles.json", "fig3", ["--set", "workload.spp=1"]),
        (TINY, "hair", CALIBRATED + ["--set", 'sweep={"primitives.kind": ["capsule", "phantom"]}']),
        (TINY, "memory", CALIBRATED + ["--set", 'sweep={"memory": ["memory-optix7", '
                                                '"memory-dxr"]}']),
    ]
    for config, name, extra in steps:
        cli = simulate(config, "--quiet", "--out", runs / name, *SMALL, *extra)
        assert cli.returncode == 0, cli.stderr
    images = tmp_path / "images"
    out = subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "make_reproduction.py"), str(runs),
                          "--images", str(images), "--trace", "16"],
                         capture_output=True, text=True, env=dict(os.environ, MPLBACKEND="Agg"))
    assert out.returncode == 0, out.stderr
    text = out.stdout
    assert text.startswith("## Synthetic table (calibrated preset)\n")
    assert "of 16 cells within +/-10%" in text
    for section in ("## hair", "## memory"):
        assert section in text
    # Every cell is the run's own speedup next to the paper's.
    fig3 = {(r.sweep_point["scene.count"], r.sweep_point["scene.tilt_deg"]): r
            for r in rtcsim.load_reports(runs / "fig3")}
    row = next(line for line in text.splitlines() if line.startswith("| 45 deg |"))
    assert f"3.20x / {fig3[(1000, 45)].speedup('obb', 'turing-calibrated'):.2f}x" in row
    assert "| tiny | phantom /1 | 60 |" in text
    assert "| tiny | 60 | memory-dxr |" in text
    assert sorted(os.listdir(images)) == [
        "fig3_n1000_r0.002_45deg_cycles_obb.png", "fig3_n1000_r0.002_45deg_cycles_ref.png",
        "fig3_n1000_r0.002_45deg_ratio.png", "fig3_speedup_vs_tilt.svg", "speedup_vs_area_ratio.svg"]
    svg = (images / "speedup_vs_area_ratio.svg").read_text()
    assert "synthetic bundles" in svg and "hair models" in svg
