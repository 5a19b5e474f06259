#!/usr/bin/env python3
"""How close the simulator came to Wald et al. 2020: the scorecard that ends
scripts/reproduce, and its two charts.

usage: scripts/reproduction_scorecard.py RUNS_DIR [--images DIR] [--mode full|quick]

RUNS_DIR is scripts/reproduce's output (fig3/, curly/, hair/, scivis/,
memory/, skipped.txt). Prints the scorecard and writes it to
RUNS_DIR/scorecard.md:
  - each table of the paper that has runs (the synthetic table, Table 1 on
    the curly stand-ins): its cells within 10 % and within 15 % of the
    paper, and how many paper values lie inside the simulated 90 % band;
  - the paper's other findings (memory overhead range, real hair faster,
    sci-vis about even) against the runs;
  - what is missing, and why.
Draws, into --images (default RUNS_DIR/images):
  fig3_paper_vs_simulated.svg    the synthetic table: paper and simulated speedups per
                                 bundle over the tilt, with the simulated 90 % bands
  table1_paper_vs_simulated.svg  Table 1: paper and simulated speedups per kind, with bands
The paper's values are constants of scripts/make_reproduction.py (PAPER,
TABLE1); every simulated value is read from the runs' report.json files."""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_reproduction as mr  # noqa: E402  (imports rtcsim, wherever it is)

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

PRESET = mr.PRESET
# The paper's Table 2: the masquerade's memory overhead under OptiX 7.
MEMORY_RANGE = (211.0, 311.0)
# The paper on sci-vis data (streamlines, neurons): "about the same either way".
SCIVIS_RANGE = (0.9, 1.3)


def load(runs_dir, name):
    path = os.path.join(runs_dir, name)
    return mr.rtcsim.load_reports(path) if os.path.isdir(path) else []


def cells_of_fig3(fig3):
    """(label, paper, simulated, band or None) per synthetic cell."""
    by = {(r.sweep_point["scene.count"], r.sweep_point["scene.tilt_deg"]): r for r in fig3}
    cells = []
    for tilt, row in mr.PAPER.items():
        for (n, _), paper in zip(mr.CONFIGS, row):
            r = by.get((n, tilt))
            if r is not None:
                cells.append((f"N = {n}, {tilt} deg", paper, r.speedup("obb", PRESET), mr.speedup_interval(r, PRESET)))
    return cells


def cells_of_table1(curly):
    """(label, paper, simulated or None, band or None, why n/a) per Table 1 cell."""
    by = {(mr.model_name(r), mr.kind_label(r)): r for r in curly}
    cells = []
    for model, kinds in mr.TABLE1.items():
        for kind, (_, paper) in kinds.items():
            r = by.get((model, kind))
            if r is None:
                cells.append((f"{model}, {kind}", paper, None, None, "not run"))
                continue
            s = r.speedup("obb", PRESET)
            why = "" if s else r.data["methods"]["obb"].get("reason", "not runnable")
            cells.append((f"{model}, {kind}", paper, s, mr.speedup_interval(r, PRESET) if s else None, why))
    return cells


def score_line(title, cells):
    """Within 10 % and 15 %, band coverage and the worst cell, of (label, paper, simulated, band)."""
    done = [(label, p, s, band) for label, p, s, band, *_ in cells if s]
    if not done:
        return f"| {title} | no cells | | | |"
    w10 = sum(abs(s / p - 1) <= 0.10 for _, p, s, _ in done)
    w15 = sum(abs(s / p - 1) <= 0.15 for _, p, s, _ in done)
    banded = [(p, band) for _, p, _, band in done if band]
    covered = sum(lo <= p <= hi for p, (lo, hi) in banded)
    worst = max(done, key=lambda c: abs(c[2] / c[1] - 1))
    band_text = f"{covered} of {len(banded)}" if banded else "no bands"
    return (f"| {title} | {w10} of {len(done)} | {w15} of {len(done)} | {band_text} | "
            f"{worst[0]}: {worst[2]:.2f}x vs {worst[1]:.2f}x ({100 * (worst[2] / worst[1] - 1):+.1f} %) |")


def memory_preset(r):
    preset = r.data.get("memory_preset")
    return preset if isinstance(preset, str) else (preset or {}).get("name")


