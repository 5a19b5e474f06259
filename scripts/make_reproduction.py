#!/usr/bin/env python3
"""Regenerates docs/reproduction.md's tables and figures from the
reproduction runs, with the rtcsim Python module.

usage: scripts/make_reproduction.py RUNS_DIR [--images DIR] [--trace [SIZE]] > tables.md

RUNS_DIR holds fig3/, curly/, hair/, scivis/, memory/ as written by
  build/simulate configs/runs/<name>.json --out RUNS_DIR/<name>
(or rtcsim.simulate). Prints the Markdown tables (synthetic table against the
paper, hair and sci-vis predictions, memory) and writes into docs/images/:
  speedup_vs_area_ratio.svg   speedup against the AABB/OBB area ratio, all runs
  fig3_speedup_vs_tilt.svg    the synthetic table's speedups against the tilt, with the paper's
With --trace, also re-traces the N = 1000, r = 0.002, 45 degree bundle at
SIZE x SIZE (default 800, as the calibration runs) for its heat maps:
  fig3_n1000_r0.002_45deg_cycles_{ref,obb}.png (common scale), ..._ratio.png
"""
import argparse
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "examples"))
from rtcsim_import import ROOT, import_rtcsim  # noqa: E402

rtcsim = import_rtcsim()
from rtcsim import plot  # noqa: E402

PAPER = {0: [1.05, 1.03, 1.04, 1.04], 15: [1.16, 1.16, 2.01, 3.83],
         30: [1.10, 1.21, 1.91, 3.32], 45: [1.12, 1.22, 1.90, 3.20]}
CONFIGS = [(1, 0.1), (10, 0.01), (100, 0.002), (1000, 0.002)]
PRESET = "turing-calibrated"


def fig3_table(runs, preset):
    cells = {(r.sweep_point["scene.count"], r.sweep_point["scene.tilt_deg"]): r for r in runs}
    lines = ["| tilt | " + " | ".join(f"N={n}, r={rad}" for n, rad in CONFIGS) + " |",
             "|---|" + "---|" * len(CONFIGS)]
    errors = []
    for tilt, row in PAPER.items():
        cols = []
        for (n, _), paper in zip(CONFIGS, row):
            s = cells[(n, tilt)].speedup("obb", preset)
            err = 100.0 * (s - paper) / paper
            errors.append(abs(err))
            mark = "" if abs(err) <= 10 else " **"
            cols.append(f"{paper:.2f}x / {s:.2f}x ({err:+.1f}%){mark}")
        lines.append(f"| {tilt} deg | " + " | ".join(cols) + " |")
    within = sum(e <= 10 for e in errors)
    lines.append("")
    lines.append(f"Paper / simulated (error). {within} of {len(errors)} cells within +/-10%; "
                 f"mean |error| {sum(errors) / len(errors):.1f}%; ** marks a miss.")
    return "\n".join(lines)


def model_name(r):
    return r.sweep_point.get("scene.name", r.name)


def kind_label(r):
    kind = r.kind
    if kind == "phantom":
        kind += f" /{r.sweep_point.get('primitives.subdivision', 1)}"
    return kind


def model_table(runs, preset):
    lines = ["| model | kind | prims | speedup | AABB/OBB area | IS calls ref -> obb (per ray) "
             "| IS-call reduction | obb memory overhead |",
             "|---|---|---:|---:|---:|---:|---:|---:|"]
    points = []
    for r in runs:
        kind = kind_label(r)
        s, a = r.speedup("obb", preset), r.area_ratio()
        ri, oi = r.is_per_ray("ref"), r.is_per_ray("obb")
        name = model_name(r)
        if ri is None or oi is None:
            lines.append(f"| {name} | {kind} | {r.primitives:,} | n/a | {a:.2f} | n/a | n/a | n/a |")
        else:
            red = f"{ri / oi:.1f}x" if ri and oi else "n/a"
            mem = r.memory_overhead("obb")
            lines.append(f"| {name} | {kind} | {r.primitives:,} | {(f'{s:.2f}x' if s else 'n/a')} | {a:.2f} | "
                         f"{ri:.2f} -> {oi:.2f} | {red} | {(f'{mem:.0f}%' if mem is not None else 'n/a')} |")
        if s:
            points.append((a, s, name))
    return "\n".join(lines), points


