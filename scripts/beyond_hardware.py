"""The tables of docs/beyond.md, Part I (the hardware after Turing), from the
output folder of `build/simulate configs/runs/beyond.json --out DIR`.
Called by `scripts/make_beyond.py hardware DIR`; standard library only.

Every number comes from the runs' report.json files: speedups and their 90 %
intervals (speedup_over_ref, speedup_interval_over_ref), the warp model's
cycles by unit (methods.<m>.cycles.<preset>.warp.breakdown), memory
(methods.<m>.memory_bytes) and the commit and presets that made them
(provenance), so a table cannot drift from the runs it describes.
"""
import glob
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import generated_blocks  # noqa: E402 (next to this script)

UNITS = [("shader", "shader (incl. AMD's loop)"), ("rt_unit", "RT unit"), ("hand_off", "hand-off"),
         ("programs", "programs")]
MIB = 1024.0 * 1024.0


def load(directory, extra=()):
    """The runs of `directory`; each folder of `extra` (beyond_rdna4.json's output: presets that build other BVH
    widths trace their own runs) adds its presets' columns to the run of the same label."""
    runs = _load_one(directory)
    by = {label(r): r for r in runs}
    for d in extra:
        for o in _load_one(d):
            r = by.get(label(o))
            if r is None:
                raise SystemExit("%s: run %s has no counterpart in %s" % (d, label(o), directory))
            _merge(r, o, d)
    return runs


def _merge(r, o, directory):
    """Adds run `o`'s preset columns (cycles, speedups, intervals, break-even maps) to run `r`, placed before
    hypothetical-obb; `o`'s BVH width is kept per preset (methods.<m>.width_by_preset)."""
    names = preset_names(o)
    for method, mo in o["methods"].items():
        m = r["methods"].setdefault(method, mo)
        cycles = dict(m.get("cycles", {}))
        for n in names:
            if n in mo.get("cycles", {}):
                cycles[n] = mo["cycles"][n]
        order = [k for k in cycles if k not in names]
        at = order.index("hypothetical-obb") if "hypothetical-obb" in order else len(order)
        order[at:at] = [n for n in names if n in cycles]
        m["cycles"] = {k: cycles[k] for k in order}
        if mo.get("structures"):
            m.setdefault("width_by_preset", {}).update({n: mo["structures"]["width"] for n in names})
    for key in ("speedup_over_ref", "speedup_interval_over_ref"):
        for method, sp in o.get(key, {}).items():
            r.setdefault(key, {}).setdefault(method, {}).update({n: v for n, v in sp.items() if n in names})
    for b in o.get("break_even", []):
        b["_dir"] = directory
        r.setdefault("break_even", []).append(b)
    r.setdefault("_extra", []).append(o)


def _load_one(directory):
    runs = []
    for path in sorted(glob.glob(os.path.join(directory, "*", "report.json"))):
        with open(path) as f:
            r = json.load(f)
        r["_label"] = os.path.basename(os.path.dirname(path))
        runs.append(r)
    if not runs:
        raise SystemExit("%s: no */report.json (run build/simulate configs/runs/beyond.json --out %s)"
                         % (directory, directory))
    return runs


def label(r):
    sp = r.get("sweep_point", {})
    kind = r["config"]["primitives"]["kind"]
    sub = r["config"]["primitives"].get("subdivision", 1)
    kind = "%s/%d" % (kind, sub) if kind == "phantom" else kind
    return "%s %s" % (kind, sp.get("scene.name") or r["config"]["scene"].get("name", r["name"]))