def findings(hair, scivis, memory):
    """The paper's qualitative findings against the runs, one table row each."""
    rows = []
    if memory:
        overheads = [r.memory_overhead("obb") for r in memory if memory_preset(r) == "memory-optix7" and r.runnable("obb")]
        overheads = [o for o in overheads if o is not None]
        if overheads:
            lo, hi = min(overheads), max(overheads)
            inside = MEMORY_RANGE[0] <= lo and hi <= MEMORY_RANGE[1]
            rows.append(f"| memory overhead of the masquerade, OptiX 7 (Table 2: +{MEMORY_RANGE[0]:.0f} to "
                        f"+{MEMORY_RANGE[1]:.0f} %) | +{lo:.0f} to +{hi:.0f} % | {'inside' if inside else 'outside'} |")
        over = [r for r in memory if not r.runnable("obb")]
        if over:
            rows.append(f"| a model over 2^24 instances cannot use the masquerade | {len(over)} runs n/a "
                        f"({mr.model_name(over[0])}) | as the paper |")
    if hair:
        speedups = [s for r in hair if (s := r.speedup("obb", PRESET))]
        if speedups:
            rows.append(f"| real hair and fur faster with the masquerade, every kind (paper: up to 5.9x) | "
                        f"{min(speedups):.2f}x to {max(speedups):.2f}x | "
                        f"{'yes' if min(speedups) > 1 else 'no'} |")
    if scivis:
        for r in scivis:
            s = r.speedup("obb", PRESET)
            if s:
                inside = SCIVIS_RANGE[0] <= s <= SCIVIS_RANGE[1]
                rows.append(f"| sci-vis about even ({SCIVIS_RANGE[0]}x-{SCIVIS_RANGE[1]}x): "
                            f"{mr.model_name(r)} {mr.kind_label(r)} | {s:.2f}x | {'inside' if inside else 'outside'} |")
    return rows


def missing(runs_dir, mode, fig3, curly, t1_cells):
    out = []
    skipped_file = os.path.join(runs_dir, "skipped.txt")
    skipped = open(skipped_file).read().split() if os.path.exists(skipped_file) else []
    if skipped:
        out.append(f"- {', '.join(skipped)}: not run, the real models are not installed "
                   "(scripts/fetch-data, docs/data.md).")
    if not fig3:
        out.append("- The synthetic table: no runs in fig3/.")
    if not curly:
        out.append("- Table 1: no runs in curly/.")
    for label, paper, s, _, why in t1_cells:
        if not s and curly:
            out.append(f"- Table 1, {label} (paper {paper:.2f}x): {why}.")
    out.append("- Table 1 runs on procedural stand-ins of the paper's two curly models: the originals "
               "(Bitterli's hair-curl, Yuksel's curly hair) have no recorded checksum, so scripts/fetch-data "
               "does not fetch them (docs/data.md).")
    out.append("- The paper's absolute rays per second are not scored: tables.md's Table 1 sets them beside the "
               "model's cycles per ray as SM-cycles per ray (72 SMs at 1.77 GHz), a check of the absolute scale "
               "(docs/reproduction.md says how far off the model is).")
    if not os.path.exists(os.path.join(runs_dir, "fig3", "calibrated_preset.json")):
        out.append("- The refit check: the synthetic runs were priced under the shipped fit, not refitted "
                   "(scripts/reproduce --refit, about 27 minutes).")
    if mode == "quick":
        out.append("- Quick mode: every image at reduced resolution (synthetic 400 x 400 x 2 paths, Table 1 "
                   "128 x 128, real models 128 x 128 x 1 path) and Table 1 without subdivision 8, so cells "
                   "move by up to about 5 % against the full run (smaller frames keep fewer rays per warp "
                   "coherent); docs/reproduction.md has the full run's numbers.")
    return out


