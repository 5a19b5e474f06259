"""rtcsim: a simulator of GPU ray-tracing hardware with a cost model, from Python.

    import rtcsim
    result = rtcsim.run("configs/runs/quickstart.json", threads=2)
    print(result.speedup("obb"))                       # cycles(ref) / cycles(obb)
    counts = result["obb"].pixel_counts                # (H, W, events) uint32, no copy
    rtcsim.price(result["obb"], "turing-per-ray-guess")        # re-priced without tracing

Configs, presets and errors are the `simulate` CLI's (rtcsim.InputError
carries its one-line "<file>: <JSON path>: <problem>" message). Figures:
rtcsim.plot (matplotlib), also `python3 -m rtcsim.plot report.json --out DIR`.
"""
import sys as _sys

from ._interpreter import BUILT_FOR as _BUILT_FOR, BUILT_VERSION as _BUILT_VERSION

try:
    import numpy as _numpy  # noqa: F401  (the compiled module and the results need it)
    from ._rtcsim import (EVENT_NAMES, EVENT_UNITS, Calibration, CostModel, InputError, PricedRun, Scene,
                          __version__, method_names)
except ImportError as _e:
    # Another interpreter than the build's (another version, or no NumPy):
    # one line naming the one to use, not a traceback from deep inside.
    raise ImportError(
        f"rtcsim was built for {_BUILT_FOR} (Python {_BUILT_VERSION}, with NumPy) and cannot be imported by "
        f"{_sys.executable} (Python {_sys.version_info[0]}.{_sys.version_info[1]}: {_e}); run {_BUILT_FOR} "
        "instead (build/rtcsim-python is that interpreter with build/python on its path)") from None
from .api import calibrate, load_scene, plan, price, run, simulate, summary_table, sweep
from .presets import PRESET_DIR, load_cost_model
from .report import Report, load_report, load_reports
from .results import EVENT_INDEX, MethodResult, Result, event_index

for _cls in (Calibration, CostModel, InputError, PricedRun, Scene):
    _cls.__module__ = __name__  # shown as rtcsim.X in messages and help()

__all__ = [
    "EVENT_NAMES", "EVENT_UNITS", "EVENT_INDEX", "Calibration", "CostModel", "InputError", "PricedRun",
    "Scene", "MethodResult", "Result", "Report", "PRESET_DIR", "__version__", "calibrate", "event_index",
    "load_cost_model", "load_report", "load_reports", "load_scene", "method_names", "plan", "price", "run",
    "simulate", "summary_table", "sweep", "plot",
]


def __getattr__(name):
    # rtcsim.plot imports matplotlib: only when asked for.
    if name == "plot":
        import importlib
        return importlib.import_module(".plot", __name__)
    raise AttributeError(f"module 'rtcsim' has no attribute {name!r}")
