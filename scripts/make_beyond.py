#!/usr/bin/env python3
"""Collects report.json files into the Markdown tables of docs/beyond.md.

usage: scripts/make_beyond.py hardware [--update docs/beyond.md] RUN_DIR [RDNA4_DIR] > part1.md
  Part I (the hardware after Turing): RUN_DIR is the output of
  build/simulate configs/runs/beyond.json --out RUN_DIR (scripts/beyond_hardware.py),
  RDNA4_DIR that of configs/runs/beyond_rdna4.json (rdna4 builds 8-wide BVHs, so
  it traces its own runs; its columns are merged in beside the others);
  --update replaces the generated blocks "hardware-presets" (the presets'
  deltas, read from configs/hw) and "hardware" (every table of the runs) of
  that file (between their markers), each ending with its commit and presets.
usage: scripts/make_beyond.py checked [--update docs/beyond.md] NAME=PATH[,PATH...] ... > checked.md
  The table "checked against measurements" (scripts/beyond_checked.py): each
  external figure beside the model's prediction; NAME is a kind of check
  (lss-dots=RUN_DIR,BAND_DIR; embree=BENCH_JSON,RUN_DIR); --update replaces
  the block "checked" and the checks' own ("checked-embree": bench
  --embree-hair's figures beside the simulator's counts).
usage: scripts/make_beyond.py [--svg PLOT.svg] [--update docs/beyond.md] RUN_DIR [RUN_DIR ...] > tables.md
  Part II (section "cluster: the paper's future work"); --update replaces
  its generated blocks "cluster" (the orientation table and the verdicts)
  and "cluster-full" (every row), each ending with the commit and presets
  of its runs, and "memory-records" (each memory preset's instance and BLAS
  record, read from configs/hw, with the commit that last changed them).
Each RUN_DIR is the output of
  build/simulate configs/runs/cluster_sweep.json --out RUN_DIR
(or configs/runs/cluster_fur20m.json). Memory is repriced from the reported
structure counts under every preset in configs/hw/memory-*.json. Cluster
size 1 is the per-primitive masquerade (obb), count for count. With --svg,
also writes the Pareto plot of every model: speedup (first cost preset)
against memory overhead (OptiX 7), one line per model and strategy, the
points labelled by cluster size. Only the Python standard library is used.
"""
import glob
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import beyond_checked  # noqa: E402 (next to this script): the "checked" block
import beyond_hardware  # noqa: E402 (next to this script): splice, last_change

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
PRESETS = ["memory-optix7", "memory-dxr", "memory-optix-record"]
MIB = 1024.0 * 1024.0


def load_presets():
    out = {}
    for name in PRESETS:
        with open(os.path.join(ROOT, "configs", "hw", name + ".json")) as f:
            j = json.load(f)
        out[name] = {k: v["value"] for k, v in j["bytes"].items()}
        out[name]["instance_includes_tlas_nodes"] = j.get("instance_includes_tlas_nodes", {}).get("value", False)
    return out


def memory_records_block():
    """The per-instance and per-BLAS bytes of every memory preset with the BLAS record's source, read from
    configs/hw/memory-*.json, stamped with the commit that last changed them."""
    files = ["configs/hw/%s.json" % n for n in PRESETS]
    lines = ["| preset | instance | BLAS record | source of the BLAS record |", "|---|---|---|---|"]
    for name, path in zip(PRESETS, files):
        with open(os.path.join(ROOT, path)) as f:
            b = json.load(f)["bytes"]
        lines.append("| `%s` | %d B | %d B | %s |" % (name, b["instance"]["value"], b["blas"]["value"],
                                                    b["blas"]["source"].replace("|", "/")))
    return "\n".join(lines) + "\n\nMade by `scripts/make_beyond.py` from %s, as last changed at commit %s." % (
        ", ".join("`%s`" % f for f in files), beyond_hardware.last_change(files, ROOT))


def reports(directory):
    paths = glob.glob(os.path.join(directory, "*", "report.json")) or \
        glob.glob(os.path.join(directory, "report.json"))
    def order(p):
        head = os.path.basename(os.path.dirname(p)).split("_")[0]
        return int(head) if head.isdigit() else 0
    out = []
    for path in sorted(paths, key=order):
        with open(path) as f:
            out.append(json.load(f))
    return out