def fig3_chart(cells, path):
    """Four panels, one per bundle: the paper's speedups and the simulated
    ones over the tilt, the simulated 90 % band shaded."""
    fig, axes = plt.subplots(1, len(mr.CONFIGS), figsize=(13, 3.4), sharey=True)
    tilts = list(mr.PAPER)
    for ax, (n, radius) in zip(axes, mr.CONFIGS):
        mine = [c for c in cells if c[0].startswith(f"N = {n},")]
        paper = [c[1] for c in mine]
        sim = [c[2] for c in mine]
        ax.plot(tilts[:len(paper)], paper, "k--x", label="paper")
        ax.plot(tilts[:len(sim)], sim, "o-", color="tab:blue", label=f"simulated ({PRESET})")
        bands = [c[3] for c in mine]
        if all(bands):
            ax.fill_between(tilts[:len(bands)], [b[0] for b in bands], [b[1] for b in bands], color="tab:blue",
                            alpha=0.2, label="90 % band")
        ax.set_title(f"N = {n}, r = {radius}")
        ax.set_xlabel("tilt (degrees)")
        ax.set_xticks(tilts)
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("obb speedup over ref")
    axes[-1].legend(loc="lower right", fontsize=8)
    fig.suptitle("Synthetic table: paper against simulated")
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def table1_chart(cells, path):
    """Two panels (the curly lock, the curly head): paper and simulated
    speedups per primitive kind, the simulated 90 % band as an error bar."""
    models = list(mr.TABLE1)
    fig, axes = plt.subplots(1, len(models), figsize=(12, 3.8), sharey=True)
    for ax, model in zip(axes, models):
        mine = [c for c in cells if c[0].startswith(model + ",")]
        x = range(len(mine))
        ax.bar([i - 0.2 for i in x], [c[1] for c in mine], 0.4, color="0.7", label="paper")
        sim = [c[2] or 0 for c in mine]
        err = [[s - c[3][0] if c[3] else 0 for s, c in zip(sim, mine)],
               [c[3][1] - s if c[3] else 0 for s, c in zip(sim, mine)]]
        ax.bar([i + 0.2 for i in x], sim, 0.4, color="tab:blue", yerr=err, capsize=3,
               label=f"simulated ({PRESET}), 90 % band")
        for i, c in zip(x, mine):
            if not c[2]:
                ax.text(i + 0.2, 0.1, "n/a", ha="center", rotation=90, fontsize=8)
        ax.set_xticks(list(x))
        ax.set_xticklabels([c[0].split(", ", 1)[1] for c in mine], rotation=30)
        ax.set_title(model + " (stand-in)")
        ax.grid(axis="y", alpha=0.3)
    axes[0].set_ylabel("obb speedup over ref")
    axes[0].legend(loc="upper right", fontsize=8)
    fig.suptitle("Table 1: paper against simulated")
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("runs_dir")
    parser.add_argument("--images")
    parser.add_argument("--mode", choices=["full", "quick"], default="full")
    args = parser.parse_args()
    images = args.images or os.path.join(args.runs_dir, "images")
    os.makedirs(images, exist_ok=True)
    fig3, curly = load(args.runs_dir, "fig3"), load(args.runs_dir, "curly")
    hair, scivis, memory = (load(args.runs_dir, n) for n in ("hair", "scivis", "memory"))
    f_cells = cells_of_fig3(fig3) if fig3 else []
    t_cells = cells_of_table1(curly) if curly else []

    lines = [f"# Scorecard against Wald et al. 2020 ({args.mode} run, cost preset `{PRESET}`)", "",
             "| table | within 10 % | within 15 % | paper inside the 90 % band | farthest cell |",
             "|---|---|---|---|---|"]
    if f_cells:
        lines.append(score_line("synthetic table (the fit's own data)", [(*c, "") for c in f_cells]))
    if t_cells:
        lines.append(score_line("Table 1 on curly stand-ins (predicted, nothing fitted)", t_cells))
        kinds = [c for c in t_cells if c[0].endswith(("capsule", "link"))]
        lines.append(score_line("Table 1, capsules and links only", kinds))
    rows = findings(hair, scivis, memory)
    if rows:
        lines += ["", "| the paper's finding | simulated | |", "|---|---|---|"] + rows
    lines += ["", "Missing, and why:", ""] + missing(args.runs_dir, args.mode, fig3, curly, t_cells)
    charts = []
    if f_cells:
        fig3_chart(f_cells, os.path.join(images, "fig3_paper_vs_simulated.svg"))
        charts.append("fig3_paper_vs_simulated.svg")
    if t_cells:
        table1_chart(t_cells, os.path.join(images, "table1_paper_vs_simulated.svg"))
        charts.append("table1_paper_vs_simulated.svg")
    if charts:
        lines += ["", f"Charts in {images}: {', '.join(charts)}."]
    text = "\n".join(lines) + "\n"
    with open(os.path.join(args.runs_dir, "scorecard.md"), "w") as f:
        f.write(text)
    print(text, end="")
    return 0


if __name__ == "__main__":
    sys.exit(main())
