"""Re-pricing without tracing equals tracing again under the other preset:
per-ray presets from the counts, warp presets from the recorded waves, and
costs edited in Python."""
import json

import numpy as np
import pytest

import rtcsim
from conftest import TINY

SMALL = {"workload.width": 24, "workload.height": 24, "output.images": False}


def run_with(presets, record_warps=False):
    sets = dict(SMALL, cost=[str(p) for p in presets])
    return rtcsim.run(TINY, threads=2, progress=False, sets=sets, record_warps=record_warps)


def warp_preset(path, lanes, context_switch):
    with open(f"{rtcsim.PRESET_DIR}/turing-per-ray-guess.json") as f:
        j = json.load(f)
    j["name"] = path.stem
    j["execution"] = {"model": {"value": "warp", "source": "test"},
                      "warp_width": {"value": 32, "source": "test"},
                      "tile": {"value": [8, 4], "source": "test"},
                      "rt_parallel_lanes": {"value": lanes, "source": "test"}}
    j["cycles"]["context_switch"]["value"] = context_switch
    path.write_text(json.dumps(j))
    return path


def test_reprice_equals_rerun_per_ray():
    other = "turing-per-ray-calibrated"
    guess = run_with([f"{rtcsim.PRESET_DIR}/turing-per-ray-guess.json"])
    calibrated = run_with([f"{rtcsim.PRESET_DIR}/{other}.json"])
    for name in ("ref", "obb"):
        again = rtcsim.price(guess[name], other)
        live = calibrated[name].priced[0]
        assert again.total_cycles == live.total_cycles
        assert np.array_equal(again.by_event, live.by_event)
        # The same from the totals alone, from a dict, and per pixel.
        assert rtcsim.price(guess[name].totals, other).total_cycles == live.total_cycles
        assert rtcsim.price(guess[name].events, other).total_cycles == live.total_cycles
        per_pixel = rtcsim.price(guess[name].pixel_counts, other)
        assert per_pixel.shape == (24, 24)
        assert per_pixel.sum() == pytest.approx(live.total_cycles, rel=1e-12)
    assert guess.speedup("obb") != calibrated.speedup("obb")


def test_edited_costs_equal_a_preset_file(tmp_path):
    base = run_with([f"{rtcsim.PRESET_DIR}/turing-per-ray-guess.json"])
    model = rtcsim.load_cost_model("turing-per-ray-guess")
    cycles = model.cycles
    cycles[rtcsim.EVENT_INDEX["context_switch"]] = 777.0
    model.cycles = cycles
    model.name = "edited"
    path = tmp_path / "edited.json"
    path.write_text(model.to_json())
    rerun = run_with([path])
    for name in ("ref", "obb"):
        assert rtcsim.price(base[name], model).total_cycles == rerun[name].priced[0].total_cycles
    with pytest.raises(ValueError, match="finite"):
        model.cycles = np.full(len(rtcsim.EVENT_NAMES), -1.0)


def test_edited_costs_keep_the_sums_of_costs():
    """turing-calibrated's obb_box_test is blas_box_test + instance_transform
    (sum_of): editing a term moves the sum, as a break-even axis does, and a
    sum given its own value keeps it."""
    model = rtcsim.load_cost_model("turing-calibrated")
    i = rtcsim.EVENT_INDEX
    cycles = model.cycles
    cycles[i["instance_transform"]] = 40.0
    model.cycles = cycles
    assert model.cycles[i["obb_box_test"]] == model.cycles[i["blas_box_test"]] + 40.0
    cycles = model.cycles
    cycles[i["obb_box_test"]] = 3.0
    cycles[i["instance_transform"]] = 50.0
    model.cycles = cycles
    assert model.cycles[i["obb_box_test"]] == 3.0