def provenance(runs):
    every = runs + [o for r in runs for o in r.get("_extra", [])]
    commits = sorted({r["provenance"]["git_commit"] + ("+dirty" if r["provenance"].get("git_dirty") else "")
                      for r in every})
    configs = sorted({os.path.basename(r["provenance"].get("config_file", "beyond.json")) for r in every})
    names = preset_names(runs[0])
    widths = sorted({(n, w) for r in runs for m in r["methods"].values() for n, w in m.get("width_by_preset", {}).items()})
    return ("Made by `scripts/make_beyond.py hardware` from %d runs of %s at commit %s; "
            "cost presets %s, memory preset %s%s." % (len(every), ", ".join("`configs/runs/%s`" % c for c in configs),
                                                   ", ".join(commits), ", ".join(names),
                                                   runs[0]["memory_preset"] if isinstance(runs[0]["memory_preset"], str)
                                                   else runs[0]["memory_preset"].get("name"),
                                                   "".join("; %s's columns from its own %d-wide BVHs (IS/ray and memory "
                                                           "columns: the 4-wide runs')" % w for w in widths)))


def preset_names(r):
    m = next(iter(r["methods"].values()))
    for mm in r["methods"].values():
        if mm.get("runnable"):
            return list(mm["cycles"].keys())
    return list(m.get("cycles", {}).keys())


def cell(r, method, preset):
    if method == "ref":
        c = r["methods"]["ref"]["cycles"].get(preset, {})
        return "n/a" if "n/a" in c else "1.00x"
    s = r["speedup_over_ref"].get(method, {}).get(preset)
    if not s:
        return "n/a"
    text = "%.3gx" % s
    iv = r.get("speedup_interval_over_ref", {}).get(method, {}).get(preset)
    if iv:
        text += " [%.3g-%.3g]" % (iv[0], iv[1])
    if "hypothetical" in r["methods"][method]["cycles"].get(preset, {}):
        text += " hyp."
    return text


def speedup_table(runs):
    presets = preset_names(runs[0])
    lines = ["| run | method | IS/ray | mem overhead | " + " | ".join(presets) + " |",
             "|---|---|---|---|" + "---|" * len(presets)]
    for r in runs:
        for method, m in r["methods"].items():
            if not m.get("runnable"):
                lines.append("| %s | %s | n/a | - | %s |" % (label(r), method, " | ".join("n/a" for _ in presets)))
                continue
            is_ray = m["events"].get("is_call", {}).get("per_ray", 0.0)
            over = r["memory_overhead_percent"].get(method, 0.0) if method != "ref" else 0.0
            lines.append("| %s | %s | %.3g | %+.0f%% | %s |" % (
                label(r), method, is_ray, over, " | ".join(cell(r, method, p) for p in presets)))
    return "\n".join(lines)


def decomposition(runs, scenes=("capsule bundle1000", "capsule sintel")):
    """Cycles per ray by unit of the warp model, per method and preset."""
    out = []
    for r in runs:
        if label(r) not in scenes:
            continue
        presets = preset_names(r)
        out.append("**%s**: cycles per ray, shader / RT unit / hand-off / programs (total)\n" % label(r))
        out.append("| method | " + " | ".join(presets) + " |")
        out.append("|---|" + "---|" * len(presets))
        for method, m in r["methods"].items():
            if not m.get("runnable"):
                continue
            cells = []
            for p in presets:
                c = m["cycles"].get(p, {})
                if "n/a" in c or "warp" not in c:
                    cells.append("n/a")
                    continue
                rays = max(m["rays"], 1)
                b = c["warp"]["breakdown"]
                cells.append("%s (%.0f)" % (" / ".join("%.0f" % (b[k] / rays) for k, _ in UNITS), c["total"] / rays))
            out.append("| %s | %s |" % (method, " | ".join(cells)))
        out.append("")
    return "\n".join(out)


def memory_table(runs, scene="sintel"):
    methods = [m for m in runs[0]["methods"]]
    lines = ["| kind | " + " | ".join(methods) + " |", "|---|" + "---|" * len(methods)]
    for r in runs:
        if not label(r).endswith(scene):
            continue
        cells = []
        for method in methods:
            m = r["methods"][method]
            if not m.get("runnable"):
                cells.append("n/a")
                continue
            b = m["memory_bytes"]
            cells.append("%.1f / %.1f" % (b["acceleration"] / MIB, b["total"] / MIB))
        lines.append("| %s (accel / total MiB) | %s |" % (label(r).rsplit(" ", 1)[0], " | ".join(cells)))
    return "\n".join(lines)


