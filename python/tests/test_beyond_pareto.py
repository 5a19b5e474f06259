"""scripts/make_beyond.py --svg: the cluster Pareto plot agrees with the
table printed beside it (each point, read back through the axis ticks, is a
row's overhead and speedup as the table writes them), and its labels are
legible: none overlaps another label or a point, and every point's cluster
size is in the label at its position. Rows are made here in the shape
make_beyond.rows() gives (four models, two strategies, sizes 1 to 256; a
strand cluster stops growing at its strand, so its large sizes coincide),
which drew 72 labels over each other before."""
import importlib.util
import math
import os
import re

from conftest import ROOT


def make_beyond():
    spec = importlib.util.spec_from_file_location("make_beyond", os.path.join(ROOT, "scripts", "make_beyond.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


SIZES = [1, 2, 4, 8, 16, 32, 64, 128, 256]


def rows():
    out = []
    for m, scene in enumerate(["bear", "fur", "sintel", "stroke"]):
        for strategy in ("orientation", "strand"):
            for k in SIZES:
                grown = k if strategy == "orientation" else min(k, 4 + 4 * (m == 3))  # strands end
                over = (180.0 + 3 * m) / grown ** (1.2 if strategy == "orientation" else 0.8)
                speedup = 1.0 + (1.2 + 0.15 * m) / grown ** 0.45
                ref = {p: 100.0 * 2 ** 20 for p in ("memory-optix7", "memory-dxr", "memory-optix-record")}
                out.append({"scene": scene, "strategy": strategy, "size": k, "instances": 1000 // k + 1,
                            "runnable": True, "cyc": 50.0 / speedup, "is": 1.0, "inst": 1.0,
                            "speedup": [speedup, speedup * 0.9], "ref_mem": ref,
                            "mem": {p: v * (1 + over / 100.0) for p, v in ref.items()}, "build": 1.0})
    return out


def parse(svg):
    circles = [(float(x), float(y)) for x, y in re.findall(r'<circle cx="([\d.]+)" cy="([\d.]+)"', svg)]
    labels = [(float(x), float(y), t) for x, y, t in
              re.findall(r'<text x="([\d.]+)" y="([\d.]+)" font-size="9" fill="[^"]*" data-point="[^"]*">([^<]*)</text>', svg)]
    xticks = [(float(x), float(t)) for x, t in re.findall(r'<text x="([\d.]+)" y="\d+" text-anchor="middle">([\d.]+)</text>', svg)]
    yticks = [(float(y) - 4, float(t)) for y, t in re.findall(r'<text x="\d+" y="([\d.]+)" text-anchor="end">([\d.]+)</text>', svg)]
    return circles, labels, xticks, yticks


def linear(ticks):
    """value(pixel) through the first and last tick."""
    (p0, v0), (p1, v1) = ticks[0], ticks[-1]
    return lambda p: v0 + (p - p0) * (v1 - v0) / (p1 - p0)


def table_numbers(text):
    """(model, strategy, size) -> (speedup, overhead in %) as the table writes them."""
    out = {}
    for line in text.splitlines()[2:]:
        cells = [c.strip() for c in line.strip("|").split("|")]
        speedup = float(cells[7].split(" / ")[0].rstrip("x"))
        overhead = float(cells[9].split(" / ")[0].rstrip("%"))
        out[(cells[0], cells[1], int(cells[2]))] = (speedup, overhead)
    return out


def test_pareto_points_are_the_tables_and_labels_do_not_overlap(tmp_path):
    mb = make_beyond()
    rs = rows()
    path = tmp_path / "pareto.svg"
    mb.pareto_svg(rs, str(path))
    circles, labels, xticks, yticks = parse(path.read_text())
    table = table_numbers(mb.table(rs))
    assert len(circles) == len(rs) == len(table)

    # The figure's numbers are the table's (to the table's rounding and a pixel).
    over_at, speedup_at = linear(xticks), linear(yticks)
    px_over = (xticks[-1][1] - xticks[0][1]) / (xticks[-1][0] - xticks[0][0])
    px_speedup = abs((yticks[-1][1] - yticks[0][1]) / (yticks[-1][0] - yticks[0][0]))
    for (cx, cy), r in zip(circles, sorted(rs, key=lambda r: (r["scene"], r["strategy"]))):
        speedup, overhead = table[(r["scene"], r["strategy"], r["size"])]
        assert math.isclose(over_at(cx), overhead, abs_tol=0.5 + px_over), (r["scene"], r["size"])
        assert math.isclose(speedup_at(cy), speedup, abs_tol=0.005 * speedup + px_speedup), (r["scene"], r["size"])

    # Legible labels: boxes (as drawn: font 9, digits about 5.2 px wide) overlap neither each other nor a dot.
    boxes = [(x, y - 9, x + 5.2 * len(t), y) for x, y, t in labels]
    dots = [(x - 3, y - 3, x + 3, y + 3) for x, y in circles]
    for i, a in enumerate(boxes):
        for b in boxes[i + 1:] + dots:
            assert not (a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]), (labels[i], b)
    assert len(labels) < len(circles)  # coinciding points share a label

    # Every point's size is named by the label of its position ("4-256" covers 4, 8, ..., 256).
    named = {}
    for px, py, text in re.findall(r'data-point="(\d+) (\d+)">([^<]*)<', path.read_text()):
        for part in text.split(","):
            lo, _, hi = part.partition("-")
            k = int(lo)
            while k <= int(hi or lo):
                named.setdefault((int(px), int(py)), set()).add(k)
                k *= 2
    for (cx, cy), r in zip(circles, sorted(rs, key=lambda r: (r["scene"], r["strategy"]))):
        at = [k for (px, py), k in named.items() if abs(px - cx) <= 1 and abs(py - cy) <= 1]  # whole pixels
        assert any(r["size"] in k for k in at), (r["scene"], r["strategy"], r["size"])
