"""Live results: a traced run kept in C++, seen from Python as a `Report`
(the same report_json the CLI writes) plus NumPy views of its per-pixel
data, rays and hits. Arrays view the C++ memory (no copy) and keep the run
alive; they are read-only.
"""
import json
import os

import numpy as np

from . import _rtcsim
from .presets import load_cost_model
from .report import Report

EVENT_INDEX = {name: i for i, name in enumerate(_rtcsim.EVENT_NAMES)}


def event_index(event):
    """The position of an event (name or index) in every per-event array."""
    if isinstance(event, (int, np.integer)):
        return int(event)
    try:
        return EVENT_INDEX[event]
    except KeyError:
        raise KeyError(f"unknown event {event!r} (see rtcsim.EVENT_NAMES)") from None


class MethodResult:
    """One method of a run. Every attribute of the C++ MethodRun is
    available (totals, pixel_counts, radiance, rays, hits, priced, memory,
    structures, pixel_warp_cycles, ...), plus the helpers below."""

    def __init__(self, method, result):
        self._m = method
        self._result = result

    def __getattr__(self, name):
        return getattr(self._m, name)

    def __dir__(self):
        return sorted(set(dir(type(self))) | set(dir(self._m)))

    @property
    def events(self):
        """{event name: total}."""
        return dict(zip(_rtcsim.EVENT_NAMES, (int(x) for x in self._m.totals)))

    def pixel_events(self, event):
        """(H, W) counts of one event per pixel (a view)."""
        return self._m.pixel_counts[..., event_index(event)]

    def price(self, preset):
        """Re-prices this method's counts under a preset (name, path or
        CostModel) without tracing; warp presets re-price the recorded waves.
        A sampled run's are scaled to the whole frame, as the CLI's totals."""
        return self._m.price(load_cost_model(preset))

    def priced_by_preset(self):
        """{preset name: PricedRun} of the run's presets."""
        return {c.name: p for c, p in zip(self._result.costs, self._m.priced)}

    def __repr__(self):
        return f"<MethodResult {self.name}: {self.rays_traced} rays>"


class Result(Report):
    """One traced run: report.json's content (see Report) and its arrays."""

    def __init__(self, run):
        self._run = run
        super().__init__(json.loads(run.report_json()))
        self.costs = run.costs  # CostModel per preset, primary first
        self._methods = {n: MethodResult(run.method(n), self) for n in run.method_names}

    @property
    def effective_config(self):
        return self.config

    @property
    def file(self):
        """The config file this run came from (or the name given to a dict)."""
        return self._run.file

    @property
    def methods(self):
        """{name: MethodResult}, in config order."""
        return dict(self._methods)

    def method(self, name):
        try:
            return self._methods[name]
        except KeyError:
            raise KeyError(f"no method {name!r} in this run (has {', '.join(self._methods)})") from None

    def __getitem__(self, name):
        return self.method(name)

    @property
    def shape(self):
        """(H, W) of the per-pixel arrays ((0, 0) for ray-file workloads)."""
        for m in self._methods.values():
            if m.runnable and m.width > 0:
                return (m.height, m.width)
        return (0, 0)

    def preset_index(self, preset=None):
        if preset is None:
            return 0
        if isinstance(preset, (int, np.integer)):
            return int(preset)
        return self.cost_presets.index(self._preset(preset))

    def pixel_cycles(self, method, preset=None):
        """(H, W) cycles per pixel of a method under one of the run's presets:
        counts x costs (per-ray model), or under a warp preset each pixel's
        share of its waves (what the CLI's heat maps show)."""
        m = self.method(method)
        p = self.preset_index(preset)
        cost = self.costs[p]
        if cost.is_warp:
            return m.pixel_warp_cycles_of(cost.name)
        return _rtcsim.price_pixels(m.pixel_counts, cost)  # as the CLI's heat maps and cycles_*.npy

    def pixel_events(self, method, event):
        return self.method(method).pixel_events(event)

    def radiance(self, method=None):
        """(H, W, 3) linear radiance (every method renders the same image)."""
        name = method or next(n for n, m in self._methods.items() if m.runnable)
        return self.method(name).radiance

    def write_outputs(self, directory, force=False):
        """report.json and the images, exactly as the CLI writes them and under
        its rules: `directory` missing or empty (force=True: or one simulate
        wrote, emptied first), locked while written, marked complete last."""
        self._run.write_outputs(os.fspath(directory), force)

    def __repr__(self):
        s = self.speedup() if self.others else None
        extra = f", speedup {s:.3f}x" if s else ""
        return f"<Result {self.label!r}: {', '.join(self._methods)}{extra}>"