def recommendations(runs, kinds=("capsule", "link")):
    """Per preset and scene: the fastest method the preset's hardware runs (not
    hypothetical), its interval and memory overhead, and what obb gives."""
    presets = preset_names(runs[0])
    lines = ["| preset | scene | fastest runnable method | its memory: total, over ref | obb (the masquerade), its memory |",
             "|---|---|---|---|---|"]
    for p in presets:
        for r in runs:
            if label(r).split(" ")[0] not in kinds:
                continue
            best, best_s = "ref", 1.0
            for method, s in r["speedup_over_ref"].items():
                m = r["methods"][method]
                v = s.get(p)
                if not v or "hypothetical" in m["cycles"].get(p, {}):
                    continue
                if v > best_s:
                    best, best_s = method, v
            over = r["memory_overhead_percent"].get(best, 0.0) if best != "ref" else 0.0
            mib = r["methods"][best]["memory_bytes"]["total"] / MIB
            obb_mib = r["methods"]["obb"]["memory_bytes"]["total"] / MIB
            lines.append("| %s | %s | %s %s | %.1f MiB, %+.0f%% | %s, %.1f MiB |" % (
                p, label(r), best, cell(r, best, p), mib, over, cell(r, "obb", p), obb_mib))
    return "\n".join(lines)


def break_even_table(runs, kinds=("capsule",)):
    """Per run and map (report.json's break_even): the winner at the preset's
    own costs with its lead and the lead's 90 % interval over the cost draws,
    each method's share of the map, and the share of cells whose winner the
    draws leave in doubt (the hatched band of the picture)."""
    lines = ["| run | map (preset) | winner at the mark, lead [90 %] | share of the map won | in doubt |",
             "|---|---|---|---|---:|"]
    for r in runs:
        if label(r).split(" ")[0] not in kinds:
            continue
        for m in r.get("break_even", []):
            mark = m["mark"]
            lead = "%.3gx" % mark["lead"] if mark["lead"] is not None and math.isfinite(mark["lead"]) else "alone"
            if mark.get("lead_interval"):
                lead += " [%.3g-%.3g]" % tuple(mark["lead_interval"])
            share = ", ".join("%s %.0f%%" % (k, 100 * v) for k, v in sorted(m["winner_share"].items(), key=lambda kv: -kv[1]))
            doubt = "%.0f%%" % (100 * m["uncertain_share"]) if m.get("uncertain_share") is not None else "no draws"
            lines.append("| %s | %s (%s) | %s %s | %s | %s |" % (label(r), m["name"], m["preset"], mark["winner"], lead,
                                                               share, doubt))
    return "\n".join(lines)


def _crossings(cells, axis, at):
    """Along the row (axis "x") or column ("y") of the map through `at` (the
    other axis' mark): the winners in order with the axis values where they
    change (geometric mean of the two cells' centres), and the range of the
    cells in doubt (their centres), from a break_even_<name>.json."""
    nx, ny = cells["nx"], cells["ny"]
    other = cells["y" if axis == "x" else "x"]
    n_other = ny if axis == "x" else nx
    k = int(n_other * math.log(at / other["lo"]) / math.log(other["hi"] / other["lo"]))
    k = min(max(k, 0), n_other - 1)
    a = cells[axis]
    n = nx if axis == "x" else ny
    centre = lambda i: a["lo"] * (a["hi"] / a["lo"]) ** ((i + 0.5) / n)
    idx = [k * nx + i for i in range(nx)] if axis == "x" else [i * nx + k for i in range(ny)]
    winners = [cells["winner"][i] for i in idx]
    low = cells.get("band_low") or [None] * len(cells["winner"])
    doubt = [j for j, i in enumerate(idx) if cells["winner"][i] >= 0 and low[i] is not None and low[i] <= 1.0]
    parts = []
    for j, w in enumerate(winners):
        name = cells["methods"][w] if w >= 0 else "none"
        if not parts or parts[-1][0] != name:
            parts.append([name, math.sqrt(centre(j - 1) * centre(j)) if j else None])
    return parts, ((centre(min(doubt)), centre(max(doubt))) if doubt else None)


