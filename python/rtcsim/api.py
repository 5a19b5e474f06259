"""The functions of the package: run a config (a file or a dict, with the
CLI's schema and errors), sweep it, re-price counts without tracing, load
cost presets and scenes, calibrate, and run the `simulate` CLI itself.
"""
import json
import os
from collections.abc import Mapping

import numpy as np

from . import _rtcsim
from .presets import load_cost_model
from .results import MethodResult, Result


def _json_default(value):
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    raise TypeError(f"{type(value).__name__} is not JSON serializable")


def _sets(sets):
    """--set overrides: a list of "key.path=value" strings or a {key.path: value} dict."""
    if sets is None:
        return []
    if isinstance(sets, Mapping):
        return [f"{k}={json.dumps(v, default=_json_default)}" for k, v in sets.items()]
    if isinstance(sets, str):
        return [sets]
    return [str(s) for s in sets]


def plan(config, sets=None, base=None, limits=None):
    """The runs of a config, planned as the CLI plans them (overrides, sweep,
    strict parsing, work estimate). `config` is a path or a dict; for a dict,
    `base` names it in messages and relative paths resolve beside it
    (default: "<dict>", paths relative to the current directory). `limits`:
    {"max_rays", "max_memory" (bytes), "max_sweep_points", "max_break_even",
    "force"}, the CLI's --max-rays, --max-memory, --max-break-even and --force
    (same defaults)."""
    if limits is not None and not isinstance(limits, Mapping):
        raise TypeError(f"limits: expected a dict such as {{\"max_rays\": 1e11}}, got {type(limits).__name__}")
    limits = dict(limits or {})
    if isinstance(config, (str, os.PathLike)):
        return _rtcsim.Plan.from_file(os.fspath(config), _sets(sets), limits)
    if isinstance(config, Mapping):
        text = json.dumps(config, default=_json_default)
        return _rtcsim.Plan.from_json(text, os.fspath(base) if base else "<dict>", _sets(sets), limits)
    raise TypeError(f"config: expected a path or a dict, got {type(config).__name__}")


def _threads(threads):
    if threads is None:
        return 0
    if not 0 <= int(threads) <= 1024:  # the CLI's --threads range
        raise ValueError(f"threads: expected 0 (all cores) or a positive integer up to 1024, got {threads}")
    return int(threads)


def run(config, threads=None, progress=True, *, sets=None, base=None, out=None, record_warps=False,
        limits=None):
    """Traces one run and returns a Result.

    config: a config file or a dict (the schema of configs/README.md); a
        config with a sweep of several points needs rtcsim.sweep().
    threads: cores to trace on (None: all). Results do not depend on it.
    progress: progress bars on stderr.
    sets: overrides as the CLI's --set ("key.path=value" strings or a dict).
    out: a directory to write what the CLI writes (report.json, images, and
        rays/hits files when the config asks for them), under the CLI's rules:
        missing or empty (limits={"force": True}: or one simulate wrote,
        emptied first), locked while the run writes, marked complete last.
    record_warps: keep every wave, so warp presets can re-price it (price()).
    limits: the CLI's work ceilings, e.g. {"max_rays": 1e11} or {"force": True}.
    Rays and hits are kept (result.method(m).rays / .hits) when the config's
    output block asks for them. Raises rtcsim.InputError on bad input.
    """
    p = plan(config, sets, base, limits)
    if len(p) != 1:
        raise ValueError(f"{p.file}: /sweep: {len(p)} sweep points; rtcsim.sweep() runs them all")
    return _run_point(p, 0, threads, progress, out, record_warps)


def _run_point(p, index, threads, progress, out, record_warps):
    handle = p.run(index, threads=_threads(threads), progress=bool(progress), record_warps=record_warps,
                   keep_rays=True, out_dir=os.fspath(out) if out else "")
    return Result(handle)


def sweep(config, threads=None, progress=True, *, sets=None, base=None, record_warps=False, keep_pixels=False,
          limits=None):
    """Runs every point of a config's sweep (one point without a sweep) and
    returns a list of Results in the CLI's order. Like the CLI, finished
    points keep their totals but drop their per-pixel data unless
    keep_pixels is set."""
    p = plan(config, sets, base, limits)
    results = []
    for i in range(len(p)):
        if progress and len(p) > 1:
            import sys
            print(f"[{i + 1}/{len(p)}] {p.label(i)}", file=sys.stderr)
        handle = p.run(i, threads=_threads(threads), progress=bool(progress), record_warps=record_warps,
                       keep_rays=keep_pixels)
        if not keep_pixels:
            handle._free_pixels()  # before any array views them
        results.append(Result(handle))
    return results


def simulate(*args):
    """Runs the `simulate` program (`simulate(["cfg.json", "--out", "d"])` or
    `simulate("cfg.json", "--quiet")`) and returns its exit code."""
    if len(args) == 1 and not isinstance(args[0], (str, os.PathLike)):
        args = tuple(args[0])
    return _rtcsim.simulate_main([os.fspath(a) if isinstance(a, os.PathLike) else str(a) for a in args])