def total_bytes(method, preset):
    """Acceleration structures under `preset` plus the shared data."""
    # As price_memory (sim/hardware/memory_model.cpp): a preset whose
    # instance price includes the TLAS nodes does not count them again.
    s = method["structures"]
    node = preset["node_w%d" % s["width"]]
    tlas = 0 if preset["instance_includes_tlas_nodes"] and s["instances"] > 0 else s["tlas_nodes"]
    accel = (tlas + s["blas_nodes"]) * node + s["instances"] * preset["instance"] + \
        s["custom_prims"] * preset["custom_prim"] + s["triangles"] * preset["triangle"] + \
        s.get("lss_prims", 0) * preset["lss_prim"] + s.get("oriented_children", 0) * preset["obb_child"] + \
        s.get("leaf_obbs", 0) * preset["leaf_obb"] + s.get("blases", 0) * preset["blas"] + \
        s.get("strip_vertices", 0) * preset["mesh_vertex"] + s.get("strip_triangles", 0) * preset["mesh_triangle"]
    return accel + method["memory_bytes"]["common"]


def fmt(x, digits=3):
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "n/a"
    return ("%." + str(digits) + "g") % x


def provenance(runs, script="scripts/make_beyond.py"):
    """The commits, configs and presets that made `runs` (report.json's provenance)."""
    commits = sorted({r.get("provenance", {}).get("git_commit", "unknown") +
                      ("+dirty" if r.get("provenance", {}).get("git_dirty") else "") for r in runs})
    configs = sorted({os.path.basename(r.get("provenance", {}).get("config_file", "?")) for r in runs})
    costs = list(dict.fromkeys(p if isinstance(p, str) else p.get("name") for r in runs for p in r["cost_presets"]))
    memory = sorted({r["memory_preset"] if isinstance(r["memory_preset"], str) else r["memory_preset"].get("name")
                     for r in runs})
    return ("Made by `%s` from %d runs of %s at commit %s; cost presets %s (speedups: the first), memory preset %s "
            "(repriced under %s)." % (script, len(runs), ", ".join("`configs/runs/%s`" % c for c in configs),
                                      ", ".join(commits), ", ".join(costs), ", ".join(memory), ", ".join(PRESETS)))


def rows(runs, presets):
    out = []
    for r in runs:
        sp = r.get("sweep_point", {})
        ref, cl = r["methods"]["ref"], r["methods"]["cluster"]
        cfg = r["config"].get("cluster", {})
        row = {
            "scene": sp.get("scene.name") or r["config"]["scene"].get("name") or r["name"],
            "prims": r["scene"]["primitives"],
            "strategy": sp.get("cluster.strategy", cfg.get("strategy", "orientation")),
            "size": sp.get("cluster.size", cfg.get("size", 16)),
            "instances": cl["instances"],
            "runnable": cl["runnable"],
        }
        if not cl["runnable"]:
            row["reason"] = cl["reason"]
            out.append(row)
            continue
        presets_cyc = list(cl["cycles"].keys())
        row["cyc"] = cl["cycles"][presets_cyc[0]]["per_ray"]
        row["ref_cyc"] = ref["cycles"][presets_cyc[0]]["per_ray"]
        row["ref_cyc_all"] = [ref["cycles"][p]["per_ray"] for p in presets_cyc]
        row["is"] = cl["events"]["is_call"]["per_ray"]
        row["ref_is"] = ref["events"]["is_call"]["per_ray"]
        row["inst"] = cl["events"]["instance_transform"]["per_ray"]
        row["speedup"] = [r["speedup_over_ref"]["cluster"].get(p) for p in presets_cyc]
        row["ref_mem"] = {p: total_bytes(ref, presets[p]) for p in presets}
        row["mem"] = {p: total_bytes(cl, presets[p]) for p in presets}
        row["build"] = cl["simulator"]["build_seconds"]
        row["ref_build"] = ref["simulator"]["build_seconds"]
        row["rays"] = cl["rays"]
        out.append(row)
    return out


