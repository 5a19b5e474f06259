"""Break-even maps as matplotlib figures: which method is cheapest as two
costs change, and where the calibration's 90 % band leaves that in doubt.

Two sources, one picture:
- `break_even(result, x_events, y_events, ...)` maps a live Result, its
  cells computed by the simulator exactly as the CLI's (break_even_grid;
  any two event groups);
- `break_even_cells(cells)` draws a map the simulator computed: the
  `break_even_<name>.json` written beside `break_even_<name>.png` by the CLI
  and `Result.write_outputs` (warp model where the preset is one, and the band
  over the run's cost draws).
A cell whose band of the winner's lead reaches 1.0 (another method wins in
more than 5 % of the draws) is hatched, as in the CLI's pictures
(sim/plot/break_even.cpp): a live map by its own band (the CLI's, unrounded),
or with `break_even(..., band=cells)` by a file's. `in_doubt(cells)` is a
file's mask. Python prices no cell itself.
"""
import json
import os

import numpy as np
from matplotlib import colors, ticker
from matplotlib.figure import Figure
from matplotlib.patches import Rectangle

from . import _rtcsim

PALETTE = ["#0072B2", "#E69F00", "#009E73", "#CC79A7", "#56B4E9", "#D55E00", "#F0E442", "#000000"]
HATCH_GID = "break-even band"  # the gid of every hatched cell's patch


def load_cells(cells):
    """A break_even_<name>.json as a dict (a path, or the dict itself)."""
    if isinstance(cells, (str, os.PathLike)):
        with open(cells) as f:
            return json.load(f)
    return cells


def in_doubt(cells):
    """(ny, nx) bool, row 0 the lowest y: cells with a winner whose 90 % band
    of its lead reaches 1.0 (BreakEvenGrid::uncertain). All False without draws.
    The file keeps 4 significant digits, so a band ending within 5e-5 above
    1.0 counts as reaching it here and not in the CLI's picture."""
    cells = load_cells(cells)
    ny, nx = cells["ny"], cells["nx"]
    winner = np.asarray(cells["winner"]).reshape(ny, nx)
    low = cells.get("band_low") or []
    if not low:
        return np.zeros((ny, nx), bool)
    low = np.array([np.inf if v is None else v for v in low], float).reshape(ny, nx)
    return (winner >= 0) & (low <= 1.0)


def _draw(winner, margin, names, x_range, y_range, x_label, y_label, title, doubt=None, draws=0, mark=None):
    """The map: hue = winner, pale = a close call (runner-up within 10 %),
    hatched = in doubt over the draws."""
    ny, nx = winner.shape
    rgb = np.array([colors.to_rgb(PALETTE[i % len(PALETTE)]) for i in range(max(len(names), 1))])[np.maximum(winner, 0)]
    rgb = np.where((margin < 1.1)[..., None], 0.55 * rgb + 0.45, rgb)
    rgb = np.where((winner < 0)[..., None], 1.0, rgb)  # no method runs: white
    fig = Figure(figsize=(6.4, 5), layout="constrained")
    ax = fig.add_subplot()
    x0, x1, y0, y1 = (*np.log10(x_range), *np.log10(y_range))
    ax.imshow(rgb, origin="lower", extent=(x0, x1, y0, y1), aspect="auto", interpolation="nearest")
    if doubt is not None and doubt.any():
        w, h = (x1 - x0) / nx, (y1 - y0) / ny
        for iy, ix in zip(*np.nonzero(doubt)):
            ax.add_patch(Rectangle((x0 + ix * w, y0 + iy * h), w, h, fill=False, hatch="////", linewidth=0,
                                   edgecolor="#333333", gid=HATCH_GID))
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    for axis, lo, hi in ((ax.xaxis, x0, x1), (ax.yaxis, y0, y1)):  # ticks at 1, 2, 5 x 10^k (log10 positions)
        k = np.arange(np.floor(lo), np.ceil(hi) + 1)
        at = np.log10(np.outer(10.0 ** k, [1, 2, 5]).ravel())
        axis.set_major_locator(ticker.FixedLocator(at[(at >= lo - 1e-9) & (at <= hi + 1e-9)]))
        axis.set_major_formatter(ticker.FuncFormatter(lambda v, _: f"{10 ** v:.4g}"))
    ax.set_xlabel(x_label)
    ax.set_ylabel(y_label)
    for i, name in enumerate(names):
        ax.plot([], [], "s", color=PALETTE[i % len(PALETTE)], label=name)
    if doubt is not None and draws:
        ax.add_patch(Rectangle((0, 0), 0, 0, fill=False, hatch="////", edgecolor="#333333",
                               label=f"in doubt: the 90 % band\nof the lead over {draws} draws\nreaches 1.0"))
    if mark is not None:
        ax.plot([np.log10(mark[0])], [np.log10(mark[1])], "k+", markersize=12, label="the preset")
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1))
    ax.set_title(title, fontsize=10)
    return fig


