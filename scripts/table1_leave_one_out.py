#!/usr/bin/env python3
"""Leave-one-model-out on Table 1's phantom rows (issue 53, item 3).

The synthetic table (Fig. 3) cannot identify how much of an intersection
program's issue cost a frame pays: its cylinders all take the same path, so
the fit drives the one scale on the operation classes (op_fma, op_div,
op_sqrt, op_branch, op_load: the CUDA Guide's throughput prices) to its lower
bound, 1/20. The paper's phantom program is the long one, so its rows are
where that scale matters. This script fits that one scale on one Table 1
model's phantom series and predicts the other model's, both ways round,
every other cost kept at `turing-calibrated`'s Fig. 3 fit. Nothing else is
fitted to Table 1, and the capsule and link cells are reported under each
fit as predictions too.

It traces `configs/runs/curly_table1.json` once through the Python module
(with the waves recorded, so the warp model re-prices them), fits with the
CLI's own calibration (`rtcsim.calibrate`), and re-prices every cell under
each fitted preset (`MethodResult.price`).

    scripts/table1_leave_one_out.py                       # 400 x 400 x 4, 1/8 of the tiles
    scripts/table1_leave_one_out.py --update docs/reproduction.md
    scripts/table1_leave_one_out.py --set workload.width=800 --set workload.height=800
"""

import argparse
import copy
import json
import os
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "examples"))
from rtcsim_import import ROOT, import_rtcsim  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import generated_blocks  # noqa: E402 (next to this script)
import paper_table1  # noqa: E402 (next to this script)

rtcsim = import_rtcsim()

# Wald et al. 2020, Table 1: the obb speedups (scripts/paper_table1.py).
PAPER = {(model, kind): cell[1] for model, cells in paper_table1.TABLE1.items() for kind, cell in cells.items()}
OPS = ["op_fma", "op_div", "op_sqrt", "op_branch", "op_load"]
START = "turing-calibrated"
# The fit scales turing-calibrated's operation prices, which are 1/20 of the
# CUDA Guide's (GUIDE_FRACTION): from 1/10 of them to 4x the Guide's (80).
GUIDE_FRACTION = 0.05
SCALE_MIN, SCALE_MAX = 0.1, 80.0


cell = paper_table1.cell_of


def speedup(result, model):
    ref, obb = result.method("ref"), result.method("obb")
    if not obb.runnable:
        return None
    r, o = ref.price(model), obb.price(model)
    if not (r.supported and o.supported) or o.total_cycles <= 0:
        return None
    return r.total_cycles / o.total_cycles


def fit_on(results, model_name):
    """The operation-class scale fitted on `model_name`'s phantom cells."""
    targets = [{"label": r.label, "speedup": PAPER[cell(r)]} for r in results
               if cell(r)[0] == model_name and cell(r)[1].startswith("phantom") and cell(r) in PAPER]
    block = {"parameters": [{"events": OPS, "min": SCALE_MIN, "max": SCALE_MAX, "tie": "scale"}],
             "start": START, "targets": targets, "method": "obb",
             "name": f"{START}-ops-fitted-on-{model_name.replace(' ', '-')}"}
    fit = rtcsim.calibrate(results, block)
    return fit, len(targets)


def fit_jointly(fig3, results, model_name, fig3_block):
    """Every parameter of the synthetic table's fit, fitted on its cells and
    `model_name`'s phantom cells together (issue 53's protocol in full)."""
    mine = [r for r in results if cell(r)[0] == model_name]
    block = copy.deepcopy(fig3_block)
    block["name"] = f"joint-fig3-{model_name.replace(' ', '-')}"
    extra = [{"label": r.label, "speedup": PAPER[cell(r)]} for r in mine
             if cell(r)[1].startswith("phantom") and cell(r) in PAPER]
    block["targets"] = block["targets"] + extra
    return rtcsim.calibrate(fig3 + mine, block), len(extra)


def joint_footnote(model_name, fit, n):
    fig3 = [run for run in fit.runs if not run["label"].startswith("scene=")]
    within = sum(abs(run["rel_error"]) <= 0.10 for run in fig3)
    worst = max(fig3, key=lambda run: abs(run["rel_error"]))
    names = {"context_switch": "hand-off", "ray": "`ray`", "instance_transform": "`instance_transform`",
             "tlas_node_visit": "TLAS scale", "blas_node_visit": "BLAS scale", "op_fma": "operation scale"}
    bounds = [names.get(p["events"][0], p["events"][0]) + (" (lower)" if p["at_lower"] else " (upper)")
              for p in fit.parameters if p["at_lower"] or p["at_upper"]]
    ops = next(p for p in fit.parameters if p["events"][0] == "op_fma")
    return (f"- Fitted jointly on Fig. 3's {len(fig3)} cells and the {model_name}'s {n} phantom cells: RMS log error "
            f"{fit.rms_log_error:.4f} over them; Fig. 3 {within}/{len(fig3)} within 10 % (worst {worst['label']}: "
            f"{100 * worst['rel_error']:+.1f} %); programs at {ops['fitted']:.3g} of the Guide's prices; at a bound: "
            f"{', '.join(bounds) if bounds else 'none'}; {fit.iterations} iterations.")