def _crossing_text(parts):
    if len(parts) == 1:
        return "%s everywhere" % parts[0][0]
    return ", ".join(("%s" % name) if at is None else ("%s from ~%.3g" % (name, at)) for name, at in parts)


def obb_vs_ref_table(runs, directory, kinds=("capsule",)):
    """Where obb stops paying against ref, read from each obb_vs_ref map's
    cells: along the mark's row (the hand-off swept at the preset's own
    transform) and its column (the transform swept at the preset's hand-off),
    the winners with the costs where they change, and the costs the draws
    leave in doubt (the hatched cells there)."""
    lines = ["| run | preset | hand-off swept (at the preset's transform): winners | in doubt | "
             "transform swept (at the preset's hand-off): winners | in doubt |", "|---|---|---|---|---|---|"]
    for r in runs:
        if label(r).split(" ")[0] not in kinds:
            continue
        for m in r.get("break_even", []):
            if not m["name"].startswith("obb_vs_ref"):
                continue
            with open(os.path.join(m.get("_dir", directory), r["_label"], m["cells"])) as f:
                cells = json.load(f)
            row, row_doubt = _crossings(cells, "x", m["mark"]["y"])
            col, col_doubt = _crossings(cells, "y", m["mark"]["x"])
            span = lambda d: ("%.3g" % d[0] if "%.3g" % d[0] == "%.3g" % d[1] else "%.3g-%.3g" % d) if d else "none"
            lines.append("| %s | %s (hand-off %.3g, transform %.3g) | %s | %s | %s | %s |" % (
                label(r), m["preset"], m["mark"]["x"], m["mark"]["y"], _crossing_text(row), span(row_doubt),
                _crossing_text(col), span(col_doubt)))
    return "\n".join(lines)


def _fastest(r, p):
    """The fastest method `p`'s hardware runs (not hypothetical) on run `r`, and its speedup."""
    best, best_s = "ref", 1.0
    for method, sp in r["speedup_over_ref"].items():
        v = sp.get(p)
        if v and "hypothetical" not in r["methods"][method]["cycles"].get(p, {}) and v > best_s:
            best, best_s = method, v
    return best