def break_even_grid(result, spec):
    """One map's cells of a live Result, computed by the simulator exactly as
    the CLI computes break_even_<name>.json (sim/report/break_even_maps.cpp):
    `spec` is a config's break_even entry (name, preset, x, y, cells,
    methods). Under a warp preset the cells price the recorded waves, costs
    made of others (sum_of) follow the axes, and the band is over the run's
    cost draws. A dict of (ny, nx) arrays (row 0 the lowest y): winner (index
    into methods, -1 none), margin (runner-up / winner cycles, unrounded),
    band_low, band_high and in_doubt; plus the mark and the caption."""
    run = getattr(result, "_run", None)
    if run is None:
        raise TypeError("break-even maps re-price a live Result (rtcsim.run); for a report on disk, "
                        "draw the CLI's cells with break_even_cells(\"break_even_<name>.json\")")
    return _rtcsim.break_even_grid(run, json.dumps(spec), result.file)


def _grid_figure(grid, title, band=None):
    """A live map's figure: hatched where the grid's own band (or, given,
    `band`: the CLI's cells of the same grid) leaves the winner in doubt."""
    doubt, draws = (grid["in_doubt"], grid["draws"]) if grid["draws"] else (None, 0)
    if band is not None:
        band = load_cells(band)
        have = (band["nx"], band["ny"], band["x"]["lo"], band["x"]["hi"], band["y"]["lo"], band["y"]["hi"])
        want = (grid["nx"], grid["ny"], grid["x"]["lo"], grid["x"]["hi"], grid["y"]["lo"], grid["y"]["hi"])
        if have != want:
            raise ValueError(f"band: its grid (nx, ny, x, y) = {have} is not this map's {want}")
        doubt, draws = in_doubt(band), band.get("draws", 0)
    mark = grid["mark"]
    return _draw(grid["winner"], grid["margin"], grid["methods"], (grid["x"]["lo"], grid["x"]["hi"]),
                 (grid["y"]["lo"], grid["y"]["hi"]), grid["x"]["label"], grid["y"]["label"], title,
                 doubt=doubt, draws=draws, mark=(mark["x"], mark["y"]))


def break_even(result, x_events, y_events, x_range=(1, 100), y_range=(1, 100), preset=None, cells=48,
               title=None, band=None, methods=None):
    """Which method is cheapest when two groups of event costs change (log
    axes, the other costs from `preset`), computed by the simulator as the
    CLI's break_even maps (break_even_grid): the same cells as a config's
    map of the same run. Pale cells: a close call (the runner-up within
    10%); hatched: in doubt over the run's cost draws. `band`: instead, the
    CLI's cells of the same grid (break_even_<name>.json, a path or dict)
    hatch it. `methods`: the methods compared (default: all the run's)."""
    x_events = [x_events] if isinstance(x_events, str) else list(x_events)
    y_events = [y_events] if isinstance(y_events, str) else list(y_events)
    p = result.preset_index(preset)
    spec = {"name": "python", "preset": result.costs[p].name, "cells": cells,
            "x": {"events": x_events, "min": x_range[0], "max": x_range[1]},
            "y": {"events": y_events, "min": y_range[0], "max": y_range[1]}}
    if methods is not None:
        spec["methods"] = list(methods)
    grid = break_even_grid(result, spec)
    return _grid_figure(grid, title or f"{result.label}: fastest method (other costs: {result.cost_presets[p]})",
                        band=band)


def break_even_cells(cells, title=None, mark=None):
    """The map the simulator computed (break_even_<name>.json: winners,
    margins and the band over the run's draws), hatched where in doubt.
    `mark`: (x, y) of the preset's own costs (report.json's break_even mark)."""
    c = load_cells(cells)
    ny, nx = c["ny"], c["nx"]
    winner = np.asarray(c["winner"]).reshape(ny, nx)
    margin = np.array([np.inf if v is None else v for v in c["margin"]], float).reshape(ny, nx)
    names = [n for n in c["methods"]]
    return _draw(winner, margin, names, (c["x"]["lo"], c["x"]["hi"]), (c["y"]["lo"], c["y"]["hi"]),
                 c["x"]["label"], c["y"]["label"], title or "fastest method", doubt=in_doubt(c),
                 draws=c.get("draws", 0), mark=mark)


def break_even_maps(result, directory=None):
    """{name: Figure} for the config's break_even list. From the CLI's cells
    (with the band) when they are on disk: in `directory`, or beside a
    report.json loaded from a file; else computed from a live Result by the
    simulator (break_even_grid), the same cells."""
    directory = directory or (os.path.dirname(result.path) if getattr(result, "path", None) else None)
    out = {}
    marks = {m["name"]: m for m in result.data.get("break_even", [])}
    for spec in result.config.get("break_even", []):
        path = os.path.join(directory, f"break_even_{spec['name']}.json") if directory else None
        if path and os.path.isfile(path):
            mark = marks.get(spec["name"], {}).get("mark")
            out[spec["name"]] = break_even_cells(path, title=f"{result.label}: {spec['name']} ({spec['preset']})",
                                                 mark=(mark["x"], mark["y"]) if mark else None)
        else:  # the config's own map, every key of it (scale axes, methods) as the CLI reads it
            out[spec["name"]] = _grid_figure(break_even_grid(result, spec),
                                             f"{result.label}: {spec['name']} ({spec['preset']})")
    return out