def fmt_error(pred, paper):
    return f"{100.0 * (pred / paper - 1.0):+.1f} %" if pred else "n/a"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--set", action="append", default=[], help="a --set override of the config (as simulate's)")
    ap.add_argument("--threads", type=int, default=None)
    ap.add_argument("--update", metavar="DOC", help="rewrite the generated block of DOC (docs/reproduction.md)")
    ap.add_argument("--config", default=os.path.join(ROOT, "configs", "runs", "curly_table1.json"),
                    help="the Table 1 config (default: configs/runs/curly_table1.json)")
    ap.add_argument("--joint", action="store_true",
                    help="fit every parameter of the synthetic table's fit on its cells and one model's phantom "
                         "cells together (the synthetic table traced with --fig3-set)")
    ap.add_argument("--fig3-config", default=os.path.join(ROOT, "configs", "runs", "fig3_bundles.json"))
    ap.add_argument("--fig3-set", action="append", default=None,
                    help="--set overrides of the synthetic table's runs with --joint (default: 400 x 400 x 2)")
    args = ap.parse_args()
    sets = ["workload.width=400", "workload.height=400"] + args.set
    config = args.config
    t0 = time.time()
    results = rtcsim.sweep(config, threads=args.threads, sets=sets, record_warps=True)
    fig3 = []
    if args.joint:
        fig3_sets = args.fig3_set or ["workload.width=400", "workload.height=400", "workload.spp=2"]
        fig3 = rtcsim.sweep(args.fig3_config, threads=args.threads, sets=fig3_sets, record_warps=True)
        with open(args.fig3_config) as f:
            fig3_block = json.load(f)["calibrate"]
    traced = time.time() - t0
    start = rtcsim.load_cost_model(START)
    fits = {}
    for model_name in ("curly lock", "curly head"):
        fits[model_name] = fit_jointly(fig3, results, model_name, fig3_block) if args.joint else \
            fit_on(results, model_name)
    rows = []
    for r in results:
        key = cell(r)
        if key not in PAPER:
            continue
        paper = PAPER[key]
        base = speedup(r, start)
        by_fit = {m: speedup(r, f.model) for m, (f, _) in fits.items()}
        rows.append((key, paper, base, by_fit))
    w = results[0].config["workload"]
    lines = []
    lines.append(f"| model | kind | paper | Fig. 3 fit alone | fitted on the lock | fitted on the head |")
    lines.append("|---|---|---:|---:|---:|---:|")
    for (model_name, kind), paper, base, by_fit in rows:
        cells = []
        for m in ("curly lock", "curly head"):
            s = by_fit[m]
            fitted = m == model_name and kind.startswith("phantom")
            text = f"{s:.2f}x ({fmt_error(s, paper)})" if s else "n/a"
            cells.append(f"*{text}*" if fitted else text)
        base_text = f"{base:.2f}x ({fmt_error(base, paper)})" if base else "n/a"
        lines.append(f"| {model_name} | {kind} | {paper:.2f}x | {base_text} | {cells[0]} | {cells[1]} |")
    lines.append("")
    for m, (f, n) in fits.items():
        if args.joint:
            lines.append(joint_footnote(m, f, n))
            continue
        p = f.parameters[0]
        where = " (at its lower bound)" if p["at_lower"] else " (at its upper bound)" if p["at_upper"] else ""
        err = f" +/- {GUIDE_FRACTION * p['std_error']:.2g}" if p["std_error"] is not None else ""
        lines.append(f"- Fitted on the {m}'s {n} phantom cells: programs at {GUIDE_FRACTION * p['fitted']:.3g}{err} of "
                     f"the CUDA Guide's throughput prices{where} (Fig. 3's fit: 0.05, at its bound), RMS log error "
                     f"{f.rms_log_error:.4f} on those cells, {f.iterations} iterations.")
    lines.append("")
    fig3_note = ""
    if args.joint:
        fw = fig3[0].config["workload"]
        fig3_note = f"; the synthetic table at {fw['width']} x {fw['height']} x {fw['spp']}"
    lines.append(f"Italics: the cells a column was fitted to; every other cell of that column is a prediction. "
                 f"Made by `scripts/table1_leave_one_out.py{' --joint' if args.joint else ''}` "
                 f"({w['width']} x {w['height']} x {w['spp']}, "
                 f"{w['bounces']} bounces, the config's sampling{fig3_note}; traced once in {traced / 60:.0f} min, "
                 f"commit {generated_blocks.commits_of(results + fig3)}).")
    text = "\n".join(lines)
    print(text)
    if args.update:
        generated_blocks.splice(args.update, {"lomo_joint" if args.joint else "lomo": text},
                                "scripts/table1_leave_one_out.py", absent_ok=False)


if __name__ == "__main__":
    main()
