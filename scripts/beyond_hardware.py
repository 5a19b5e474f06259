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

UNITS = [("shader", "shader (incl. AMD's loop)"), ("rt_unit", "RT unit"), ("hand_off", "hand-off"),
         ("programs", "programs")]
MIB = 1024.0 * 1024.0


def load(directory):
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
    commits = sorted({r["provenance"]["git_commit"] + ("+dirty" if r["provenance"].get("git_dirty") else "")
                      for r in runs})
    presets = runs[0]["cost_presets"] if isinstance(runs[0]["cost_presets"], list) else list(runs[0]["cost_presets"])
    names = [p if isinstance(p, str) else p.get("name") for p in presets]
    return ("Made by `scripts/make_beyond.py hardware` from %d runs of `configs/runs/beyond.json` at commit %s; "
            "cost presets %s, memory preset %s." % (len(runs), ", ".join(commits), ", ".join(names),
                                                 runs[0]["memory_preset"] if isinstance(runs[0]["memory_preset"], str)
                                                 else runs[0]["memory_preset"].get("name")))


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


def report(directory):
    runs = load(directory)
    parts = [provenance(runs), "", "### Speedup over ref, 90 % interval", "", speedup_table(runs), "",
             "### Where the cycles go", "", decomposition(runs), "### Memory on the Sintel hair (memory preset of the run)",
             "", memory_table(runs), "", "### Which method to build", "", recommendations(runs), "",
             "### Where each stops paying: the break-even maps at the mark, and the band the draws leave in doubt", "",
             break_even_table(runs)]
    return "\n".join(parts) + "\n"


BEGIN = "<!-- generated by scripts/make_beyond.py hardware: begin -->"
END = "<!-- generated by scripts/make_beyond.py hardware: end -->"


def splice(path, text):
    """Replaces the block between BEGIN and END in `path` with `text`."""
    with open(path) as f:
        doc = f.read()
    if BEGIN not in doc or END not in doc:
        raise SystemExit("%s: no generated block (%s ... %s)" % (path, BEGIN, END))
    head, rest = doc.split(BEGIN, 1)
    tail = rest.split(END, 1)[1]
    with open(path, "w") as f:
        f.write(head + BEGIN + "\n" + text + END + tail)
