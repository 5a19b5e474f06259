"""Wald et al. 2020's Table 1 for its two curly models (../shared/docs/method.md),
the cells the stand-ins of configs/runs/curly_table1.json are compared with:
the reference method's rays/s and the masquerade's speedup, per model and kind.
One copy, read by make_reproduction.py, table1_leave_one_out.py and
table1_cost_map.py."""

TABLE1 = {
    "curly lock": {"capsule": (4.1e6, 3.82), "link": (4.2e6, 4.03), "phantom /1": (81.3e3, 1.74),
                   "phantom /2": (343.0e3, 2.37), "phantom /4": (1.3e6, 3.44), "phantom /8": (5.0e6, 3.65)},
    "curly head": {"capsule": (15.5e6, 3.17), "link": (15.0e6, 3.27), "phantom /1": (1.0e6, 2.06),
                   "phantom /2": (3.7e6, 2.73), "phantom /4": (12.2e6, 2.88)},
}


def cell_of(result):
    """(model, kind) of a traced point of a Table 1 config, as TABLE1 names
    its cells: the scene's name and the kind, phantom curves with their
    pre-subdivision ("phantom /4")."""
    c = result.config  # the point's effective config
    kind = c["primitives"]["kind"]
    if kind == "phantom":
        kind = f"phantom /{c['primitives'].get('subdivision', 1)}"
    return c["scene"]["name"], kind


def speedup(model, kind):
    """The paper's obb speedup of a cell, or None."""
    return TABLE1.get(model, {}).get(kind, (None, None))[1]


def ref_cost_over_capsule(model, kind):
    """The paper's reference cost of a `kind` ray over a capsule ray on the
    same model (capsule rays/s over the kind's), or None."""
    cells = TABLE1.get(model, {})
    if kind not in cells or "capsule" not in cells:
        return None
    return cells["capsule"][0] / cells[kind][0]
