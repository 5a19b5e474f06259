"""scripts/table1_cost_map.py: the grid's prices and the verdict of each cell,
without its traces (the curly stand-ins are millions of primitives). A cell
at hand-off H and scale s prices the hand-off at H and every operation class
at s times the CUDA Guide's price, all else at turing-calibrated; it is bold
only when all four figures are within the issue's tolerances of the paper's."""
import importlib.util
import os
import sys

import pytest

import rtcsim
from conftest import ROOT

sys.path.insert(0, os.path.join(ROOT, "scripts"))
import paper_table1  # noqa: E402


@pytest.fixture(scope="module")
def cost_map():
    spec = importlib.util.spec_from_file_location("table1_cost_map", os.path.join(ROOT, "scripts", "table1_cost_map.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_grid_prices(cost_map):
    base = rtcsim.load_cost_model("turing-calibrated")
    m = cost_map.model_at(150, 0.2)
    i = rtcsim.EVENT_INDEX
    assert m.cycles[i["context_switch"]] == 150
    guide = {"op_fma": 0.5, "op_div": 4, "op_sqrt": 3, "op_branch": 1, "op_load": 16}  # the Guide's prices
    for op, price in guide.items():
        assert m.cycles[i[op]] == pytest.approx(0.2 * price)
    for e in ("ray", "instance_transform", "tlas_node_visit", "blas_box_test"):
        assert m.cycles[i[e]] == base.cycles[i[e]]  # everything else as the Fig. 3 fit
    at_fit = cost_map.model_at(100, 0.05)
    assert list(at_fit.cycles) == pytest.approx(list(base.cycles))  # the shipped preset is the grid's cell (100, 0.05)


def values_for(model, capsule_speedup, link, phantom1, deepest):
    cap_ref = 100.0
    k = f"phantom /{cost_map_deepest(model)}"
    return {"capsule": (cap_ref, cap_ref / capsule_speedup), "link": (link * cap_ref, None),
            "phantom /1": (phantom1 * cap_ref, None), k: (deepest * cap_ref, None)}


def cost_map_deepest(model):
    return {"curly lock": 8, "curly head": 4}[model]


def test_cell_verdicts(cost_map):
    model = "curly lock"
    paper_ph1 = paper_table1.ref_cost_over_capsule(model, "phantom /1")
    paper_ph8 = paper_table1.ref_cost_over_capsule(model, "phantom /8")
    good = values_for(model, 3.82, 1.0, paper_ph1, paper_ph8)
    assert cost_map.cell_text(good, model) == f"**3.82x, 1.00, {paper_ph1:.1f}, {paper_ph8:.2f}**"
    # Each figure just outside its tolerance loses the bold.
    for bad in (values_for(model, 3.82 * 1.16, 1.0, paper_ph1, paper_ph8),
                values_for(model, 3.82, 1.31, paper_ph1, paper_ph8),
                values_for(model, 3.82, 1.0, paper_ph1 / 2.01, paper_ph8),
                values_for(model, 3.82, 1.0, paper_ph1, paper_ph8 * 2.01)):
        text = cost_map.cell_text(bad, model)
        assert not text.startswith("**"), text
    # The head's deepest subdivision is /4 (its /8 is over the instance limit, n/a in the paper).
    head = values_for("curly head", 3.17, 1.0, 15.5, 1.27)
    assert cost_map.cell_text(head, "curly head").startswith("**3.17x")
