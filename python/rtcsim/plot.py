"""The paper's views as matplotlib figures: the speedup table, speedup
against a sweep axis, speedup against the AABB/OBB surface-area ratio with
labelled points, per-pixel heat maps and ratio maps with colour bars.

Functions take Reports (report.json; rtcsim.load_reports) or live Results
(rtcsim.run); heat and ratio maps need a live Result's per-pixel arrays.
Each returns a matplotlib Figure (no pyplot state: safe in scripts, tests
and notebooks); save it with fig.savefig(path).

    python3 -m rtcsim.plot out/quickstart/report.json --out figures/
"""
import argparse
import math
import os
import sys

import matplotlib
import numpy as np
from matplotlib import colors, ticker
from matplotlib.figure import Figure

from .axes import axis_index, sweep_axes
from .report import Report, load_report, load_reports


def _reports(runs):
    if isinstance(runs, (Report, str, os.PathLike)):
        runs = [runs]
    return [r if isinstance(r, Report) else load_report(r) for r in runs]


def _fmt(x, digits=3):
    return "n/a" if x is None else f"{x:.{digits}g}"


# -- tables and sweeps -----------------------------------------------------------
def _speedup_text(r, method, preset):
    """"2.86x [2.61-3.10]", as the terminal table writes it (no interval: "2.86x")."""
    s = r.speedup(method, preset)
    if not s:
        return "n/a"
    i = r.speedup_interval(method, preset)
    return f"{s:.2f}x" + (f" [{i[0]:.2f}-{i[1]:.2f}]" if i else "")


def speedup_table(runs, preset=None, title=None):
    """One row per run: rays, cycles and IS calls per ray of each method,
    speedup of each method over the baseline, AABB/OBB area, memory overhead."""
    runs = _reports(runs)
    methods = list(dict.fromkeys(m for r in runs for m in r.method_names))
    base = runs[0].baseline
    others = [m for m in methods if m != base]
    header = ["run", "kind", "prims", "rays"] + [f"{m} cyc/ray" for m in methods] + \
             [f"{m} IS/ray" for m in methods] + [f"{m} speedup" for m in others] + \
             ["AABB/OBB area"] + [f"{m} mem" for m in others]
    rows = []
    for r in runs:
        have = [m for m in methods if m in r.method_names]
        rays = next((r.rays(m) for m in have if r.runnable(m)), None)
        row = [r.label, r.kind, f"{r.primitives:,}", f"{rays:,}" if rays else "-"]
        row += [_fmt(r.cycles_per_ray(m, preset), 4) if m in have else "-" for m in methods]
        row += [_fmt(r.is_per_ray(m), 4) if m in have else "-" for m in methods]
        row += [_speedup_text(r, m, preset) for m in others]
        row.append(_fmt(r.area_ratio(), 3))
        row += [f"{o:.0f}%" if (o := r.memory_overhead(m)) is not None else "-" for m in others]
        rows.append(row)
    chars = sum(max(len(str(c)) for c in col) + 2 for col in zip(header, *rows))
    fig = Figure(figsize=(min(0.4 + 0.075 * chars, 24), 0.8 + 0.3 * (len(rows) + 1)), layout="constrained")
    ax = fig.add_subplot()
    ax.axis("off")
    table = ax.table(cellText=rows, colLabels=header, loc="center", cellLoc="right")
    table.auto_set_font_size(False)
    table.set_fontsize(8)
    table.auto_set_column_width(list(range(len(header))))
    for (row, _), cell in table.get_celld().items():
        if row == 0:
            cell.set_text_props(weight="bold")
            cell.set_facecolor("#eeeeee")
    preset_name = runs[0]._preset(preset)
    ax.set_title(title or f"speedup over {base} ({preset_name})")
    return fig