# Table 1 of the paper (method.md): ref rays/s and the masquerade's speedup
# per kind, for the two curly models the stand-ins of curly_table1.json mimic.
TABLE1 = {
    "curly lock": {"capsule": (4.1e6, 3.82), "link": (4.2e6, 4.03), "phantom /1": (81.3e3, 1.74),
                   "phantom /2": (343.0e3, 2.37), "phantom /4": (1.3e6, 3.44), "phantom /8": (5.0e6, 3.65)},
    "curly head": {"capsule": (15.5e6, 3.17), "link": (15.0e6, 3.27), "phantom /1": (1.0e6, 2.06),
                   "phantom /2": (3.7e6, 2.73), "phantom /4": (12.2e6, 2.88)},
}


def speedup_interval(r, preset, method="obb"):
    """The run's 90 % interval of the speedup under `preset`, or None."""
    table = r.data.get(f"speedup_interval_over_{r.baseline}", {}).get(method, {})
    value = table.get(preset) if isinstance(table, dict) else None
    return tuple(value) if value else None


def table1_predictions(runs, preset):
    """Table 1 on the curly stand-ins, nothing fitted to it: each speedup with
    its interval against the paper's, and the reference method's cost per ray
    relative to capsules on the same model (the paper's: capsule rays/s over
    the kind's)."""
    lines = ["| model | kind | ref cycles/ray vs capsule (paper) | obb speedup [90 %] | paper | error | "
             "paper inside the interval |", "|---|---|---:|---:|---:|---:|---|"]
    by_model = {}
    for r in runs:
        by_model.setdefault(model_name(r), {})[kind_label(r)] = r
    inside = counted = 0
    for model, kinds in by_model.items():
        paper = TABLE1.get(model, {})
        capsule = kinds.get("capsule")
        for kind, r in kinds.items():
            s = r.speedup("obb", preset)
            ref_ratio = r.cycles_per_ray("ref", preset) / capsule.cycles_per_ray("ref", preset) if capsule else None
            rays, target = paper.get(kind, (None, None))
            paper_ratio = paper["capsule"][0] / rays if rays and "capsule" in paper else None
            interval = speedup_interval(r, preset)
            shown = f"{s:.2f}x" if s else "n/a"
            if s and interval:
                shown += f" [{interval[0]:.2f}-{interval[1]:.2f}]"
            error = f"{100 * (s / target - 1):+.1f} %" if s and target else ""
            within = ""
            if interval and target and kind in ("capsule", "link"):
                counted += 1
                hit = interval[0] <= target <= interval[1]
                inside += hit
                within = "yes" if hit else "no"
            ratio = f"{ref_ratio:.2f}" if ref_ratio else "n/a"
            if paper_ratio:
                ratio += f" ({paper_ratio:.2f})"
            lines.append(f"| {model} | {kind} | {ratio} | {shown} | {f'{target:.2f}x' if target else ''} | "
                         f"{error} | {within} |")
    lines.append("")
    lines.append(f"Paper values inside the 90 % interval (capsule and link cells): {inside} of {counted}.")
    return "\n".join(lines)


def memory_table(runs):
    lines = ["| model | prims | memory preset | ref total | obb total | overhead |",
             "|---|---:|---|---:|---:|---:|"]
    for r in runs:
        def mib(method):
            total = r.memory_total(method)
            return f"{total / 2**20:,.1f} MiB" if total is not None else "n/a"
        over = r.memory_overhead("obb")
        reason = "" if r.runnable("obb") else f" ({r.data['methods']['obb'].get('reason')})"
        lines.append(f"| {model_name(r)} | {r.primitives:,} | {r.data['memory_preset']} | "
                     f"{mib('ref')} | {mib('obb')}{reason} | {(f'{over:.0f}%' if over is not None else 'n/a')} |")
    return "\n".join(lines)


