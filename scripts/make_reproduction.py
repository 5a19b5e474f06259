#!/usr/bin/env python3
"""Collects the report.json files of the reproduction runs into the tables of
docs/reproduction.md and a scatter plot of speedup against the AABB/OBB
surface-area ratio over all runs (docs/images/speedup_vs_area_ratio.svg).

usage: scripts/make_reproduction.py RUNS_DIR > tables.md
RUNS_DIR holds fig3/, hair/, scivis/, memory/ as written by
  build/simulate configs/runs/<name>.json --out RUNS_DIR/<name>
Only the Python standard library is used.
"""
import glob
import json
import math
import os
import sys

PAPER = {0: [1.05, 1.03, 1.04, 1.04], 15: [1.16, 1.16, 2.01, 3.83],
         30: [1.10, 1.21, 1.91, 3.32], 45: [1.12, 1.22, 1.90, 3.20]}
CONFIGS = [(1, 0.1), (10, 0.01), (100, 0.002), (1000, 0.002)]


def reports(directory):
    out = []
    for path in sorted(glob.glob(os.path.join(directory, "*", "report.json")),
                       key=lambda p: int(os.path.basename(os.path.dirname(p)).split("_")[0])):
        with open(path) as f:
            out.append((path, json.load(f)))
    return out


def speedup(r, preset):
    s = (r["speedup_over_ref"] or {}).get("obb", {}).get(preset)
    return s


def is_per_ray(r, method):
    m = r["methods"].get(method, {})
    if not m.get("runnable"):
        return None
    return m["events"]["is_call"]["per_ray"]


def fig3_table(runs, preset):
    cells = {}
    for _, r in runs:
        sp = r["sweep_point"]
        cells[(sp["scene.count"], sp["scene.tilt_deg"])] = (speedup(r, preset), r)
    lines = ["| tilt | " + " | ".join(f"N={n}, r={rad}" for n, rad in CONFIGS) + " |",
             "|---|" + "---|" * len(CONFIGS)]
    errors = []
    for tilt, row in PAPER.items():
        cols = []
        for (n, _), paper in zip(CONFIGS, row):
            s = cells[(n, tilt)][0]
            err = 100.0 * (s - paper) / paper
            errors.append(abs(err))
            mark = "" if abs(err) <= 10 else " **"
            cols.append(f"{paper:.2f}x / {s:.2f}x ({err:+.1f}%){mark}")
        lines.append(f"| {tilt} deg | " + " | ".join(cols) + " |")
    within = sum(e <= 10 for e in errors)
    lines.append("")
    lines.append(f"Paper / simulated (error). {within} of {len(errors)} cells within +/-10%; "
                 f"mean |error| {sum(errors) / len(errors):.1f}%; ** marks a miss.")
    return "\n".join(lines), cells


def model_table(runs, preset):
    lines = ["| model | kind | prims | speedup | AABB/OBB area | IS calls ref -> obb (per ray) | IS-call reduction | obb memory overhead |",
             "|---|---|---:|---:|---:|---:|---:|---:|"]
    points = []
    for _, r in runs:
        sp = r.get("sweep_point", {})
        kind = r["scene"]["primitive_kind"]
        if kind == "phantom":
            kind += f" /{sp.get('primitives.subdivision', 1)}"
        s = speedup(r, preset)
        a = r["scene"]["surface_area"]["aabb_over_obb_paper"]
        ri, oi = is_per_ray(r, "ref"), is_per_ray(r, "obb")
        red = f"{ri / oi:.1f}x" if ri and oi else "n/a"
        mem = (r["memory_overhead_percent"] or {}).get("obb")
        name = sp.get("scene.name", r["name"])
        lines.append(f"| {name} | {kind} | {r['scene']['primitives']:,} | "
                     f"{(f'{s:.2f}x' if s else 'n/a')} | {a:.2f} | "
                     f"{ri:.2f} -> {oi:.2f} | {red} | {(f'{mem:.0f}%' if mem is not None else 'n/a')} |"
                     if ri is not None and oi is not None else
                     f"| {name} | {kind} | {r['scene']['primitives']:,} | n/a | {a:.2f} | n/a | n/a | n/a |")
        if s:
            points.append((a, s, name))
    return "\n".join(lines), points