def speedup_vs_axis(runs, axis, preset=None, method=None, title=None, log_x=None):
    """Speedup of `method` (default: every non-baseline method) against a
    sweep axis (a key, or a paired axis by its key or any member's: see
    sweep_axes), one line per combination of the other axes' values: the
    series of the CLI's speedup_vs_<axis>.svg."""
    runs = _reports(runs)
    axes = sweep_axes(runs)
    found = next((a for a in axes if axis == a["key"] or axis in a["keys"]), None)
    if found is None:
        raise ValueError(f"no run has the sweep axis {axis!r}")
    others = [a for a in axes if a is not found]
    methods = [method] if method else list(dict.fromkeys(m for r in runs for m in r.others))
    series = {}
    for m in methods:
        for r in runs:
            rest = ", ".join(a["legend"][axis_index(a, r)] for a in others)
            key = rest if len(methods) == 1 else (f"{m}, {rest}" if rest else m)
            s = r.speedup(m, preset)
            low, high = (r.speedup_interval(m, preset) if s else None) or (math.nan, math.nan)
            x = found["x"][axis_index(found, r)]
            pts = series.setdefault(key or m, [])
            if all(p[0] != x for p in pts):  # a point already there for its series is not repeated
                pts.append((x, s if s else math.nan, low, high))
    fig = Figure(figsize=(7, 4.5), layout="constrained")
    ax = fig.add_subplot()
    for key, pts in series.items():
        pts.sort()
        line, = ax.plot([p[0] for p in pts], [p[1] for p in pts], marker="o", label=key,
                        linestyle="-" if found["numeric"] else "none")  # categories are not joined
        if any(not math.isnan(p[2]) for p in pts):  # the 90 % interval of the draws, as a band
            ax.fill_between([p[0] for p in pts], [p[2] for p in pts], [p[3] for p in pts],
                            color=line.get_color(), alpha=0.18, linewidth=0)
    xs = found["x"]
    if log_x or (log_x is None and found["numeric"] and min(xs) > 0 and max(xs) / min(xs) >= 100):
        ax.set_xscale("log")
    if len(found["keys"]) > 1 or not found["numeric"]:  # ticks name each value, as the CLI's
        ax.set_xticks(xs, found["tick"])
        ax.xaxis.set_minor_locator(ticker.NullLocator())
    ax.axhline(1.0, color="#888888", lw=0.8, ls="--")
    base = runs[0].baseline
    who = methods[0] if len(methods) == 1 else "each method"
    ax.set_xlabel(found["name"])
    ax.set_ylabel(f"speedup ({base} cycles / {who} cycles)")
    ax.set_title(title or f"speedup of {who} over {base} vs {found['name']} ({runs[0]._preset(preset)})")
    ax.grid(True, alpha=0.3)
    if len(series) > 1 or next(iter(series)) != methods[0]:
        ax.legend(fontsize=8)
    return fig


def numeric_axes(runs):
    """The sweep axes placed on a number (sweep_axes), by key: a single key
    ("scene.tilt_deg") or a paired axis's common prefix ("scene")."""
    return [a["key"] for a in sweep_axes(_reports(runs)) if a["numeric"]]


def _plain_log_ticks(ax, xs, ys):
    """Log axes labelled 1, 2, 5, 10 (x) and 0.75x, 1x, 1.5x, 2x (y), not 10^k."""
    ax.xaxis.set_major_locator(ticker.LogLocator(subs=(1, 2, 5)))
    ax.xaxis.set_major_formatter(ticker.FuncFormatter(lambda v, _: f"{v:g}"))
    ax.xaxis.set_minor_formatter(ticker.NullFormatter())
    if ys:
        lo, hi = min(ys) / 1.1, max(ys) * 1.1
        ticks = [v for v in (0.25, 0.5, 0.75, 1, 1.25, 1.5, 2, 2.5, 3, 4, 5, 6, 8, 10, 15, 20) if lo <= v <= hi]
        ax.yaxis.set_major_locator(ticker.FixedLocator(ticks))
    ax.yaxis.set_major_formatter(ticker.FuncFormatter(lambda v, _: f"{v:g}x"))
    ax.yaxis.set_minor_formatter(ticker.NullFormatter())


def speedup_vs_area_ratio(groups, preset=None, method=None, labels=True, fit=True, title=None):
    """Speedup against the AABB/OBB surface-area ratio (paper OBBs), log-log.

    groups: runs (one group), or {group name: runs or [(ratio, speedup, label)]}.
    labels: label each point with its run's label (or the given label).
    fit: a least-squares line through all points (log-log)."""
    if not isinstance(groups, dict):
        groups = {"runs": groups}
    fig = Figure(figsize=(7.5, 5), layout="constrained")
    ax = fig.add_subplot()
    allx, ally = [], []
    for name, members in groups.items():
        pts = []
        for m in members:
            if isinstance(m, tuple):
                pts.append(m)
                continue
            r = m if isinstance(m, Report) else load_report(m)
            s = r.speedup(method, preset)
            if s:
                pts.append((r.area_ratio(), s, r.label))
        if not pts:
            continue
        ax.scatter([p[0] for p in pts], [p[1] for p in pts], label=name, alpha=0.8, s=24)
        if labels:
            for x, y, text in pts:
                if text:
                    ax.annotate(text, (x, y), xytext=(4, 3), textcoords="offset points", fontsize=7)
        allx += [p[0] for p in pts]
        ally += [p[1] for p in pts]
    if fit and len(allx) >= 2 and len(set(allx)) > 1:
        lx, ly = np.log(allx), np.log(ally)
        slope, icept = np.polyfit(lx, ly, 1)
        xs = np.geomspace(min(allx), max(allx), 50)
        ax.plot(xs, np.exp(icept) * xs ** slope, color="#888888", lw=1, ls="--",
                label=f"least squares (log-log), slope {slope:.2f}")
    ax.set_xscale("log")
    ax.set_yscale("log")
    _plain_log_ticks(ax, allx, ally)
    ax.set_xlabel("sum of AABB areas / sum of OBB areas (paper OBBs)")
    ax.set_ylabel("speedup over the baseline")
    ax.set_title(title or "speedup vs AABB/OBB surface-area ratio")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    return fig


