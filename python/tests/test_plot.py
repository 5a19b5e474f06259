"""The matplotlib figures, from a live result and from finished CLI runs,
and `python3 -m rtcsim.plot report.json --out DIR`."""
import importlib.util
import math
import os
import re
import subprocess
import sys

import numpy as np
import pytest

import rtcsim
from conftest import ROOT, TINY
from rtcsim import plot

SWEEP = {"workload.width": 16, "workload.height": 16, "output.images": False,
         "sweep": {"scene.tilt_deg": [0, 30, 60], "scene.count": [10, 40]}}


@pytest.fixture(scope="module")
def sweep_dir(simulate, tmp_path_factory):
    out = tmp_path_factory.mktemp("sweep")
    sets = [a for k, v in SWEEP.items() for a in ("--set", f"{k}={__import__('json').dumps(v)}")]
    cli = simulate(TINY, "--quiet", "--out", out, *sets)
    assert cli.returncode == 0, cli.stderr
    return out


def saved(fig, path):
    fig.savefig(path)
    assert path.stat().st_size > 1000
    return path


def test_maps_from_a_live_result(tiny, tmp_path):
    fig = plot.heatmaps(tiny)
    assert len(fig.axes) == 3  # two maps and one shared colour bar
    bar = fig.axes[-1]
    # One scale for both methods: the CLI's (99.5th percentile of all pixels).
    both = np.concatenate([tiny.pixel_cycles(m).ravel() for m in ("ref", "obb")])
    assert bar.get_ylim()[1] == pytest.approx(np.percentile(both, 99.5))
    saved(fig, tmp_path / "heat.png")
    saved(plot.heatmap(tiny, "obb", "is_call"), tmp_path / "calls.png")
    saved(plot.heatmaps(tiny, log=True), tmp_path / "log.png")
    fig = plot.ratio_map(tiny)
    image = fig.axes[0].images[0]
    ratio = image.get_array()
    a, b = tiny.pixel_cycles("ref"), tiny.pixel_cycles("obb")
    on = (a > 0) & (b > 0)
    assert np.allclose(ratio[on], (a / b)[on])
    lo, hi = image.norm.vmin, image.norm.vmax
    assert lo == pytest.approx(1 / hi)  # centred at 1 on a log scale
    saved(fig, tmp_path / "ratio.png")
    saved(plot.render(tiny), tmp_path / "render.png")
    saved(plot.speedup_table(tiny), tmp_path / "table.png")
    saved(plot.cycle_breakdown(tiny), tmp_path / "breakdown.svg")


def test_break_even_matches_pricing(tiny, tmp_path):
    fig = plot.break_even(tiny, "context_switch", ["instance_transform"], (10, 1000), (1, 100), cells=8)
    rgb = fig.axes[0].images[0].get_array()
    assert rgb.shape == (8, 8, 3)
    # Corners: cheap switches favour ref, dear ones obb (the masquerade avoids them).
    model = rtcsim.load_cost_model("turing-per-ray-guess").copy()
    for (iy, ix) in ((0, 0), (7, 7), (0, 7), (7, 0)):
        c = model.cycles
        c[rtcsim.EVENT_INDEX["context_switch"]] = 10 * 100 ** ((ix + 0.5) / 8)
        c[rtcsim.EVENT_INDEX["instance_transform"]] = 100 ** ((iy + 0.5) / 8)
        model.cycles = c
        cycles = {m: rtcsim.price(tiny[m], model).total_cycles for m in ("ref", "obb")}
        best = min(cycles, key=cycles.get)
        leg = fig.axes[0].get_legend()
        handles = getattr(leg, "legend_handles", None) or leg.legendHandles  # matplotlib < 3.7
        legend = {t.get_text(): h.get_color() for t, h in zip(leg.get_texts(), handles)}
        want = np.array(__import__("matplotlib").colors.to_rgb(legend[best]))
        close = max(cycles.values()) / min(cycles.values()) < 1.1
        assert np.allclose(rgb[iy, ix], 0.55 * want + 0.45 if close else want)
    saved(fig, tmp_path / "break_even.png")
    config = dict(tiny.config, break_even=[{"name": "a", "preset": "turing-per-ray-guess", "cells": 4,
                                            "x": {"events": ["context_switch"], "min": 10, "max": 1000},
                                            "y": {"events": ["ray"], "min": 10, "max": 1000}}])
    tiny.data["config"], saved_config = config, tiny.data["config"]
    try:
        assert list(plot.break_even_maps(tiny)) == ["a"]
    finally:
        tiny.data["config"] = saved_config