def memory_table(runs):
    lines = ["| model | prims | memory preset | ref total | obb total | overhead |",
             "|---|---:|---|---:|---:|---:|"]
    for _, r in runs:
        sp = r.get("sweep_point", {})
        ref, obb = r["methods"]["ref"], r["methods"]["obb"]
        def mib(m):
            return f"{m['memory_bytes']['total'] / 2**20:,.1f} MiB" if m.get("runnable") else "n/a"
        over = (r["memory_overhead_percent"] or {}).get("obb")
        reason = "" if obb.get("runnable") else f" ({obb.get('reason')})"
        lines.append(f"| {sp.get('scene.name', r['name'])} | {r['scene']['primitives']:,} | {r['memory_preset']} | "
                     f"{mib(ref)} | {mib(obb)}{reason} | {(f'{over:.0f}%' if over is not None else 'n/a')} |")
    return "\n".join(lines)


def scatter_svg(groups, path):
    """groups: {label: [(x, y, name)]}, log-log axes."""
    w, h, left, right, top, bottom = 640, 440, 70, 170, 40, 60
    xs = [p[0] for g in groups.values() for p in g]
    ys = [p[1] for g in groups.values() for p in g]
    lx0, lx1 = math.log10(min(xs) * 0.8), math.log10(max(xs) * 1.25)
    ly0, ly1 = math.log10(min(ys) * 0.9), math.log10(max(ys) * 1.1)
    def px(x):
        return left + (math.log10(x) - lx0) / (lx1 - lx0) * (w - left - right)
    def py(y):
        return h - bottom - (math.log10(y) - ly0) / (ly1 - ly0) * (h - top - bottom)
    colors = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e"]
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" font-family="sans-serif" font-size="12">',
           f'<rect width="{w}" height="{h}" fill="white"/>',
           f'<text x="{w / 2 - 60}" y="22" font-size="15" text-anchor="middle">speedup vs AABB/OBB surface-area ratio (all runs)</text>']
    for e in range(math.floor(lx0), math.ceil(lx1) + 1):
        for m in (1, 2, 5):
            v = m * 10 ** e
            if lx0 <= math.log10(v) <= lx1:
                out.append(f'<line x1="{px(v):.1f}" y1="{top}" x2="{px(v):.1f}" y2="{h - bottom}" stroke="#eee"/>')
                out.append(f'<text x="{px(v):.1f}" y="{h - bottom + 16}" text-anchor="middle">{v:g}</text>')
    for v in (0.5, 0.75, 1, 1.5, 2, 3, 4, 5, 6, 8, 10):
        if ly0 <= math.log10(v) <= ly1:
            out.append(f'<line x1="{left}" y1="{py(v):.1f}" x2="{w - right}" y2="{py(v):.1f}" stroke="#eee"/>')
            out.append(f'<text x="{left - 6}" y="{py(v) + 4:.1f}" text-anchor="end">{v:g}x</text>')
    out.append(f'<rect x="{left}" y="{top}" width="{w - left - right}" height="{h - top - bottom}" fill="none" stroke="#333"/>')
    out.append(f'<text x="{(left + w - right) / 2}" y="{h - 20}" text-anchor="middle">sum of AABB areas / sum of OBB areas (paper OBBs), log</text>')
    out.append(f'<text transform="translate(18,{(top + h - bottom) / 2}) rotate(-90)" text-anchor="middle">speedup of obb over ref, log</text>')
    for i, (label, pts) in enumerate(groups.items()):
        c = colors[i % len(colors)]
        for x, y, _ in pts:
            out.append(f'<circle cx="{px(x):.1f}" cy="{py(y):.1f}" r="4" fill="{c}" fill-opacity="0.8"/>')
        ly = top + 10 + 20 * i
        out.append(f'<circle cx="{w - right + 16}" cy="{ly}" r="4" fill="{c}"/>')
        out.append(f'<text x="{w - right + 26}" y="{ly + 4}">{label}</text>')
    out.append("</svg>")
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


def main():
    runs_dir = sys.argv[1]
    preset = "turing-calibrated"
    fig3 = reports(os.path.join(runs_dir, "fig3"))
    table, cells = fig3_table(fig3, preset)
    print("## Synthetic table (calibrated preset)\n")
    print(table)
    groups = {"synthetic bundles": [(r["scene"]["surface_area"]["aabb_over_obb_paper"], s, "")
                                    for s, r in cells.values() if s]}
    for name in ("hair", "scivis"):
        runs = reports(os.path.join(runs_dir, name))
        if not runs:
            continue
        t, points = model_table(runs, preset)
        print(f"\n## {name}\n")
        print(t)
        groups[name + " models"] = points
    mem = reports(os.path.join(runs_dir, "memory"))
    if mem:
        print("\n## memory\n")
        print(memory_table(mem))
    scatter_svg(groups, os.path.join(os.path.dirname(__file__), "..", "docs", "images", "speedup_vs_area_ratio.svg"))


if __name__ == "__main__":
    main()
