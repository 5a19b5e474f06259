"""The table "checked against measurements" of docs/beyond.md (issue 54 item 7):
each row an external figure (published, or measured on this machine), its
source, the scene, the model's prediction with its band, the figure and the
error. Called by `scripts/make_beyond.py checked`; standard library only.

Each kind of check is one function that takes the paths of its runs and
returns its rows (see row()), the stamp of the runs that made them and any
blocks of its own (the Embree check's measurements in detail,
"checked-embree"); CHECKS maps the name given on the command line
(`NAME=PATH[,PATH...]`) to it. A new check (say oriented
boxes over triangles, from a results.csv) is one more function and one more
entry. A figure the model misses stays in the table, with why in its note.
Nothing here feeds back into a preset: these are checks, not targets.

"""
import glob
import json
import os

# "about X" in a source: taken as X +-10 % when deciding whether the band meets it.
ABOUT = 0.10


def _runs(directory):
    """Every report.json under `directory`, by scene name."""
    out = {}
    for path in sorted(glob.glob(os.path.join(directory, "*", "report.json"))) or \
            glob.glob(os.path.join(directory, "report.json")):
        with open(path) as f:
            r = json.load(f)
        name = r.get("sweep_point", {}).get("scene.name") or r["config"]["scene"].get("name") or r["name"]
        out[name] = r
    if not out:
        raise SystemExit("%s: no report.json (run build/simulate on its config first)" % directory)
    return out


def _commit(runs):
    return ", ".join(sorted({r["provenance"]["git_commit"] + ("+dirty" if r["provenance"].get("git_dirty") else "")
                             for r in runs}))


def _first_preset(r):
    p = r["cost_presets"][0]
    return p if isinstance(p, str) else p["name"]


def _speedup(r, method, preset):
    """Speedup over the run's baseline (report.json's speedup_over_<baseline>) and its interval ((lo, hi) or
    None)."""
    base = next(k[len("speedup_over_"):] for k in r if k.startswith("speedup_over_"))
    s = r["speedup_over_" + base][method][preset]
    iv = r.get("speedup_interval_over_" + base, {}).get(method, {}).get(preset)
    return s, (tuple(iv) if iv else None)


def _memory(r, method):
    return r["methods"][method]["memory_bytes"]["total"]


def row(figure, source, scene, model, band, measured, note=""):
    """measured: (lo, hi, text, central) of the figure: the range a band must meet to agree (lo == hi for a
    point, "about X" as X +-ABOUT) and the value the error is taken against (None: the range's nearer end)."""
    return {"figure": figure, "source": source, "scene": scene, "model": model, "band": band,
            "measured": measured, "note": note}


def about(x):
    return (x * (1 - ABOUT), x * (1 + ABOUT), "about %gx" % x, x)


def point(x, text=None):
    return (x, x, text or "%#.3gx" % x, x)


def between(lo, hi):
    return (lo, hi, "%g-%gx" % (lo, hi), None)


def spread(median, lo, hi):
    """A local measurement: the median of alternated pairs (what a band must meet: on a shared machine one
    pair's ratio can stray far) and the pairs' range (shown)."""
    return (median, median, "%.2fx [%.2f-%.2f]" % (median, lo, hi), median)


# --- lss against dots (configs/runs/lss_vs_dots.json) -------------------------

def lss_dots_rows(run_dir, band_dir):
    """NVIDIA's LSS-over-DOTS speed and DOTS-over-LSS memory on human hair (RTX 50). run_dir: ref, lss, dots
    with ref as baseline; band_dir: the same with baseline lss (dots' speedup over lss carries the interval)."""
    runs, band = _runs(run_dir), _runs(band_dir)
    blog = "NVIDIA blog 2025 (RTX 50, animated human hair)"
    perf = "RTXCR docs/RtxcrLssPerf.md (RTX 5090, frame time / all video memory)"
    speed_note = ("the model has no BVH update of animated hair and no memory traffic; "
                  "its DOTS and LSS trees are the same size (beyond.md, 'lss against dots')")
    out = []
    for scene, r in runs.items():
        p = _first_preset(r)
        s = _speedup(r, "lss", p)[0] / _speedup(r, "dots", p)[0]
        iv = None
        if scene in band:  # the same counts with lss as the baseline: dots' speedup over lss and its interval
            d, div = _speedup(band[scene], "dots", p)
            s = 1.0 / d
            if div:
                iv = (1.0 / div[1], 1.0 / div[0])
        out.append(row("LSS speed over DOTS", blog, scene, s, iv, about(2), speed_note))
        if scene == "sintel":
            out.append(row("LSS speed over DOTS", perf, scene, s, iv, point(6.37 / 4.94, "1.29x"),
                           "a static frame: closer to the model, no update to pay"))
        m = _memory(r, "dots") / _memory(r, "lss")
        out.append(row("DOTS memory over LSS", blog + ", 'to store the geometry'", scene, m, None, about(5),
                       "the model counts 144 B of strip buffers per segment, RTXCR 432 B"))
        if scene == "sintel":
            out.append(row("DOTS memory over LSS", perf, scene, m, None, point(3388.0 / 2450.0, "1.38x"),
                           "all video memory (frame buffers, denoiser, textures), not the geometry alone"))
    return out, "`configs/runs/lss_vs_dots.json` (%s) at commit %s" % (_first_preset(next(iter(runs.values()))),
                                                                      _commit(list(runs.values()))), {}