def test_figures_from_reports(sweep_dir, tmp_path):
    runs = rtcsim.load_reports(sweep_dir)
    assert len(runs) == 6
    assert plot.numeric_axes(runs) == ["scene.count", "scene.tilt_deg"]
    fig = plot.speedup_vs_axis(runs, "scene.tilt_deg")
    lines = [line for line in fig.axes[0].get_lines() if line.get_marker() == "o"]
    assert len(lines) == 2  # one per count
    want = sorted((r.sweep_point["scene.tilt_deg"], r.speedup()) for r in runs
                  if r.sweep_point["scene.count"] == 10)
    line = next(line for line in lines if line.get_label() == "scene.count=10")
    assert list(line.get_xdata()) == [w[0] for w in want]
    assert np.allclose(line.get_ydata(), [w[1] for w in want])
    saved(fig, tmp_path / "tilt.png")
    fig = plot.speedup_vs_area_ratio({"bundles": runs, "extra": [(3.0, 1.5, "a point")]})
    texts = [t.get_text() for t in fig.axes[0].texts]
    assert "a point" in texts and runs[0].label in texts
    saved(fig, tmp_path / "area.svg")
    table = plot.speedup_table(runs)
    cells = table.axes[0].tables[0].get_celld()
    assert cells[(1, 0)].get_text().get_text() == runs[0].label
    with pytest.raises(ValueError, match="sweep axis"):
        plot.speedup_vs_axis(runs, "scene.radius")


def test_plot_command(sweep_dir, tmp_path):
    env = dict(os.environ, MPLBACKEND="Agg")
    first = next(sweep_dir.glob("0_*")) / "report.json"
    one = subprocess.run([sys.executable, "-m", "rtcsim.plot", str(first), "--out", str(tmp_path / "one")],
                         capture_output=True, text=True, env=env)
    assert one.returncode == 0, one.stderr
    assert sorted(os.listdir(tmp_path / "one")) == ["cycles_by_event.png", "speedup_table.png"]
    many = subprocess.run([sys.executable, "-m", "rtcsim.plot", str(sweep_dir), "--out", str(tmp_path / "many"),
                           "--format", "svg"], capture_output=True, text=True, env=env)
    assert many.returncode == 0, many.stderr
    assert sorted(os.listdir(tmp_path / "many")) == [
        "speedup_table.svg", "speedup_vs_area_ratio.svg", "speedup_vs_scene.count.svg",
        "speedup_vs_scene.tilt_deg.svg"]


PAIRED = {"workload.width": 16, "workload.height": 16, "output.images": False,
          "sweep": {"scene": [{"count": 10, "radius": 0.01}, {"count": 40, "radius": 0.005},
                              {"count": 20, "radius": 0.02}],
                    "scene.tilt_deg": [0, 30]}}


def test_a_paired_axis_is_one_axis_as_in_the_cli(simulate, tmp_path):
    out = tmp_path / "paired"
    sets = [a for k, v in PAIRED.items() for a in ("--set", f"{k}={__import__('json').dumps(v)}")]
    cli = simulate(TINY, "--quiet", "--out", out, *sets)
    assert cli.returncode == 0, cli.stderr
    runs = rtcsim.load_reports(out)
    # {count, radius} is one axis placed at count, as the CLI's speedup_vs_scene.svg.
    assert plot.numeric_axes(runs) == ["scene", "scene.tilt_deg"]
    cli_plots = sorted(p.name for p in out.glob("speedup_vs_*.svg")
                       if p.name not in ("speedup_vs_area_ratio.svg", "speedup_vs_memory.svg"))  # not sweep axes
    assert cli_plots == sorted(f"speedup_vs_{a}.svg" for a in plot.numeric_axes(runs))
    for axis in ("scene", "scene.count", "scene.radius"):  # by the axis or by either member
        fig = plot.speedup_vs_axis(runs, axis)
        lines = [line for line in fig.axes[0].get_lines() if line.get_marker() == "o"]
        assert sorted(line.get_label() for line in lines) == ["scene.tilt_deg=0", "scene.tilt_deg=30"]
        for line in lines:  # three points each, the reports' speedups
            tilt = int(line.get_label().split("=")[1])
            want = sorted((r.sweep_point["scene.count"], r.speedup()) for r in runs
                          if r.sweep_point["scene.tilt_deg"] == tilt)
            assert list(line.get_xdata()) == [w[0] for w in want]
            assert np.allclose(line.get_ydata(), [w[1] for w in want])
        assert fig.axes[0].get_xlabel() == "count, radius"
        assert sorted(t.get_text() for t in fig.axes[0].get_xticklabels()) == ["10, 0.01", "20, 0.02", "40, 0.005"]