def table(rs):
    lines = ["| model | strategy | size | instances | cycles/ray | IS calls/ray | instance transforms/ray "
             "| speedup (calibrated / guess) | memory, OptiX 7 | overhead OptiX 7 / DXR / records | build (s) |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rs:
        head = "| %s | %s | %d | %s |" % (r["scene"], r["strategy"], r["size"], format(r["instances"], ","))
        if not r["runnable"]:
            lines.append(head + " n/a | | | | | %s | |" % r["reason"])
            continue
        over = [100.0 * (r["mem"][p] / r["ref_mem"][p] - 1.0) for p in PRESETS]
        lines.append(head + " %s | %s | %s | %s | %.1f MiB | %s | %.1f |" % (
            fmt(r["cyc"], 4), fmt(r["is"]), fmt(r["inst"]),
            " / ".join(fmt(s) + "x" for s in r["speedup"]),
            r["mem"]["memory-optix7"] / MIB, " / ".join("%+.0f%%" % o for o in over), r["build"]))
    return "\n".join(lines)


def reference_table(rs):
    """Per model, `ref` (the baseline of every speedup): cycles per ray under each cost preset."""
    lines = ["| model | capsules | ref cycles/ray (each cost preset) | ref IS calls/ray | ref memory (OptiX 7) |",
             "|---|---|---|---|---|"]
    for scene in dict.fromkeys(r["scene"] for r in rs):
        r = next((r for r in rs if r["scene"] == scene and r["runnable"]), None)
        if r:
            lines.append("| %s | %s | %s | %s | %.1f MiB |" % (
                scene, format(r["prims"], ","), " / ".join(format(c, ",.4g") for c in r["ref_cyc_all"]),
                fmt(r["ref_is"]), r["ref_mem"]["memory-optix7"] / MIB))
    return "\n".join(lines)


def verdicts(rs):
    """Per model: the masquerade (size 1) and the best cluster size within +50 % memory (OptiX 7)."""
    lines = ["| model | obb (= size 1) speedup, overhead | best within +50 % memory (OptiX 7) | share of obb's speedup |",
             "|---|---|---|---|"]
    for scene in dict.fromkeys(r["scene"] for r in rs):
        mine = [r for r in rs if r["scene"] == scene and r["runnable"]]
        one = [r for r in mine if r["size"] == 1]
        within = [r for r in mine if 100.0 * (r["mem"]["memory-optix7"] / r["ref_mem"]["memory-optix7"] - 1) <= 50.0
                  and r["size"] > 1]
        if not within:
            continue
        best = max(within, key=lambda r: r["speedup"][0] or 0)
        over = overhead(best)
        if one:
            o = one[0]
            oover = 100.0 * (o["mem"]["memory-optix7"] / o["ref_mem"]["memory-optix7"] - 1)
            obb = "%sx, %+.0f%%" % (fmt(o["speedup"][0]), oover)
            share = "%.0f %%" % (100.0 * best["speedup"][0] / o["speedup"][0])
        else:
            obb, share = "n/a (over the instance limit)", "-"
        lines.append("| %s | %s | %s, size %d, %sx at %+.0f%% | %s |" % (
            scene, obb, best["strategy"], best["size"], fmt(best["speedup"][0]), over, share))
    return "\n".join(lines)


def overhead(r, preset="memory-optix7"):
    return 100.0 * (r["mem"][preset] / r["ref_mem"][preset] - 1.0)


def pareto_svg(rs, path):
    """Speedup against memory overhead, one polyline per (model, strategy)."""
    series = {}
    for r in rs:
        if r["runnable"] and r["speedup"][0]:
            series.setdefault((r["scene"], r["strategy"]), []).append((overhead(r), r["speedup"][0], r["size"]))
    W, H, L, R, T, B = 760, 520, 70, 250, 40, 60
    xmax = max(x for pts in series.values() for x, _, _ in pts)
    xmax = 50.0 * math.ceil(xmax / 50.0)
    ymax = 0.5 * math.ceil(max(y for pts in series.values() for _, y, _ in pts) / 0.5)
    X = lambda x: L + (W - L - R) * x / xmax
    Y = lambda y: H - B - (H - T - B) * y / ymax
    colours = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2", "#17becf"]
    out = ['<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d" font-family="sans-serif" font-size="12">' % (W, H),
           '<rect width="100%" height="100%" fill="white"/>',
           '<text x="%d" y="22" font-size="15">cluster: speedup over ref vs memory overhead (labels: cluster size; 1 = obb)</text>' % L]
    for i in range(int(xmax / 50) + 1):
        x = X(50.0 * i)
        out.append('<line x1="%.1f" y1="%d" x2="%.1f" y2="%d" stroke="#ddd"/>' % (x, T, x, H - B))
        out.append('<text x="%.1f" y="%d" text-anchor="middle">%d</text>' % (x, H - B + 16, 50 * i))
    for i in range(int(ymax / 0.5) + 1):
        y = Y(0.5 * i)
        out.append('<line x1="%d" y1="%.1f" x2="%d" y2="%.1f" stroke="#ddd"/>' % (L, y, W - R, y))
        out.append('<text x="%d" y="%.1f" text-anchor="end">%.1f</text>' % (L - 6, y + 4, 0.5 * i))
    out.append('<line x1="%d" y1="%.1f" x2="%d" y2="%.1f" stroke="#888" stroke-dasharray="4 3"/>' % (L, Y(1), W - R, Y(1)))
    out.append('<text x="%d" y="%d" text-anchor="middle">total memory over ref (%%), OptiX 7 preset</text>' % ((L + W - R) // 2, H - 18))
    out.append('<text transform="translate(18 %d) rotate(-90)" text-anchor="middle">speedup over ref (turing-calibrated)</text>' % ((T + H - B) // 2))
    # Labels: one per drawn position, not per point. Sizes whose points
    # coincide (a strand cluster cannot outgrow its strand; size 1 is the
    # same masquerade under both strategies) share one label ("4-256"), and
    # each label goes where it overlaps no other label and no point (the
    # first free spot on rings around its point, with a leader line when
    # away from it), so none of them is drawn over another.
    FONT, CHAR = 9, 5.2  # font size and a digit's width at that size (px)
    groups = {}  # drawn position -> [colour, sizes]
    for n, ((scene, strategy), pts) in enumerate(sorted(series.items())):
        for x, y, k in pts:
            g = groups.setdefault((round(X(x)), round(Y(y))), [colours[n % len(colours)], []])
            if k not in g[1]:
                g[1].append(k)

    def label_text(sizes):
        sizes = sorted(sizes)
        runs, start = [], 0
        for i in range(1, len(sizes) + 1):  # consecutive cluster sizes (powers of two) as a range
            if i == len(sizes) or sizes[i] != 2 * sizes[i - 1]:
                runs.append(str(sizes[start]) if i - start == 1 else "%d-%d" % (sizes[start], sizes[i - 1]))
                start = i
        return ",".join(runs)

    def overlaps(a, b):
        return a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]

    dots = [(X(x), Y(y)) for pts in series.values() for x, y, _ in pts]
    taken = [(px - 3.5, py - 3.5, px + 3.5, py + 3.5) for px, py in dots]  # the dots (r = 3), and a margin
    labels = []
    for (px, py), (c, sizes) in sorted(groups.items()):
        text = label_text(sizes)
        w = CHAR * len(text)
        spot = None
        for ring in range(1, 16):
            d = 4 + 7 * (ring - 1)
            for dx, dy in ((1, -1), (1, 1), (-1, -1), (-1, 1), (1, 0), (-1, 0), (0, -1), (0, 1)):
                x0 = px + dx * d if dx >= 0 else px - d - w
                if dx == 0:
                    x0 = px - w / 2
                base = py + dy * d + (FONT if dy > 0 else 0) + (FONT / 2 if dy == 0 else 0)
                box = (x0, base - FONT, x0 + w, base)
                if box[0] < L or box[2] > W - R or box[1] < T or box[3] > H - B:
                    continue
                if not any(overlaps(box, t) for t in taken):
                    spot = (box, base, ring)
                    break
            if spot:
                break
        if not spot:
            continue  # no free spot: the point stays unlabelled rather than covered
        box, base, ring = spot
        taken.append(box)
        labels.append((px, py, box, base, ring, c, text))
    for n, ((scene, strategy), pts) in enumerate(sorted(series.items())):
        c = colours[n % len(colours)]
        dash = '' if strategy == "orientation" else ' stroke-dasharray="5 3"'
        out.append('<polyline fill="none" stroke="%s" stroke-width="1.6"%s points="%s"/>' % (
            c, dash, " ".join("%.1f,%.1f" % (X(x), Y(y)) for x, y, _ in pts)))
        for x, y, k in pts:
            out.append('<circle cx="%.1f" cy="%.1f" r="3" fill="%s"/>' % (X(x), Y(y), c))
        ly = T + 10 + 18 * n
        out.append('<line x1="%d" y1="%d" x2="%d" y2="%d" stroke="%s" stroke-width="2"%s/>' % (W - R + 12, ly, W - R + 36, ly, c, dash))
        out.append('<text x="%d" y="%d">%s, %s</text>' % (W - R + 42, ly + 4, scene, strategy))
    for px, py, box, base, ring, c, text in labels:
        if ring > 1:  # away from its point: a leader line to the label's nearest corner
            lx = min(max(px, box[0]), box[2])
            ly = min(max(py, box[1]), box[3])
            out.append('<line x1="%d" y1="%d" x2="%.1f" y2="%.1f" stroke="%s" stroke-width="0.6"/>' % (px, py, lx, ly, c))
        out.append('<text x="%.1f" y="%.1f" font-size="%d" fill="%s" data-point="%d %d">%s</text>' % (
            box[0], base, FONT, c, px, py, text))
    out.append('</svg>')
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


def main():
    args = sys.argv[1:]
    if args[:1] == ["hardware"]:
        update = None
        if len(args) >= 4 and args[1] == "--update":
            update, args = args[2], args[:1] + args[3:]
        if len(args) < 2:
            sys.exit(__doc__)
        texts = beyond_hardware.blocks(args[1], ROOT, args[2:])
        if update:
            beyond_hardware.splice(update, texts)
        else:
            sys.stdout.write(texts["hardware-presets"] + "\n" + texts["hardware"])
        return
    if args[:1] == ["checked"]:
        update = None
        if len(args) >= 3 and args[1] == "--update":
            update, args = args[2], args[:1] + args[3:]
        if len(args) < 2:
            sys.exit(__doc__)
        texts = beyond_checked.block(args[1:])
        if update:
            beyond_hardware.splice(update, texts)
        else:
            sys.stdout.write("\n".join(texts.values()))
        return
    svg = update = None
    while len(args) >= 2 and args[0] in ("--svg", "--update"):
        if args[0] == "--svg":
            svg = args[1]
        else:
            update = args[1]
        args = args[2:]
    if not args:
        sys.exit(__doc__)
    presets = load_presets()
    runs = []
    for d in args:
        runs += reports(d)
    rs = rows(runs, presets)
    stamp = provenance(runs)
    orientation = table([r for r in rs if r["strategy"] == "orientation"])
    bar = ("The issue's bar: keep >= 90 % of the masquerade's speedup at <= 50 % memory overhead "
           "(OptiX 7, the first cost preset):")
    blocks = {"cluster": "\n".join([stamp, "", "Reference runs (`ref`, the baseline of every speedup):", "",
                                     reference_table(rs), "", "The orientation strategy (size 1 = `obb`; overheads are total memory "
                                     "over `ref`'s under the OptiX 7 / DXR / OptixInstance-record presets):", "",
                                     orientation, "", bar, "", verdicts(rs)]),
              "cluster-full": "\n".join(["<details><summary>every strategy and size (%d runs)</summary>" % len(rs), "",
                                          table(rs), "", stamp, "", "</details>"]),
              "memory-records": memory_records_block()}
    print(blocks["cluster"])
    print()
    print(blocks["cluster-full"])
    if update:
        beyond_hardware.splice(update, blocks)
    if svg:
        pareto_svg(rs, svg)


if __name__ == "__main__":
    main()