# --- Embree's oriented hair BVH (configs/runs/embree_hair.json) ---------------

def embree_rows(bench_json, run_dir):
    """obb-nodes over ref (the model) beside Embree's oriented hair BVH over its aligned BVH, measured here by
    `build/bench --embree-hair` on the same scenes and rays, and the published figures. bench_json: bench's
    --json; run_dir: simulate's output of the same config."""
    with open(bench_json) as f:
        bench = json.load(f)
    runs = _runs(run_dir)
    woop = "Woop et al. 2014 (Embree, over pre-tessellated hair)"
    wald = "Wald et al. 2020, quoting Embree's oriented nodes"
    speed_note = ("Embree's aligned side runs a scalar callback per segment, its oriented side a SIMD test of 8: "
                  "the CPU ratio holds both; beyond.md, 'obb-nodes against Embree'")
    out = []
    for e in bench["scenes"]:
        scene = e["scene"]
        r = runs.get(scene)
        if r is None:
            continue
        p = _first_preset(r)
        s, iv = _speedup(r, "obb-nodes", p)
        emb = e["embree"]
        rate = max(emb["rates"], key=lambda x: x["threads"])
        med, lo, hi = rate["speedup"]
        local = "Embree %s, measured here (%d threads, %d pairs)" % (emb["version"], rate["threads"], emb["repeat"])
        out.append(row("oriented over aligned BVH, speed", local, scene, s, iv,
                       spread(med, lo, hi), speed_note))
        out.append(row("oriented over aligned BVH, speed", woop, scene, s, iv, about(2),
                       "a different baseline (triangles) and other scenes"))
        out.append(row("oriented over aligned BVH, speed", wald, scene, s, iv, between(2, 2.5),
                       "Embree's oriented nodes on CPUs (rt-hardware.md, sec. 7)"))
        m = _memory(r, "obb-nodes") / _memory(r, "ref")
        bvh_a, bvh_o = emb["aligned"]["bvh"], emb["oriented"]["bvh"]
        nodes_a = bvh_a["aligned_nodes"] + bvh_a["oriented_nodes"]
        nodes_o = max(bvh_o["aligned_nodes"] + bvh_o["oriented_nodes"], 1)
        out.append(row("oriented over aligned BVH, memory", "Embree %s, measured here (BVH + segment data)"
                       % emb["version"], scene, m, None, point(emb["memory_ratio"]),
                       "Embree's aligned BVH over user primitives has a leaf per segment and %.1fx the oriented "
                       "BVH's nodes; the hair BVHs alone: %.2fx" % (nodes_a / nodes_o, emb["hair_bvh_bytes_ratio"])))
        out.append(row("oriented over aligned BVH, memory", wald, scene, m, None, about(1.5),
                       "the model: +24 B per oriented child (memory-optix7), Embree's node layout"))
    stamp = "`configs/runs/embree_hair.json` (%s) at commit %s and `bench --embree-hair` at commit %s" % (
        _first_preset(next(iter(runs.values()))), _commit(list(runs.values())), bench.get("git_commit", "unknown"))
    return out, stamp, {"checked-embree": embree_tables(bench, runs) + "\n\nMade by `scripts/make_beyond.py checked` "
                        "from " + stamp + ".\n"}