def table_cycles_per_ray(result):
    """{method: cycles per ray} of the CLI's summary table (its primary preset)."""
    import csv
    import io
    row = next(csv.DictReader(io.StringIO(rtcsim.summary_table(result, "csv"))))
    return {m: float(row[f"{m} cyc/ray"]) for m in result.method_names}


def test_cycles_by_event_figure_is_the_table(tmp_path):
    # Under the warp preset the per-event prices of the per-ray model are not
    # the run's cycles (they were drawn as ~8x the table's): the bars stack
    # the warp model's units and end at the table's cycles per ray.
    for presets in (["turing-calibrated", "turing-per-ray-guess"], ["turing-per-ray-guess", "turing-calibrated"]):
        result = rtcsim.run(TINY, threads=2, progress=False,
                            sets={"output.images": False, "workload.width": 24, "workload.height": 24,
                                  "cost": presets})
        fig = plot.cycle_breakdown(result)  # the primary preset, as the table
        tops = {}
        for bar in fig.axes[0].patches:
            x = round(bar.get_x() + bar.get_width() / 2)
            tops[x] = max(tops.get(x, 0.0), bar.get_y() + bar.get_height())
        methods = [t.get_text() for t in fig.axes[0].get_xticklabels()]
        assert methods == ["ref", "obb"]
        table = table_cycles_per_ray(result)
        for i, m in enumerate(methods):
            assert tops[i] == pytest.approx(table[m], rel=1e-3), (presets[0], m)  # the table's 4 digits
            for p in presets:  # and every preset's, as report.json has it
                other = plot.cycle_breakdown(result, p)
                top = sum(b.get_height() for b in other.axes[0].patches if round(b.get_x() + b.get_width() / 2) == i)
                assert top == pytest.approx(result.cycles_per_ray(m, p)), (p, m)
        if presets[0] == "turing-calibrated":
            saved(fig, tmp_path / "warp.png")


