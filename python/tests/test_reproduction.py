"""scripts/make_reproduction.py on small reproduction runs: the tables of
docs/reproduction.md from the runs' reports, and its figures; and the
scorecard scripts/reproduce ends with (scripts/reproduction_scorecard.py)."""
import os
import re
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
        (TINY, "hair_tight", CALIBRATED + ["--set", 'sweep={"primitives": [{"kind": "phantom", "obb": "tight"}]}']),
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
    assert "\n## Synthetic table (calibrated preset)\n" in text
    # The calibration table is read from the shipped preset, and says so.
    assert "| `context_switch` | 200 | 100 |" in text and "from `configs/hw/turing-calibrated.json`" in text
    assert "| cells within +/-10 % |" in text
    # Every table says where it came from, with the overrides its runs were made with.
    assert re.search(r"runs of `configs/runs/fig3_bundles.json` \(`--set workload.width=8` .*\) at commit ", text)
    # --trace: the heat maps' table, stamped with the trace's commit.
    assert "Traced by `scripts/make_reproduction.py --trace 16`" in text and "at commit " in text
    for section in ("## hair", "## memory"):
        assert section in text
    # Every cell is the run's own speedup next to the paper's.
    fig3 = {(r.sweep_point["scene.count"], r.sweep_point["scene.tilt_deg"]): r
            for r in rtcsim.load_reports(runs / "fig3")}
    row = next(line for line in text.splitlines() if line.startswith("| 45 deg |"))
    cell = fig3[(1000, 45)]
    assert (f"3.20 / {cell.speedup('obb', 'turing-per-ray-calibrated'):.2f} / "
            f"**{cell.speedup('obb', 'turing-calibrated'):.3f}**") in row
    assert "| tiny | phantom /1 | 60 |" in text
    assert "| tiny | 60 | memory-dxr |" in text
    # The tight-OBB table: each tight run beside the hair run of the same kind, stamped with both.
    tight = text.split("## Tighter OBBs\n", 1)[1]
    row = next(line for line in tight.splitlines() if line.startswith("| tiny | phantom /1 | "))
    assert row.count(" -> ") == 3
    assert "of the same config with `\"obb\": \"tight\"`" in tight.split("\n## ", 1)[0]
    assert sorted(os.listdir(images)) == [
        "fig3_n1000_r0.002_45deg_cycles_obb.png", "fig3_n1000_r0.002_45deg_cycles_ref.png",
        "fig3_n1000_r0.002_45deg_ratio.png", "fig3_speedup_vs_tilt.svg", "speedup_vs_area_ratio.svg"]
    svg = (images / "speedup_vs_area_ratio.svg").read_text()
    assert "synthetic bundles" in svg and "hair models" in svg

    # The scorecard scripts/reproduce ends with, on the same runs: the
    # synthetic cells counted against the paper, what is missing, the charts.
    out = subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "reproduction_scorecard.py"), str(runs),
                          "--images", str(images), "--mode", "quick"],
                         capture_output=True, text=True, env=dict(os.environ, MPLBACKEND="Agg"))
    assert out.returncode == 0, out.stderr
    card = out.stdout
    assert card == (runs / "scorecard.md").read_text()
    within = sum(abs(r.speedup("obb", "turing-calibrated") / paper - 1) <= 0.10
                 for tilt, row in PAPER.items() for (n, paper) in zip((1, 10, 100, 1000), row)
                 for r in [fig3[(n, tilt)]])
    assert f"| synthetic table (the fit's own data) | {within} of 16 |" in card
    assert "- Table 1: no runs in curly/." in card and "Quick mode:" in card
    assert (images / "fig3_paper_vs_simulated.svg").stat().st_size > 0
    assert not (images / "table1_paper_vs_simulated.svg").exists()  # no Table 1 runs, no chart


def test_make_reproduction_radius_table(simulate, tmp_path):
    """The radius table sets each cell of the three radius runs side by side,
    and says whether the paper's value lies in the range they span."""
    runs = tmp_path / "runs"
    # Named as the paper's model (a sweep's scene name labels its cells), so its cells are compared.
    sweep = ["--set", 'sweep={"scene.name": ["curly lock"], "primitives": [{"kind": "capsule"}, {"kind": "phantom"}]}']
    for name, radius in (("curly_thin", 0.002), ("curly", 0.01), ("curly_thick", 0.03)):
        cli = simulate(TINY, "--quiet", "--out", runs / name, *SMALL, *CALIBRATED, *sweep,
                       "--set", f"scene.radius={radius}")
        assert cli.returncode == 0, cli.stderr
    out = subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "make_reproduction.py"), str(runs),
                          "--images", str(tmp_path / "images")],
                         capture_output=True, text=True, env=dict(os.environ, MPLBACKEND="Agg"))
    assert out.returncode == 0, out.stderr
    table = out.stdout.split("\n## Table 1 at three hair radii\n", 1)[1].split("\n## ", 1)[0]
    by_radius = {name: {r.kind: r.speedup("obb", "turing-calibrated") for r in rtcsim.load_reports(runs / name)}
                 for name in ("curly_thin", "curly", "curly_thick")}
    row = next(line for line in table.splitlines() if line.startswith("| curly lock | capsule | 3.82x |"))
    cells = [by_radius[n]["capsule"] for n in ("curly_thin", "curly", "curly_thick")]
    assert row.startswith("| curly lock | capsule | 3.82x | " + " | ".join(f"{v:.2f}x" for v in cells) + " | ")
    inside = min(cells) <= 3.82 <= max(cells)
    assert row.endswith("| yes |") if inside else "| no (" in row
    assert "Paper values within the range the three radii span: " in table
    assert "curly lock: " in table and "(paper 50.4)" in table  # the phantom /1 over capsule cost ratios
    assert "--set scene.radius=0.002" in table  # the runs' overrides, in the stamp


PAPER = {0: [1.05, 1.03, 1.04, 1.04], 15: [1.16, 1.16, 2.01, 3.83],  # the paper's synthetic table
         30: [1.10, 1.21, 1.91, 3.32], 45: [1.12, 1.22, 1.90, 3.20]}


def test_make_reproduction_update(simulate, tmp_path):
    """--update rewrites each generated block of a Markdown file in place and
    leaves the text around it; a block the runs cannot make stays as it was."""
    runs = tmp_path / "runs"
    cli = simulate(TINY, "--quiet", "--out", runs / "memory", *SMALL, *CALIBRATED,
                   "--set", 'sweep={"memory": ["memory-optix7", "memory-dxr"]}')
    assert cli.returncode == 0, cli.stderr
    doc = tmp_path / "doc.md"
    marker = "<!-- generated by scripts/make_reproduction.py {}: {} -->"
    doc.write_text("before\n" + marker.format("memory", "begin") + "\nold table\n" + marker.format("memory", "end") +
                   "\nbetween\n" + marker.format("hair", "begin") + "\nold hair\n" + marker.format("hair", "end") +
                   "\nafter\n")
    out = subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "make_reproduction.py"), str(runs),
                          "--images", str(tmp_path / "images"), "--update", str(doc)],
                         capture_output=True, text=True, env=dict(os.environ, MPLBACKEND="Agg"))
    assert out.returncode == 0, out.stderr
    text = doc.read_text()
    assert "old table" not in text and "| tiny | 60 | memory-dxr |" in text
    assert "runs of `configs/runs/" in text and "at commit " in text
    assert "old hair" in text and "no runs for" in out.stderr
    assert text.startswith("before\n") and "\nbetween\n" in text and text.endswith("\nafter\n")