def test_reprice_equals_rerun_warp(tmp_path):
    a = warp_preset(tmp_path / "warp-a.json", lanes=32, context_switch=200)
    b = warp_preset(tmp_path / "warp-b.json", lanes=4, context_switch=600)
    traced = run_with([a], record_warps=True)
    rerun = run_with([b])
    for name in ("ref", "obb"):
        m = traced[name]
        assert m.recorded_waves > 0
        live = m.priced[0]
        assert live.execution == "warp" and live.warp["waves"] > 0
        assert m.price(rtcsim.load_cost_model(a)).total_cycles == pytest.approx(live.total_cycles, rel=1e-12)
        again = rtcsim.price(m, b)
        want = rerun[name].priced[0]
        assert again.total_cycles == pytest.approx(want.total_cycles, rel=1e-12)
        assert again.warp["rounds"] == want.warp["rounds"]
        # Per-pixel warp cycles (the first warp preset) add up to the frame's.
        assert traced.pixel_cycles(name).sum() == pytest.approx(live.total_cycles, rel=1e-5)
        assert m.pixel_simt_slots.shape == (24, 24)
    assert traced.speedup("obb") == pytest.approx(traced.cycles("ref") / traced.cycles("obb"))


def test_warp_pricing_needs_the_waves(tmp_path):
    a = warp_preset(tmp_path / "warp-a.json", lanes=32, context_switch=200)
    per_ray = run_with([f"{rtcsim.PRESET_DIR}/turing-per-ray-guess.json"])
    with pytest.raises(ValueError, match="record_warps"):
        rtcsim.price(per_ray["obb"], a)
    with pytest.raises(ValueError, match="warp preset"):
        rtcsim.price(per_ray["obb"].totals, a)
    traced = run_with([a], record_warps=True)
    j = json.loads(rtcsim.load_cost_model(a).to_json())
    j["execution"]["warp_width"]["value"] = 16
    j["execution"]["tile"]["value"] = [4, 4]
    j["execution"]["rt_parallel_lanes"]["value"] = 16
    other = rtcsim.CostModel.from_json(json.dumps(j))
    with pytest.raises(ValueError, match="other warps"):
        rtcsim.price(traced["obb"], other)


def test_cost_model_round_trip():
    m = rtcsim.load_cost_model("turing-per-ray-guess")
    assert m.name == "turing-per-ray-guess" and not m.is_warp
    assert m.execution["model"] == "per_ray"
    assert len(m.cycles) == len(m.sources) == len(rtcsim.EVENT_NAMES)
    again = rtcsim.CostModel.from_json(m.to_json())
    assert np.array_equal(again.cycles, m.cycles) and again.sources == m.sources
    with pytest.raises(rtcsim.InputError, match=r"^x.json: /cycles/ray: missing"):
        j = json.loads(m.to_json())
        del j["cycles"]["ray"]
        rtcsim.CostModel.from_json(json.dumps(j), "x.json")


def test_package_modules_import_in_one_direction():
    """No two of rtcsim's modules import each other, directly or through
    others (api -> results -> report; both use presets), so each loads and
    reads on its own."""
    import ast
    import pathlib

    import rtcsim
    package = pathlib.Path(rtcsim.__file__).parent
    names = {f.stem for f in package.glob("*.py")}
    graph = {}
    for f in package.glob("*.py"):
        deps = set()
        for node in ast.walk(ast.parse(f.read_text())):
            if isinstance(node, ast.ImportFrom) and node.level == 1:
                deps.update([node.module.split(".")[0]] if node.module else [a.name for a in node.names])
        graph[f.stem] = deps & names - {"__init__"}
    assert {"api", "results", "presets"} <= names
    state = {}

    def visit(module, path):
        if state.get(module) == "done":
            return
        assert state.get(module) != "open", "import cycle: " + " -> ".join(path + [module])
        state[module] = "open"
        for dep in sorted(graph[module]):
            visit(dep, path + [module])
        state[module] = "done"

    for module in sorted(graph):
        visit(module, [])