def answers_table(runs, directory, hair=("capsule sintel", "link sintel"), bundle="capsule bundle1000"):
    """Per preset: the fastest method on the real hair (capsules / links) and
    the dense bundle, with the masquerade beside it when it is another, the
    memory, and where obb stops paying against ref (its obb_vs_ref maps)."""
    by = {label(r): r for r in runs}
    if not all(k in by for k in hair + (bundle,)):
        return ""
    presets = preset_names(runs[0])
    lines = ["| preset | real hair, Sintel capsules / links: fastest | its memory (capsules): total, over ref | "
             "dense bundle (capsules): fastest | obb against ref (obb_vs_ref maps, capsules): obb wins from a hand-off "
             "of (at the preset's transform), up to a transform of (at the preset's hand-off); [in doubt] |",
             "|---|---|---|---|---|"]
    for p in presets:
        caps, links, bun = by[hair[0]], by[hair[1]], by[bundle]
        b = _fastest(caps, p)
        text = "%s %s / %s" % (b, cell(caps, b, p), cell(links, _fastest(links, p), p)
                               if _fastest(links, p) == b else "%s %s" % (_fastest(links, p), cell(links, _fastest(links, p), p)))
        if b != "obb":
            text += "; obb %s / %s" % (cell(caps, "obb", p), cell(links, "obb", p))
        m = caps["methods"][b]["memory_bytes"]["total"] / MIB
        over = caps["memory_overhead_percent"].get(b, 0.0) if b != "ref" else 0.0
        bb = _fastest(bun, p)
        btext = "%s %s" % (bb, cell(bun, bb, p)) + ("; obb %s" % cell(bun, "obb", p) if bb != "obb" else "")
        stops = []
        for name, r in (("Sintel", caps), ("bundle", bun)):
            m_ = next((x for x in r.get("break_even", []) if x["name"].startswith("obb_vs_ref") and x["preset"] == p), None)
            if not m_:
                continue
            with open(os.path.join(m_.get("_dir", directory), r["_label"], m_["cells"])) as f:
                cells = json.load(f)
            row, rd = _crossings(cells, "x", m_["mark"]["y"])
            col, cd = _crossings(cells, "y", m_["mark"]["x"])
            at = lambda parts, who: next(("~%.3g" % x for n, x in parts if n == who and x), None)
            frm = at(row, "obb") or ("any" if row[0][0] == "obb" and len(row) == 1 else "never")
            upto = at(col, "ref") or ("any" if col[0][0] == "obb" and len(col) == 1 else "none")
            span = lambda d: (" [%.3g]" % d[0] if "%.3g" % d[0] == "%.3g" % d[1] else " [%.3g-%.3g]" % d) if d else ""
            stops.append("%s: from %s%s, up to %s%s" % (name, frm, span(rd), upto, span(cd)))
        lines.append("| %s | %s | %.1f MiB, %+.0f%% | %s | %s |" % (
            p, text, m, over, btext, "; ".join(stops) or "no obb_vs_ref map (see the all-method maps)"))
    return "\n".join(lines)


def _short_source(text):
    """"[D] NVIDIA GA102 whitepaper, 2020: twice ..." -> ("D", "NVIDIA GA102 whitepaper, 2020")."""
    tag, rest = "", text.strip()
    if rest.startswith("[") and "]" in rest:
        tag, rest = rest[1:rest.index("]")], rest[rest.index("]") + 1:].strip()
    import re
    if not tag:  # a tag at the end: "... (CUDA Programming Guide) [D]."
        m = re.search(r"\[([DMCI])\]", rest)
        tag = m.group(1) if m else ""
    for stop in (": ", "; ", ". "):
        if stop in rest:
            rest = rest[:rest.index(stop)]
    cut = len(rest) > 80
    rest = rest[:77] if cut else rest
    if rest.count("(") > rest.count(")"):  # no half parenthesis
        rest, cut = rest[:rest.rindex(" (")], True
    return tag, rest + ("..." if cut else "")


def _delta_text(d):
    events = ", ".join("`%s`" % e for e in d["events"])
    if "scale" in d:
        what = "%s x%g" % (events, d["scale"])
    elif "sum_of" in d:
        what = "%s = %s" % (events, " + ".join("%g %s" % (v, k) for k, v in d["sum_of"].items()))
    else:
        what = "%s = %g" % (events, d.get("value", float("nan")))
    tag, short = _short_source(d.get("source", ""))
    return "%s [%s: %s]" % (what, tag or "?", short)