def tilt_figure(runs, preset):
    fig = plot.speedup_vs_axis(runs, "scene.tilt_deg", preset, "obb",
                               title=f"synthetic bundles: speedup vs tilt ({preset}); dashed: the paper")
    ax = fig.axes[0]
    lines = {line.get_label(): line for line in ax.get_lines() if line.get_marker() == "o"}
    for i, (n, rad) in enumerate(CONFIGS):
        line = next((v for k, v in lines.items() if f"scene.count={n}," in k + ","), None)
        ax.plot(list(PAPER), [PAPER[t][i] for t in PAPER], ls="--", marker="x",
                color=line.get_color() if line else None, label=f"paper N={n}, r={rad}")
    ax.legend(fontsize=7, ncol=2)
    return fig


def trace_heatmaps(size, images):
    with open(os.path.join(ROOT, "configs", "runs", "fig3_bundles.json")) as f:
        config = json.load(f)
    config.pop("sweep")
    config.pop("calibrate", None)
    config["scene"].update(count=1000, radius=0.002, tilt_deg=45)
    config["workload"].update(width=size, height=size)
    config["output"] = {"images": False}
    result = rtcsim.run(config, base=os.path.join(ROOT, "configs", "runs", "fig3_bundles.json"))
    stem = os.path.join(images, "fig3_n1000_r0.002_45deg")
    for method in ("ref", "obb"):
        fig = plot.heatmaps(result, "cycles", [method], PRESET, scale_methods=["ref", "obb"],
                            title=f"{method}: cycles per pixel ({PRESET})\nN=1000, r=0.002, 45 deg, common scale")
        fig.savefig(f"{stem}_cycles_{method}.png", dpi=100)
    plot.ratio_map(result, "obb", PRESET).savefig(f"{stem}_ratio.png", dpi=100)


def main():
    parser = argparse.ArgumentParser(description="docs/reproduction.md's tables (stdout) and figures")
    parser.add_argument("runs_dir")
    parser.add_argument("--images", default=os.path.join(ROOT, "docs", "images"))
    parser.add_argument("--trace", type=int, nargs="?", const=800, default=None, metavar="SIZE",
                        help="re-trace the N=1000, 45 degree bundle for its heat maps (default 800 x 800)")
    args = parser.parse_args()

    fig3 = rtcsim.load_reports(os.path.join(args.runs_dir, "fig3"))
    print("## Synthetic table (calibrated preset)\n")
    print(fig3_table(fig3, PRESET))
    groups = {"synthetic bundles": [(r.area_ratio(), s, "") for r in fig3 if (s := r.speedup("obb", PRESET))]}
    for name in ("hair", "scivis"):
        runs = rtcsim.load_reports(os.path.join(args.runs_dir, name))
        if not runs:
            continue
        table, points = model_table(runs, PRESET)
        print(f"\n## {name}\n")
        print(table)
        groups[name + " models"] = points
    curly = rtcsim.load_reports(os.path.join(args.runs_dir, "curly"))
    if curly:
        print(f"\n## Table 1 predictions (curly stand-ins, {PRESET})\n")
        print(table1_predictions(curly, PRESET))
    mem = rtcsim.load_reports(os.path.join(args.runs_dir, "memory"))
    if mem:
        print("\n## memory\n")
        print(memory_table(mem))
    os.makedirs(args.images, exist_ok=True)
    plot.speedup_vs_area_ratio(groups, title="speedup vs AABB/OBB surface-area ratio (all runs)").savefig(
        os.path.join(args.images, "speedup_vs_area_ratio.svg"))
    tilt_figure(fig3, PRESET).savefig(os.path.join(args.images, "fig3_speedup_vs_tilt.svg"))
    if args.trace:
        trace_heatmaps(args.trace, args.images)


if __name__ == "__main__":
    main()