def cycle_breakdown(run, preset=None, title=None):
    """Cycles per ray of each method under a preset, stacked: by event under
    a per-ray preset, by unit (shader, RT unit, hand-off, programs) under a
    warp preset, whose cycles are the warps' and not the sum of per-event
    prices. Either way each bar is the table's cycles per ray."""
    r = _reports(run)[0]
    methods = [m for m in r.method_names if r.runnable(m) and r.cycles(m, preset) is not None]
    warp = any(r.warp_breakdown(m, preset) is not None for m in methods)
    parts = {m: (r.warp_breakdown(m, preset) if warp else r.cycle_breakdown(m, preset)) or {} for m in methods}
    names = list(dict.fromkeys(e for m in methods for e in parts[m]))
    fig = Figure(figsize=(7, 4.5), layout="constrained")
    ax = fig.add_subplot()
    bottom = np.zeros(len(methods))
    for e in names:
        v = np.array([parts[m].get(e, 0.0) / max(r.rays(m), 1) for m in methods])
        ax.bar(methods, v, bottom=bottom, label=e)
        bottom += v
    ax.set_ylabel("cycles per ray")
    what = "by unit, warp model" if warp else "by event"
    ax.set_title(title or f"{r.label}: cycles per ray {what} ({r._preset(preset)})")
    ax.legend(fontsize=7, ncol=2)
    return fig


# -- per-pixel maps (live results) -----------------------------------------------
def _field(result, method, quantity, preset):
    if quantity == "cycles":
        return np.asarray(result.pixel_cycles(method, preset), dtype=float), "cycles / pixel"
    return np.asarray(result.pixel_events(method, quantity), dtype=float), f"{quantity} / pixel"


def heatmaps(result, quantity="cycles", methods=None, preset=None, percentile=99.5, log=False, cmap=None,
             title=None, scale_methods=None):
    """Per-pixel heat maps of each method on one common scale with a colour
    bar: "cycles" under a preset, or an event's counts ("is_call", ...). The
    scale's top is the `percentile` of all values (the CLI's heat maps);
    scale_methods: the methods whose values set the scale (default: those drawn),
    so maps drawn one per figure can share a scale."""
    methods = methods or [n for n, m in result.methods.items() if m.runnable]
    fields = [_field(result, m, quantity, preset) for m in methods]
    scaled = fields if scale_methods is None else [_field(result, m, quantity, preset) for m in scale_methods]
    values = np.concatenate([f.ravel() for f, _ in scaled])
    if log:
        pos = values[values > 0]
        norm = colors.LogNorm(np.percentile(pos, 100 - percentile), np.percentile(pos, percentile)) \
            if pos.size else colors.LogNorm(1, 10)
    else:
        norm = colors.Normalize(values.min() if values.size else 0, np.percentile(values, percentile)
                                if values.size else 1)
    cmap = cmap or ("inferno" if quantity == "cycles" else "viridis")
    fig = Figure(figsize=(3.6 * len(methods) + 1.2, 3.9), layout="constrained")
    axes = fig.subplots(1, len(methods), squeeze=False)[0]
    image = None
    for ax, m, (f, unit) in zip(axes, methods, fields):
        image = ax.imshow(f, cmap=cmap, norm=norm, interpolation="nearest")
        ax.set_title(m)
        ax.set_xticks([])
        ax.set_yticks([])
    bar = fig.colorbar(image, ax=list(axes), shrink=0.9)
    bar.set_label(fields[0][1])
    warp = ", warp model" if quantity == "cycles" and result.costs[result.preset_index(preset)].is_warp else ""
    what = f"cycles per pixel ({result._preset(preset)}{warp})" if quantity == "cycles" else f"{quantity} per pixel"
    fig.suptitle(title or f"{result.label}: {what}, common scale", fontsize=10)
    return fig


