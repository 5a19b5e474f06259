"""A break-even map drawn from Python is the CLI's map of the same run, cell
by cell (issue 55): Python prices no cell itself but asks the simulator
(rtcsim.plot.break_even_grid -> break_even_grid, sim/report/break_even_maps.cpp).
The run is under the fitted warp preset, whose cells price the recorded
waves and whose obb_box_test is a sum of blas_box_test and
instance_transform: what a per-ray `totals @ costs` in Python got wrong."""
import json
import math

import pytest

import rtcsim
from rtcsim import plot

from conftest import TINY

X = {"events": ["context_switch"], "min": 1, "max": 1000}
Y = {"events": ["instance_transform"], "min": 1, "max": 100}
MAPS = [
    {"name": "switch_vs_transform", "preset": "turing-calibrated", "cells": 10, "x": X, "y": Y},
    # A factor axis and a map of a subset of methods, as a config may ask.
    {"name": "factor", "preset": "turing-calibrated", "cells": 6, "methods": ["obb", "ref"],
     "x": {"events": ["is_call", "context_switch"], "min": 0.1, "max": 10, "scale": True},
     "y": {"events": ["instance_transform"], "min": 1, "max": 100}},
]
SETS = {"cost": ["turing-calibrated", "turing-per-ray-guess"],
        "workload.width": 32, "workload.height": 32, "output.images": False, "output.arrays": False,
        "output.rays": False, "output.hits": False, "uncertainty": {"draws": 16, "seed": 5}, "break_even": MAPS}


def cli_args(sets):
    return [a for k, v in sets.items() for a in ("--set", f"{k}={json.dumps(v)}")]


@pytest.fixture(scope="module")
def runs(simulate, tmp_path_factory):
    """The same config through `simulate` (its files) and through rtcsim.run."""
    out = tmp_path_factory.mktemp("cli")
    cli = simulate(TINY, "--quiet", "--threads", 2, "--out", out, *cli_args(SETS))
    assert cli.returncode == 0, cli.stderr
    result = rtcsim.run(TINY, threads=2, progress=False, sets=SETS)
    return out, result


def file_number(v):
    """A number as break_even_<name>.json writes it (4 significant digits; None: not finite)."""
    return float(f"{v:.4g}") if math.isfinite(v) else None


@pytest.mark.parametrize("spec", MAPS, ids=[m["name"] for m in MAPS])
def test_python_map_is_the_cli_map(runs, spec):
    out, result = runs
    assert result.costs[0].is_warp
    cli = json.loads((out / f"break_even_{spec['name']}.json").read_text())
    grid = plot.break_even_grid(result, spec)
    assert "warp model" in grid["caption"]  # the waves priced, not per-ray totals
    assert grid["methods"] == cli["methods"]
    assert (grid["nx"], grid["ny"], grid["draws"]) == (cli["nx"], cli["ny"], cli["draws"]) and cli["draws"] == 16
    for k in ("x", "y"):
        assert grid[k] == cli[k]
    # Every cell: the winner exactly, the lead and its band as the file
    # rounds them (4 digits).
    assert grid["winner"].ravel().tolist() == cli["winner"]
    assert [file_number(v) for v in grid["margin"].ravel()] == cli["margin"]
    assert [file_number(v) for v in grid["band_low"].ravel()] == cli["band_low"]
    assert [file_number(v) for v in grid["band_high"].ravel()] == cli["band_high"]
    # A map worth comparing: more than one winner, some cells in doubt.
    assert len(set(cli["winner"])) > 1 and 0 < grid["in_doubt"].sum() < grid["in_doubt"].size
    # report.json keeps the lead at the preset's own costs unrounded.
    report = json.loads((out / "report.json").read_text())
    mark = next(m for m in report["break_even"] if m["name"] == spec["name"])["mark"]
    assert (grid["mark"]["x"], grid["mark"]["y"]) == (mark["x"], mark["y"])
    assert grid["mark"]["winner"] == mark["winner"]
    assert grid["mark"]["lead"] == pytest.approx(mark["lead"], rel=1e-9)
    assert grid["mark"]["lead_interval"] == pytest.approx(mark["lead_interval"], rel=1e-9)


def test_figures_draw_the_cli_cells(runs):
    """plot.break_even and a live Result's break_even_maps draw those cells."""
    out, result = runs
    cli = json.loads((out / "break_even_switch_vs_transform.json").read_text())
    fig = plot.break_even(result, X["events"], Y["events"], (X["min"], X["max"]), (Y["min"], Y["max"]),
                          "turing-calibrated", cells=10)
    rgb = fig.axes[0].images[0].get_array()
    colours = {tuple(rgb[i // 10, i % 10]) for i, w in enumerate(cli["winner"]) if cli["margin"][i] >= 1.1}
    assert len(colours) == len({w for w, m in zip(cli["winner"], cli["margin"]) if m >= 1.1})
    assert list(plot.break_even_maps(result)) == [m["name"] for m in MAPS]


def test_a_map_is_checked_as_a_config_map_is(runs):
    out, result = runs
    with pytest.raises(rtcsim.InputError, match="/break_even/y/events/0: unknown event"):
        plot.break_even(result, "context_switch", "no_such_event", preset="turing-calibrated")
    with pytest.raises(rtcsim.InputError, match="/break_even/methods/0: \"lss\" is not one of the run's methods"):
        plot.break_even(result, "context_switch", "ray", methods=["lss", "obb"])
    with pytest.raises(TypeError, match="live Result"):
        plot.break_even_grid(rtcsim.load_report(out / "report.json"), MAPS[0])