def preset_table(names, root):
    """Each hardware preset as its file states it: what it derives from, its
    deltas with their tags and the first clause of their sources, its
    execution-model changes and the features it adds over the one before."""
    lines = ["| preset | derived from | deltas [tag: source, first clause] | features added |", "|---|---|---|---|"]
    features = {}
    for name in names:
        with open(os.path.join(root, "configs", "hw", name + ".json")) as f:
            j = json.load(f)
        parent = (j.get("derived_from") or "").replace(".json", "")
        feats = j.get("features", [])
        features[name] = feats
        deltas = [_delta_text(d) for d in j.get("deltas", [])]
        execution = dict((j.get("execution") or {}).items()) if parent else {}
        for sub, v in execution.pop("sm", {}).items():  # the SM block, entry by entry
            execution["sm." + sub] = v
        for key, v in execution.items():
            if isinstance(v, dict) and isinstance(v.get("value"), dict):
                v = dict(v, value=["%s %s" % kv for kv in v["value"].items()])
            if isinstance(v, dict) and "value" in v:
                val = v["value"]
                tag, short = _short_source(v.get("source", ""))
                deltas.append("execution `%s` = %s [%s: %s]" % (
                    key, ", ".join(map(str, val)) if isinstance(val, list) else val, tag or "?", short))
        base = features.get(parent)
        if base is None and parent:
            with open(os.path.join(root, "configs", "hw", parent + ".json")) as f:
                base = json.load(f).get("features", [])
        added = [x for x in feats if x not in (base or [])] if parent else []
        lines.append("| %s | %s | %s | %s |" % (name, parent or "- (fitted)", "; ".join(deltas) or (
                     "-" if parent else "- (fitted to the synthetic table; the SIMT warp model)"),
                                                ", ".join(added) or "-"))
    return "\n".join(lines)


def report(directory, extra=()):
    runs = load(directory, extra)
    parts = [provenance(runs), "", "### Speedup over ref, 90 % interval", "", speedup_table(runs), "",
             "### Where the cycles go", "", decomposition(runs), "### Memory on the Sintel hair (memory preset of the run)",
             "", memory_table(runs), "", "### Which method to build", "", recommendations(runs), "",
             "### Where each stops paying: the break-even maps at the mark, and the band the draws leave in doubt", "",
             break_even_table(runs), "", "Where obb stops paying against ref (the obb_vs_ref maps through the mark; "
             "costs in cycles, \"from ~X\": the cost where the winner changes, between two cells' centres):", "",
             obb_vs_ref_table(runs, directory)]
    return "\n".join(parts) + "\n"


def presets_block(directory, root, extra=()):
    """The preset table of the runs' cost presets, read from configs/hw, with its stamp."""
    runs = load(directory, extra)
    names = preset_names(runs[0])
    return (preset_table(names, root) + "\n\nMade by `scripts/make_beyond.py hardware` from `configs/hw/<preset>.json` "
            "of the cost presets of the runs below (%s), as last changed at commit %s; the runs below are of "
            "commit %s.\n" % (", ".join(names), last_change(["configs/hw/%s.json" % n for n in names], root),
                              ", ".join(sorted({r["provenance"]["git_commit"] for r in runs}))))


def last_change(files, root):
    """The commit that last changed `files` (paths relative to `root`), "+ uncommitted changes" when they differ
    from it."""
    import subprocess
    try:
        commit = subprocess.run(["git", "log", "-1", "--format=%h", "--"] + files, cwd=root, capture_output=True,
                                text=True, check=True).stdout.strip()
        dirty = subprocess.run(["git", "status", "--porcelain", "--"] + files, cwd=root, capture_output=True,
                               text=True, check=True).stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        commit, dirty = "unknown", ""
    return (commit or "uncommitted") + (" (+ uncommitted changes)" if dirty else "")


def blocks(directory, root, extra=()):
    """{generated block name: text} of docs/beyond.md Part I; `extra`: folders of runs of presets with their own
    BVH width (beyond_rdna4.json), merged in as columns."""
    runs = load(directory, extra)
    answers = answers_table(runs, directory)
    out = {"hardware": report(directory, extra), "hardware-presets": presets_block(directory, root, extra)}
    if answers:
        out["hardware-answers"] = answers + "\n\n" + provenance(runs) + "\n"
    return out


def splice(path, texts):
    """Replaces each block "<!-- generated by scripts/make_beyond.py NAME: begin -->"
    ... "end -->" in `path` with its text (every block must be there)."""
    generated_blocks.splice(path, texts, "scripts/make_beyond.py", absent_ok=False)


