"""rtcsim.plot's break-even maps draw the calibration's 90 % band as the CLI
does: exactly the cells of break_even_<name>.json whose band of the winner's
lead reaches 1.0 are hatched (sim/plot/break_even.cpp,
tests/output/test_break_even_band.cpp)."""
import json
import os

import numpy as np
import pytest

import rtcsim
from rtcsim import plot
from rtcsim.plot_break_even import HATCH_GID, PALETTE

from conftest import ROOT, TINY

CELLS = 12
X = {"events": ["context_switch"], "min": 1, "max": 1000}
Y = {"events": ["instance_transform"], "min": 1, "max": 100}


@pytest.fixture(scope="module")
def band_run(tmp_path_factory):
    """The tiny bundle under the fitted warp preset, with 32 cost draws and one
    map whose break-even line crosses it; its outputs written as the CLI's."""
    with open(os.path.join(ROOT, TINY)) as f:
        config = json.load(f)
    config["cost"] = ["../../configs/hw/turing-calibrated.json"]
    config["output"] = {"images": False}
    config["uncertainty"] = {"draws": 32, "seed": 3}
    config["break_even"] = [{"name": "band", "preset": "turing-calibrated", "cells": CELLS, "x": X, "y": Y}]
    result = rtcsim.run(config, base=os.path.join(ROOT, TINY), threads=2, progress=False)
    out = tmp_path_factory.mktemp("band")
    result.write_outputs(out)
    return result, out


def hatched(fig, cells):
    """The (iy, ix) cells the figure hatches, from its patches' positions."""
    ax = fig.axes[0]
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    w, h = (x1 - x0) / cells["nx"], (y1 - y0) / cells["ny"]
    out = set()
    for p in ax.patches:
        if p.get_gid() != HATCH_GID:
            continue
        assert p.get_hatch() and p.get_width() == pytest.approx(w) and p.get_height() == pytest.approx(h)
        out.add((round((p.get_y() - y0) / h), round((p.get_x() - x0) / w)))
    return out


def expected(cells):
    """The JSON's cells in doubt: a winner, and the band's low end at or below 1.0."""
    nx = cells["nx"]
    return {(i // nx, i % nx) for i, (w, lo) in enumerate(zip(cells["winner"], cells["band_low"]))
            if w >= 0 and lo is not None and lo <= 1.0}


def test_cells_map_hatches_the_cells_in_doubt(band_run):
    _, out = band_run
    path = out / "break_even_band.json"
    cells = json.loads(path.read_text())
    assert cells["draws"] == 32 and len(cells["band_low"]) == CELLS * CELLS
    want = expected(cells)
    # A map worth testing: some cells in doubt, most not.
    assert 0 < len(want) < CELLS * CELLS / 2
    fig = plot.break_even_cells(path)
    assert hatched(fig, cells) == want
    assert {tuple(c) for c in np.argwhere(plot.in_doubt(cells))} == want
    # Hue: the JSON's winner of every cell.
    rgb = fig.axes[0].images[0].get_array()
    names = cells["methods"]
    for i, w in enumerate(cells["winner"]):
        iy, ix = divmod(i, cells["nx"])
        full = np.array(__import__("matplotlib").colors.to_rgb(PALETTE[w]))
        m = cells["margin"][i]
        assert np.allclose(rgb[iy, ix], 0.55 * full + 0.45 if m is not None and m < 1.1 else full), names[w]
    fig.savefig(out / "band.png")


def test_live_map_hatches_the_same_cells(band_run):
    result, out = band_run
    cells = json.loads((out / "break_even_band.json").read_text())
    fig = plot.break_even(result, X["events"], Y["events"], (X["min"], X["max"]), (Y["min"], Y["max"]),
                          "turing-calibrated", cells=CELLS, band=out / "break_even_band.json")
    assert hatched(fig, cells) == expected(cells)
    with pytest.raises(ValueError, match="grid"):
        plot.break_even(result, X["events"], Y["events"], (X["min"], X["max"]), (Y["min"], Y["max"]),
                        "turing-calibrated", cells=CELLS + 1, band=cells)


def test_maps_of_a_report_on_disk_carry_the_band(band_run):
    _, out = band_run
    report = rtcsim.load_report(out / "report.json")
    figs = plot.break_even_maps(report)
    assert list(figs) == ["band"]
    cells = json.loads((out / "break_even_band.json").read_text())
    assert hatched(figs["band"], cells) == expected(cells)
    # The share in doubt that report.json states is the hatched share.
    entry = report.data["break_even"][0]
    assert entry["uncertain_share"] == pytest.approx(len(expected(cells)) / (CELLS * CELLS))


def test_make_beyond_reads_the_boundary_and_its_band_from_the_cells(band_run):
    """scripts/beyond_hardware.py's "where obb stops paying": along the mark's
    row, the winners in order, the cost where they change (between the two
    cells' centres) and the span of the hatched cells there."""
    import importlib.util
    spec = importlib.util.spec_from_file_location("beyond_hardware", os.path.join(ROOT, "scripts", "beyond_hardware.py"))
    bh = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(bh)
    _, out = band_run
    cells = json.loads((out / "break_even_band.json").read_text())
    doubt = plot.in_doubt(cells)
    centre = lambda a, i, n: a["lo"] * (a["hi"] / a["lo"]) ** ((i + 0.5) / n)
    for iy in range(CELLS):
        y = centre(cells["y"], iy, CELLS)
        parts, span = bh._crossings(cells, "x", y)
        row = cells["winner"][iy * CELLS:(iy + 1) * CELLS]
        changes = [ix for ix in range(1, CELLS) if row[ix] != row[ix - 1]]
        assert [p[0] for p in parts] == [cells["methods"][row[0]]] + [cells["methods"][row[ix]] for ix in changes]
        for (_, at), ix in zip(parts[1:], changes):
            assert centre(cells["x"], ix - 1, CELLS) < at < centre(cells["x"], ix, CELLS)
        hatched_x = [centre(cells["x"], ix, CELLS) for ix in np.nonzero(doubt[iy])[0]]
        assert span == ((min(hatched_x), max(hatched_x)) if hatched_x else None)