def embree_tables(bench, runs):
    """What bench --embree-hair measured per scene (Embree's statistics, builds, memory, rates) and, beside it,
    what the simulator counted and predicts on the same rays."""
    lines = ["| scene | segments, rays | Embree BVH | nodes aligned + oriented, leaves | Embree SAH | hair BVH "
             "| Embree holds (+ capsules) | build, %d threads | Mrays/s, %d threads | oriented / aligned |" % (
                 bench["scenes"][0]["embree"]["build_threads"], max(x["threads"] for x in
                                                                    bench["scenes"][0]["embree"]["rates"])),
             "|---|---|---|---|---|---|---|---|---|---|"]
    for e in bench["scenes"]:
        em = e["embree"]
        rate = max(em["rates"], key=lambda x: x["threads"])
        for side in ("aligned", "oriented"):
            sd, v = em[side], em[side]["bvh"]
            first = side == "aligned"
            mem = "%.1f MB" % (sd["embree_bytes"] / 1e6)
            if first:
                mem += " (+ %.1f)" % ((sd["memory_bytes"] - sd["embree_bytes"]) / 1e6)
            ratio = "" if first else "speed %.2fx [%.2f-%.2f], build %.2fx, memory %.2fx" % (
                tuple(rate["speedup"]) + (em["build_ratio"][0], em["memory_ratio"]))
            lines.append("| %s | %s | %s `%s` | %s + %s, %s | %.1f | %.2f MB | %s | %.2f s | %.3g [%.3g-%.3g] | %s |" % (
                e["scene"] if first else "", "{:,}, {:,}".format(e["segments"], em["rays"]) if first else "",
                side, sd["device_config"].split(",")[-1], format(v["aligned_nodes"], ","),
                format(v["oriented_nodes"], ","), format(v["leaves"], ","), v["sah"], v["bytes"] / 1e6, mem,
                sd["build_seconds"], *rate[side + "_mrays"], ratio))
    lines += ["", "| scene | ref: aligned box tests, programs per ray | Embree aligned: callbacks per ray "
              "| obb-nodes: aligned + oriented box tests, programs per ray | model speedup | model memory |",
              "|---|---|---|---|---|---|"]
    for e in bench["scenes"]:
        r = runs.get(e["scene"])
        if r is None:
            continue
        ref, on = e["rtcsim"]["ref"], e["rtcsim"]["obb-nodes"]
        p = _first_preset(r)
        s, iv = _speedup(r, "obb-nodes", p)
        mem_o, mem_r = _memory(r, "obb-nodes"), _memory(r, "ref")
        lines.append("| %s | %.1f, %.2f | %.2f | %.1f + %.2f, %.2f | %.2fx [%.2f-%.2f] (%s) | %.2fx (%.1f / %.1f MiB) |" % (
            e["scene"], ref["blas_box_tests"], ref["is_calls"], e["embree"]["aligned"]["capsule_tests_per_ray"],
            on["blas_box_tests"], on["obb_box_tests"], on["is_calls"], s, iv[0], iv[1], p, mem_o / mem_r,
            mem_o / 2 ** 20, mem_r / 2 ** 20))
    return "\n".join(lines)


# --- oriented boxes over triangles (configs/runs/obb_triangles.json) ----------

KERN = "Kern et al. 2025 (DOBB-BVH, RDNA-class GPU, game scenes)"


def _triangle_runs(directory):
    """{(scene, bounces): report.json} of the obb_triangles sweep."""
    out = {}
    for path in sorted(glob.glob(os.path.join(directory, "*", "report.json"))):
        with open(path) as f:
            r = json.load(f)
        out[(r["config"]["scene"]["name"], r["config"]["workload"]["bounces"])] = r
    if not out:
        raise SystemExit("%s: no sweep point's report.json (run build/simulate on obb_triangles.json first)"
                         % directory)
    return out


def _total(r, method, preset):
    return r["methods"][method]["cycles"][preset]["total"]


def secondary_speedup(primary, paths, method, preset):
    """The bounces' own speedup: the two runs share their primary rays, so the cycles of the bounces alone are
    the difference (no band: the draws of the two runs are not paired in report.json)."""
    ref = _total(paths, "ref", preset) - _total(primary, "ref", preset)
    other = _total(paths, method, preset) - _total(primary, method, preset)
    return ref / other if other > 0 else None


