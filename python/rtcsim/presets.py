"""Cost presets from Python: a CostModel, a preset file or a preset name,
found as the CLI finds them. Its own module so that api.py (runs, sweeps,
pricing) and results.py (a method's counts re-priced) both use it without
importing each other.
"""
import os

from . import _rtcsim

PRESET_DIR = os.path.join(os.path.dirname(__file__), "configs", "hw")


def load_cost_model(preset):
    """A cost preset: a CostModel (returned as is), a preset file, or a
    preset name from configs/hw ("turing-per-ray-guess", "turing-calibrated", ...)."""
    if isinstance(preset, _rtcsim.CostModel):
        return preset
    path = os.fspath(preset)
    if not os.path.exists(path):
        for candidate in (os.path.join(PRESET_DIR, path), os.path.join(PRESET_DIR, path + ".json")):
            if os.path.isfile(candidate):
                path = candidate
                break
    return _rtcsim.CostModel.load(path)
