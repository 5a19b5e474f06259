"""Finished runs as Python objects: a `Report` reads report.json (what the
CLI writes for every run and sweep point) and answers the questions the
tables and figures ask: speedups per preset, events and cycles per ray,
surface-area ratio, memory. A live `rtcsim.Result` is a Report too, built
from the same report_json, plus the per-pixel NumPy arrays.
"""
import glob
import json
import os


class Report:
    """One run's report.json, read-only. `data` is the parsed JSON."""

    def __init__(self, data, path=None):
        self.data = data
        self.path = path

    # -- identity -------------------------------------------------------------
    @property
    def name(self):
        return self.data["name"]

    @property
    def sweep_point(self):
        """{sweep key: value} of this point ({} for a run without a sweep)."""
        return self.data.get("sweep_point", {})

    @property
    def label(self):
        """The sweep point's label (as in the summary table), else the run's name."""
        if "sweep_label" in self.data:
            return self.data["sweep_label"]
        if self.sweep_point:
            return " ".join(f"{k}={v if isinstance(v, str) else json.dumps(v)}"
                            for k, v in self.sweep_point.items())
        return self.name

    @property
    def config(self):
        """The effective configuration of this run (overrides and sweep applied)."""
        return self.data["config"]

    @property
    def baseline(self):
        return self.config.get("baseline", "ref")

    @property
    def method_names(self):
        return list(self.data["methods"])

    @property
    def others(self):
        """The methods compared against the baseline."""
        return [m for m in self.method_names if m != self.baseline]

    @property
    def cost_presets(self):
        return list(self.data["cost_presets"])

    @property
    def kind(self):
        return self.data["scene"]["primitive_kind"]

    @property
    def primitives(self):
        return self.data["scene"]["primitives"]

    # -- per method -----------------------------------------------------------
    def _method(self, method):
        try:
            return self.data["methods"][method]
        except KeyError:
            raise KeyError(f"no method {method!r} in run {self.label!r} "
                           f"(has {', '.join(self.method_names)})") from None

    def _preset(self, preset):
        presets = self.cost_presets
        if preset is None:
            return presets[0]
        if isinstance(preset, int):
            return presets[preset]
        name = getattr(preset, "name", preset)
        if name not in presets:
            raise KeyError(f"no cost preset {name!r} in run {self.label!r} (has {', '.join(presets)})")
        return name

    def runnable(self, method):
        return bool(self._method(method).get("runnable"))

    def rays(self, method):
        return self._method(method).get("rays", 0)

    def events(self, method):
        """{event name: total} of a method (empty when it did not run)."""
        m = self._method(method)
        return {k: v["total"] for k, v in m.get("events", {}).items()}

    def per_ray(self, method, event):
        """Events per ray, or None when the method did not run."""
        m = self._method(method)
        return m["events"][event]["per_ray"] if m.get("runnable") else None

    def is_per_ray(self, method):
        """Intersection-program calls per ray."""
        return self.per_ray(method, "is_call")

    def cycles(self, method, preset=None):
        """Total cycles of a method under a preset (its execution model), None if n/a."""
        m = self._method(method)
        entry = m.get("cycles", {}).get(self._preset(preset)) if m.get("runnable") else None
        return entry.get("total") if entry else None

    def cycles_per_ray(self, method, preset=None):
        m = self._method(method)
        entry = m.get("cycles", {}).get(self._preset(preset)) if m.get("runnable") else None
        return entry.get("per_ray") if entry else None

    def cycle_breakdown(self, method, preset=None):
        """{event: cycles} of the per-ray model (events that cost anything).
        Under a warp preset these are the per-ray model's figures of the same
        costs, not cycles(): warp_breakdown has the warp model's, by unit."""
        m = self._method(method)
        entry = m.get("cycles", {}).get(self._preset(preset)) if m.get("runnable") else None
        return dict(entry.get("breakdown", {})) if entry else {}

    def warp_breakdown(self, method, preset=None):
        """{unit: cycles} of the warp model (shader, rt_unit, hand_off,
        programs), which add up to cycles(method, preset); None under a
        per-ray preset (cycle_breakdown is then the run's own)."""
        m = self._method(method)
        entry = m.get("cycles", {}).get(self._preset(preset)) if m.get("runnable") else None
        warp = (entry or {}).get("warp")
        return dict(warp["breakdown"]) if warp else None

    def memory_total(self, method):
        m = self._method(method)
        return m["memory_bytes"]["total"] if m.get("runnable") else None

    def memory_overhead(self, method=None):
        """Total memory of `method` over the baseline's, in percent (None: n/a)."""
        method = method or self.others[0]
        return (self.data.get("memory_overhead_percent") or {}).get(method)

    # -- comparisons ----------------------------------------------------------
    def speedup(self, method=None, preset=None):
        """cycles(baseline) / cycles(method) under a preset (name, index or
        CostModel; default the primary), or None when not available."""
        method = method or self.others[0]
        table = self.data.get(f"speedup_over_{self.baseline}") or {}
        return (table.get(method) or {}).get(self._preset(preset))

    def speedup_interval(self, method=None, preset=None):
        """The 90 % interval (low, high) of speedup(method, preset) over draws
        of the preset's fitted costs (calibration uncertainty only), or None
        when the preset has no covariance: `uncertainty_note(preset)` says why."""
        method = method or self.others[0]
        table = self.data.get(f"speedup_interval_over_{self.baseline}") or {}
        pair = (table.get(method) or {}).get(self._preset(preset))
        return tuple(pair) if pair else None

    def sampling_interval(self, method=None, preset=None):
        """A sampled run's 95 % sampling interval (low, high) of speedup(method,
        preset) (docs/sampling.md), or None when every tile was traced;
        `data["sampling"]` says the fraction and seed."""
        method = method or self.others[0]
        table = self.data.get(f"speedup_sampling_interval_over_{self.baseline}") or {}
        pair = (table.get(method) or {}).get(self._preset(preset))
        return tuple(pair) if pair else None

    def uncertainty_note(self, preset=None):
        """What the preset's intervals are, or why it has none."""
        return (self.data.get("uncertainty") or {}).get(self._preset(preset))

    def area_ratio(self, tight=False):
        """Sum of primitive AABB areas over sum of OBB areas (paper or tight OBBs)."""
        a = self.data["scene"]["surface_area"]
        return a["aabb_over_obb_tight" if tight else "aabb_over_obb_paper"]

    def __repr__(self):
        return f"<Report {self.label!r}: {', '.join(self.method_names)}>"