def _check_counts(counts, what):
    """Counts are whole numbers >= 0: a negative or NaN one cast to uint64
    priced as about 1e22 cycles (issue 56)."""
    if counts.dtype == object or not (np.issubdtype(counts.dtype, np.number) or counts.dtype == bool):
        raise TypeError(f"{what}: expected numbers, got {counts.dtype}")
    if np.issubdtype(counts.dtype, np.complexfloating):
        raise TypeError(f"{what}: expected real counts, got {counts.dtype}")
    if np.issubdtype(counts.dtype, np.floating):
        bad = ~np.isfinite(counts) | (counts < 0) | (counts != np.floor(counts))
        if np.any(bad):
            raise ValueError(f"{what}: expected whole numbers >= 0, got {counts[bad].flat[0]!r}")
    elif np.issubdtype(counts.dtype, np.signedinteger) and np.any(counts < 0):
        raise ValueError(f"{what}: expected counts >= 0, got {counts[counts < 0].flat[0]!r}")


def price(counts, preset):
    """Cycles of counts under a preset, without tracing.

    counts: a MethodResult (its totals; under a warp preset its recorded
        waves; a sampled run's scaled to the whole frame, as report.json's
        totals are), a {event: count} dict, event totals (EVENT_NAMES order), or
        per-pixel counts (..., events), which give cycles per pixel.
    preset: a CostModel, a preset file or a preset name.
    Returns a PricedRun, or an array of cycles for per-pixel counts.
    """
    model = load_cost_model(preset)
    if isinstance(counts, (MethodResult, _rtcsim.MethodRun)):
        return counts.price(model)
    if isinstance(counts, Mapping):
        from .results import event_index
        totals = np.zeros(len(_rtcsim.EVENT_NAMES), dtype=np.uint64)
        for event, n in counts.items():
            _check_counts(np.asarray(n), f"counts[{event!r}]")
            totals[event_index(event)] = n
        counts = totals
    counts = np.asarray(counts)
    _check_counts(counts, "counts")
    if model.is_warp:
        raise ValueError(f"{model.name} is a warp preset: it prices recorded waves, not counts; "
                         "pass a method of a run traced with record_warps=True")
    if counts.shape[-1:] != (len(_rtcsim.EVENT_NAMES),):
        raise ValueError(f"counts: expected a last axis of {len(_rtcsim.EVENT_NAMES)} events, got {counts.shape}")
    if counts.ndim == 1:
        return _rtcsim.price_totals(counts.astype(np.uint64, copy=False), model)
    return _rtcsim.price_pixels(counts, model)  # the CLI's per-pixel cycles


def load_scene(scene, base=None):
    """A scene as a run loads it: `scene` is a scene block (dict), a config
    (dict with a "scene" block) or a config file. Strands, radii and mesh
    are NumPy views; scene.primitives(kind) gives the primitives."""
    file = os.fspath(base) if base else "<dict>"
    if isinstance(scene, (str, os.PathLike)):
        file = os.fspath(scene)
        # Read as the CLI reads a config: its errors name the file and line.
        return _rtcsim.load_scene_file(file)
    if not isinstance(scene, Mapping):
        raise TypeError(f"scene: expected a scene block, a config or a config file, got {type(scene).__name__}")
    block = scene["scene"] if "scene" in scene else scene
    if not isinstance(block, Mapping):
        raise TypeError(f"{file}: /scene: expected a scene block (dict), got {type(block).__name__}")
    return _rtcsim.load_scene(json.dumps(block, default=_json_default), file, "/scene")


def calibrate(results, block=None, *, base=None):
    """Fits cost presets to target speedups on traced runs, as `simulate
    calibrate` does, by re-pricing their counts (warp presets: their recorded
    waves, so trace with record_warps=True). `block` is a `calibrate` block
    (dict); default: the one in the runs' config. Returns a Calibration with
    .model (a CostModel), .runs, .parameters, .report_markdown(), .preset_json().
    """
    if isinstance(results, Result):
        results = [results]
    results = list(results)
    if not results:
        raise ValueError("calibrate: no runs")
    if block is None:
        block = results[0].config.get("calibrate")
        if block is None:
            raise ValueError(f"{results[0].file}: /calibrate: missing (pass a calibrate block)")
    file = os.fspath(base) if base else results[0].file
    text = json.dumps({"calibrate": block}, default=_json_default)
    return _rtcsim.calibrate([r._run for r in results], text, file)


def summary_table(results, format="console", table="summary"):
    """The CLI's tables over results: "summary" (the terminal table,
    summary.csv/.md) or "speedups" (every method under every preset,
    speedups.csv/.md); format "console", "csv" or "markdown"."""
    if isinstance(results, Result):
        results = [results]
    return _rtcsim.summary_table([r._run for r in results], format, table)