def obb_triangles_rows(run_dir):
    """Kern et al.'s average gains of oriented boxes over the triangle BVH (primary, secondary rays) beside
    obb-quantized over ref on the procedural triangle scenes, under rdna4 (GPURT's pass, what RDNA4 runs)
    and hypothetical-obb."""
    runs = _triangle_runs(run_dir)
    note = {"rdna4": "RDNA4 priced by its own issue rates (AMD columns: a sensitivity study); beyond.md, "
                     "'oriented boxes over triangles'",
            "hypothetical-obb": "a rotation priced as an instance transform plus a box test"}
    out, scenes = [], sorted({s for s, _ in runs})
    for preset in ("rdna4", "hypothetical-obb"):
        for scene in scenes:
            primary, paths = runs.get((scene, 0)), runs.get((scene, 2))
            if primary and "obb-quantized" in primary["speedup_over_ref"]:
                s, iv = _speedup(primary, "obb-quantized", preset)
                out.append(row("oriented boxes over triangles, primary rays (%s)" % preset, KERN, scene, s, iv,
                               point(1.185, "1.185x (average)"), note[preset]))
            if primary and paths:
                s = secondary_speedup(primary, paths, "obb-quantized", preset)
                if s:
                    out.append(row("oriented boxes over triangles, secondary rays (%s)" % preset, KERN, scene, s,
                                   None, point(1.324, "1.324x (average)"),
                                   "derived: the bounces' cycles (paths less primary), no band"))
    first = next(iter(runs.values()))
    return out, "`configs/runs/obb_triangles.json` (%s) at commit %s" % (
        ", ".join(first["cost_presets"] if isinstance(first["cost_presets"][0], str)
                  else [p["name"] for p in first["cost_presets"]]), _commit(list(runs.values()))), {}


CHECKS = {
    "lss-dots": (lss_dots_rows, "RUN_DIR,BAND_DIR"),
    "embree": (embree_rows, "BENCH_JSON,RUN_DIR"),
    "obb-triangles": (obb_triangles_rows, "RUN_DIR"),
}

COLUMNS = ["figure", "source", "scene", "model (band)", "measured", "model / measured", "verdict", "note"]


def _fmt_model(r):
    text = "%#.3gx" % r["model"]
    if r["band"]:
        text += " [%#.3g-%#.3g]" % r["band"]
    return text


def _verdict(r):
    """model / measured (against the figure's central value; for a range without one, 1 inside it, else
    against its nearer end) and whether the band (the prediction alone without one) meets the figure's range."""
    lo, hi, _, central = r["measured"]
    m = r["model"]
    if central is not None:
        ratio = m / central
    else:
        ratio = 1.0 if lo <= m <= hi else m / (lo if m < lo else hi)
    blo, bhi = r["band"] or (m, m)
    meets = blo <= hi and bhi >= lo
    return ratio, "agrees" if meets else "miss"


def table(rows):
    lines = ["| " + " | ".join(COLUMNS) + " |", "|" + "---|" * len(COLUMNS)]
    for r in rows:
        ratio, verdict = _verdict(r)
        lines.append("| %s | %s | %s | %s | %s | %.2f | %s | %s |" % (
            r["figure"], r["source"], r["scene"], _fmt_model(r), r["measured"][2], ratio, verdict,
            r["note"]))
    return "\n".join(lines)


def block(args):
    """The blocks' texts from `NAME=PATH[,PATH...]` arguments, one per check: "checked" (the table) and the
    checks' own blocks (their measurements in detail)."""
    rows, stamps, blocks = [], [], {}
    for a in args:
        name, _, paths = a.partition("=")
        if name not in CHECKS or not paths:
            raise SystemExit("checked: expected NAME=PATH[,PATH...] with NAME one of %s (%s), got %r" % (
                ", ".join(CHECKS), "; ".join("%s=%s" % (k, v[1]) for k, v in CHECKS.items()), a))
        fn = CHECKS[name][0]
        got, stamp, extra = fn(*paths.split(","))
        rows += got
        stamps.append(stamp)
        blocks.update(extra)
    legend = ("model / measured: the prediction over the figure (over a local measurement's median; for a "
              "published range, 1.00 within it, else against its nearer end). agrees: the model's band (the "
              "prediction itself where it has none) meets the figure's range ('about X' read as X +-%d %%, a "
              "local measurement as the median of its alternated pairs, their range in brackets). Made by "
              "`scripts/make_beyond.py checked` from %s." % (round(100 * ABOUT), "; ".join(stamps)))
    blocks["checked"] = table(rows) + "\n\n" + legend + "\n"
    return blocks