_MARK = ".rtcsim-output"


def require_finished(directory):
    """Raises InputError when `directory` (or, for a sweep point, the sweep's
    directory above it) is a simulate output directory whose run did not
    finish: its mark, .rtcsim-output, does not say `state: complete` (the run
    failed, was killed, or is still running). A report outside one (a copy)
    is not checked. simulate merge checks the same (sim/app/output_dir.h)."""
    from ._rtcsim import InputError
    directory = os.path.abspath(directory)
    for d in (directory, os.path.dirname(directory)):
        mark = os.path.join(d, _MARK)
        if not os.path.isfile(mark):
            continue
        with open(mark, encoding="utf-8", errors="replace") as f:
            text = f.read()
        if "state: complete\n" in text or (text and "state: " not in text):  # an older simulate's mark: no state
            return
        raise InputError(f"{d}: an unfinished simulate run ({_MARK} does not say complete: it failed, was killed, "
                         "or is still running)")


def _path_argument(value, name, what):
    if not isinstance(value, (str, os.PathLike)):
        raise TypeError(f"{name}: expected {what} (a str or path), got {type(value).__name__}")
    return os.fspath(value)


def _read_json(path):
    from ._rtcsim import InputError
    try:
        with open(path, "rb") as f:
            text = f.read()
    except FileNotFoundError:  # as simulate merge says it (e.g. a run killed before it marked its directory)
        raise InputError(f"{path}: not found") from None
    except OSError as e:
        raise InputError(f"{path}: cannot read ({e.strerror})") from None
    try:
        return json.loads(text)
    except (ValueError, RecursionError) as e:
        where = f"line {e.lineno}: " if hasattr(e, "lineno") else ""
        raise InputError(f"{path}: {where}invalid JSON ({getattr(e, 'msg', e)})") from None


def load_report(path):
    """A report.json file, or the report.json inside a directory. Raises
    rtcsim.InputError for a cut file or an unfinished run's directory."""
    path = _path_argument(path, "path", "a report.json file or a CLI output directory")
    if os.path.isdir(path):
        path = os.path.join(path, "report.json")
    require_finished(os.path.dirname(path) or ".")
    return Report(_read_json(path), path)


def load_reports(directory):
    """Every report of a CLI output directory: its report.json (one run, or a
    sweep's combined report with every point), else the sweep points'
    `<index>_<label>/report.json` in index order."""
    directory = _path_argument(directory, "directory", "a CLI output directory")
    if not os.path.isdir(directory):
        from ._rtcsim import InputError
        raise InputError(f"{directory}: not a directory (load_reports reads a CLI output directory, "
                         "load_report one report.json)")
    require_finished(directory)
    single = os.path.join(directory, "report.json")
    if os.path.isfile(single):
        data = _read_json(single)
        if "points" not in data:
            return [Report(data, single)]
        # A sweep's combined report.json: its points' reports, in sweep order.
        return [Report(p["report"], os.path.join(directory, p["dir"], "report.json")) for p in data["points"]]

    def index(path):
        head = os.path.basename(os.path.dirname(path)).split("_")[0]
        return int(head) if head.isdigit() else 1 << 30

    paths = sorted(glob.glob(os.path.join(directory, "*", "report.json")), key=lambda p: (index(p), p))
    return [load_report(p) for p in paths]