def heatmap(result, method, quantity="cycles", preset=None, **kw):
    """One method's heat map (see heatmaps)."""
    return heatmaps(result, quantity, [method], preset, **kw)


def ratio_map(result, method=None, preset=None, limit=None, title=None):
    """Per-pixel cycles of the baseline over `method`, on a log scale centred
    at 1 (red: the method is cheaper, blue: the baseline is), with a colour bar."""
    method = method or result.others[0]
    base = result.baseline
    a = np.asarray(result.pixel_cycles(base, preset), dtype=float)
    b = np.asarray(result.pixel_cycles(method, preset), dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        ratio = np.where((a > 0) & (b > 0), a / b, np.nan)
    finite = ratio[np.isfinite(ratio)]
    if limit is None:  # symmetric in log around 1, at least 1.5x either way
        spread = float(np.percentile(np.abs(np.log(finite)), 99.5)) if finite.size else 0.0
        limit = math.exp(max(spread, math.log(1.5)))
    fig = Figure(figsize=(5.2, 4.2), layout="constrained")
    ax = fig.add_subplot()
    cmap = matplotlib.colormaps["RdBu_r"].copy()
    cmap.set_bad("#bbbbbb")
    m = limit
    image = ax.imshow(ratio, cmap=cmap, norm=colors.LogNorm(1 / m, m), interpolation="nearest")
    ax.set_xticks([])
    ax.set_yticks([])
    bar = fig.colorbar(image, ax=ax)
    ticks = [v for v in (0.1, 0.2, 0.25, 1 / 3, 0.5, 2 / 3, 0.8, 1, 1.25, 1.5, 2, 3, 4, 5, 10) if 1 / m <= v <= m]
    bar.ax.minorticks_off()
    bar.set_ticks(ticks, labels=[f"{v:.2g}x" for v in ticks])
    bar.set_label(f"{base} / {method} cycles")
    ax.set_title(title or f"{result.label}: cycles per pixel, {base} / {method}\n"
                          f"red: {method} cheaper, blue: {base} cheaper, grey: no cycles", fontsize=9)
    return fig


def render(result, exposure=1.0, title=None):
    """The traced image (linear radiance, clipped and gamma-encoded)."""
    rgb = np.clip(np.asarray(result.radiance()) * exposure, 0, 1) ** (1 / 2.2)
    fig = Figure(figsize=(4.5, 4.5), layout="constrained")
    ax = fig.add_subplot()
    ax.imshow(rgb)
    ax.set_xticks([])
    ax.set_yticks([])
    ax.set_title(title or result.label)
    return fig


# Break-even maps (with the calibration's band): rtcsim/plot_break_even.py.
from .plot_break_even import break_even, break_even_cells, break_even_grid, break_even_maps, in_doubt  # noqa: E402,F401


# -- python3 -m rtcsim.plot ---------------------------------------------------------
def figures_for(reports, preset=None):
    """{file name: Figure} for finished runs: the speedup table and cycle
    breakdown; over several runs, speedup against each numeric sweep axis
    and against the surface-area ratio."""
    figs = {"speedup_table": speedup_table(reports, preset)}
    if len(reports) == 1:
        figs["cycles_by_event"] = cycle_breakdown(reports[0], preset)
    else:
        for axis in numeric_axes(reports):
            figs["speedup_vs_" + axis.replace("/", "_")] = speedup_vs_axis(reports, axis, preset)
        figs["speedup_vs_area_ratio"] = speedup_vs_area_ratio(reports, preset, labels=len(reports) <= 24)
    return figs


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python3 -m rtcsim.plot",
                                     description="Figures from finished simulate runs (report.json).")
    parser.add_argument("reports", nargs="+",
                        help="report.json files, or output directories (a run's or a sweep's)")
    parser.add_argument("--out", required=True, help="directory for the figures")
    parser.add_argument("--preset", help="cost preset name (default: each run's primary)")
    parser.add_argument("--format", default="png", choices=["png", "svg", "pdf"])
    args = parser.parse_args(argv)
    from ._rtcsim import InputError
    reports = []
    try:
        for path in args.reports:
            reports += load_reports(path) if os.path.isdir(path) else [load_report(path)]
    except InputError as e:  # a cut report.json, an unfinished run: one line, exit 2 as simulate
        print(f"{parser.prog}: {e}", file=sys.stderr)
        return 2
    if not reports:
        parser.error("no report.json found")
    os.makedirs(args.out, exist_ok=True)
    for name, fig in figures_for(reports, args.preset).items():
        path = os.path.join(args.out, f"{name}.{args.format}")
        fig.savefig(path, dpi=150)
        print(path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