# -- scripts/make_beyond.py --svg ------------------------------------------------------
# scripts/make_beyond.py --svg: the cluster Pareto plot agrees with the
# table printed beside it (each point, read back through the axis ticks, is a
# row's overhead and speedup as the table writes them), and its labels are
# legible: none overlaps another label or a point, and every point's cluster
# size is in the label at its position. Rows are made here in the shape
# make_beyond.rows() gives (four models, two strategies, sizes 1 to 256; a
# strand cluster stops growing at its strand, so its large sizes coincide),
# which drew 72 labels over each other before.
def make_beyond():
    spec = importlib.util.spec_from_file_location("make_beyond", os.path.join(ROOT, "scripts", "make_beyond.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


SIZES = [1, 2, 4, 8, 16, 32, 64, 128, 256]


def rows():
    out = []
    for m, scene in enumerate(["bear", "fur", "sintel", "stroke"]):
        for strategy in ("orientation", "strand"):
            for k in SIZES:
                grown = k if strategy == "orientation" else min(k, 4 + 4 * (m == 3))  # strands end
                over = (180.0 + 3 * m) / grown ** (1.2 if strategy == "orientation" else 0.8)
                speedup = 1.0 + (1.2 + 0.15 * m) / grown ** 0.45
                ref = {p: 100.0 * 2 ** 20 for p in ("memory-optix7", "memory-dxr", "memory-optix-record")}
                out.append({"scene": scene, "strategy": strategy, "size": k, "instances": 1000 // k + 1,
                            "runnable": True, "cyc": 50.0 / speedup, "is": 1.0, "inst": 1.0,
                            "speedup": [speedup, speedup * 0.9], "ref_mem": ref,
                            "mem": {p: v * (1 + over / 100.0) for p, v in ref.items()}, "build": 1.0})
    return out


def parse(svg):
    circles = [(float(x), float(y)) for x, y in re.findall(r'<circle cx="([\d.]+)" cy="([\d.]+)"', svg)]
    labels = [(float(x), float(y), t) for x, y, t in
              re.findall(r'<text x="([\d.]+)" y="([\d.]+)" font-size="9" fill="[^"]*" data-point="[^"]*">([^<]*)</text>', svg)]
    xticks = [(float(x), float(t)) for x, t in re.findall(r'<text x="([\d.]+)" y="\d+" text-anchor="middle">([\d.]+)</text>', svg)]
    yticks = [(float(y) - 4, float(t)) for y, t in re.findall(r'<text x="\d+" y="([\d.]+)" text-anchor="end">([\d.]+)</text>', svg)]
    return circles, labels, xticks, yticks


def linear(ticks):
    """value(pixel) through the first and last tick."""
    (p0, v0), (p1, v1) = ticks[0], ticks[-1]
    return lambda p: v0 + (p - p0) * (v1 - v0) / (p1 - p0)


def table_numbers(text):
    """(model, strategy, size) -> (speedup, overhead in %) as the table writes them."""
    out = {}
    for line in text.splitlines()[2:]:
        cells = [c.strip() for c in line.strip("|").split("|")]
        speedup = float(cells[7].split(" / ")[0].rstrip("x"))
        overhead = float(cells[9].split(" / ")[0].rstrip("%"))
        out[(cells[0], cells[1], int(cells[2]))] = (speedup, overhead)
    return out


def test_pareto_points_are_the_tables_and_labels_do_not_overlap(tmp_path):
    mb = make_beyond()
    rs = rows()
    path = tmp_path / "pareto.svg"
    mb.pareto_svg(rs, str(path))
    circles, labels, xticks, yticks = parse(path.read_text())
    table = table_numbers(mb.table(rs))
    assert len(circles) == len(rs) == len(table)

    # The figure's numbers are the table's (to the table's rounding and a pixel).
    over_at, speedup_at = linear(xticks), linear(yticks)
    px_over = (xticks[-1][1] - xticks[0][1]) / (xticks[-1][0] - xticks[0][0])
    px_speedup = abs((yticks[-1][1] - yticks[0][1]) / (yticks[-1][0] - yticks[0][0]))
    for (cx, cy), r in zip(circles, sorted(rs, key=lambda r: (r["scene"], r["strategy"]))):
        speedup, overhead = table[(r["scene"], r["strategy"], r["size"])]
        assert math.isclose(over_at(cx), overhead, abs_tol=0.5 + px_over), (r["scene"], r["size"])
        assert math.isclose(speedup_at(cy), speedup, abs_tol=0.005 * speedup + px_speedup), (r["scene"], r["size"])

    # Legible labels: boxes (as drawn: font 9, digits about 5.2 px wide) overlap neither each other nor a dot.
    boxes = [(x, y - 9, x + 5.2 * len(t), y) for x, y, t in labels]
    dots = [(x - 3, y - 3, x + 3, y + 3) for x, y in circles]
    for i, a in enumerate(boxes):
        for b in boxes[i + 1:] + dots:
            assert not (a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]), (labels[i], b)
    assert len(labels) < len(circles)  # coinciding points share a label

    # Every point's size is named by the label of its position ("4-256" covers 4, 8, ..., 256).
    named = {}
    for px, py, text in re.findall(r'data-point="(\d+) (\d+)">([^<]*)<', path.read_text()):
        for part in text.split(","):
            lo, _, hi = part.partition("-")
            k = int(lo)
            while k <= int(hi or lo):
                named.setdefault((int(px), int(py)), set()).add(k)
                k *= 2
    for (cx, cy), r in zip(circles, sorted(rs, key=lambda r: (r["scene"], r["strategy"]))):
        at = [k for (px, py), k in named.items() if abs(px - cx) <= 1 and abs(py - cy) <= 1]  # whole pixels
        assert any(r["size"] in k for k in at), (r["scene"], r["strategy"], r["size"])


def test_the_memory_records_table_is_the_presets():
    """docs/beyond.md's memory-records block is what make_beyond.py makes of
    configs/hw/memory-*.json now: a changed preset without a regenerated
    table fails here (rerun: scripts/make_beyond.py --update docs/beyond.md
    RUN_DIR)."""
    mb = make_beyond()
    block = mb.memory_records_block()
    with open(os.path.join(ROOT, "configs", "hw", "memory-dxr.json")) as f:
        dxr = __import__("json").load(f)["bytes"]
    assert "| `memory-dxr` | %d B | %d B |" % (dxr["instance"]["value"], dxr["blas"]["value"]) in block
    with open(os.path.join(ROOT, "docs", "beyond.md")) as f:
        assert block in f.read()
