"""scripts/make_benchmark.py: docs/benchmark.md's tables and verdicts, made
here from a tiny hand-made run folder in the shape --run writes it (bench
--json's own file, the other programs' printed tables, run.json). The
verdicts are computed from the figures, every table carries its command,
commit and machine, and --update rewrites only the generated blocks."""
import importlib.util
import json
import os
import re

from conftest import ROOT


def script():
    spec = importlib.util.spec_from_file_location("make_benchmark", os.path.join(ROOT, "scripts", "make_benchmark.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def method(name, rate1, rate2):
    rates = [{"threads": t, "best_rays_per_second": r, "median_rays_per_second": r * 0.9, "best_seconds": 1.0}
             for t, r in ((1, rate1), (2, rate2))]
    return {"method": name, "build_seconds": 0.012, "rays": 640000, "rates": rates, "is_calls_per_ray": 0.46,
            "box_tests_per_ray": 16.3, "bytes_per_primitive": 128.5, "counts_match": True, "events": {"is_call": 1}}


# What bench --embree prints (sim/bench/embree_bench.cpp): case 2 ref below 0.9x on one thread.
EMBREE = """bench: threads 1,2 (2 cores), best and median of 5 traces; counting sinks on; load average 0.50
case 2: bundle N=1000 r=0.002 tilt 0, capsules
  capsules: 1000 primitives, 0 triangles
    ref  build s: rtcsim 0.001, Embree 0.002; 640000 rays; hits: rtcsim 264248, Embree 264248, on one side only 0, other capsule 0, max |dt|/t 0
      threads  rtcsim Mrays/s med [range]  Embree Mrays/s med [range]  rtcsim/Embree med [range]
            1       7.123 [ 6.5- 7.4]       9.001 [ 8.8- 9.2]        0.79x [ 0.70- 0.85]
            2       16.1 [ 15.2- 17.3]       17.5 [ 17.1- 18.0]        0.92x [ 0.88- 0.97]
    obb  build s: rtcsim 0.001, Embree 0.002; 640000 rays; hits: rtcsim 264248, Embree 264248, on one side only 0, other capsule 0, max |dt|/t 0
      threads  rtcsim Mrays/s med [range]  Embree Mrays/s med [range]  rtcsim/Embree med [range]
            1       8.5 [ 8.1- 8.9]       9.0 [ 8.8- 9.2]        0.94x [ 0.91- 0.99]
            2       17.0 [ 16.2- 17.3]       17.5 [ 17.1- 18.0]        0.97x [ 0.95- 0.99]
  (load average 0.60)
"""
EMBREE3 = """case 3: bundle N=100000 r=0.0005 tilt 30, obb only
  capsules: 100000 primitives, 0 triangles
    obb  build s: rtcsim 0.120, Embree 0.050; 4096 rays; hits: rtcsim 1958, Embree 1958, on one side only 0, other capsule 0, max |dt|/t 0
      threads  rtcsim Mrays/s med [range]  Embree Mrays/s med [range]  rtcsim/Embree med [range]
            1     0.004012 [0.0039-0.0041]     0.000701 [0.0007-0.00071]        5.72x [ 5.55- 5.99]
"""
WARP = """case 1: bundle N=1000 r=0.002 tilt 45, capsules
  capsules: 1000 primitives, 0 triangles; warp preset turing-calibrated
    ref    threads  per-ray Mrays/s med [range]     warp Mrays/s med [range]  warp/per-ray time med [range]
                 1      0.6100 [0.6000-0.6200]      0.4950 [0.4800-0.5000]       1.231 [0.999-1.338]
    obb    threads  per-ray Mrays/s med [range]     warp Mrays/s med [range]  warp/per-ray time med [range]
                 1      1.2000 [1.1000-1.3000]      1.2100 [1.1000-1.3000]       0.992 [0.892-1.100]
"""
BUILDER = """memory: freed memory kept in the heap (as simulate does)
case           prims     nodes          SAH          tree hash    best s Mprims/s/thr Mprims/cpu-s  threads
bundle       1000000    466000  7724.185693 540ee8098c45bdaf    0.3200        3.125        3.000  1 thread
bundle       1000000    466000  7724.185693 540ee8098c45bdaf    0.1700        2.941        2.900  2 threads
bundle     scaling 1 -> 2 threads: 1.88x (best times), rounds 1.85x median [1.70-1.95] of 5
bundle     control: 2 1-thread builds at once: 1.90x (best times), rounds 1.88x median [1.60-1.95]
hair         1000000    470000    29.856065 4489ecdb1a927db8    0.3300        3.030        3.000  1 thread
hair         1000000    470000    29.856065 4489ecdb1a927db8    0.2000        2.500        2.400  2 threads
hair       scaling 1 -> 2 threads: 1.65x (best times), rounds 1.60x median [1.50-1.70] of 5
hair       control: 2 1-thread builds at once: 1.70x (best times), rounds 1.66x median [1.55-1.80]
"""
FUR = """case           prims     nodes          SAH          tree hash    best s Mprims/s/thr Mprims/cpu-s  threads
fur         20000000     78125            - bf86c7a260fcc0b0   79.0000        0.253        0.800  1 thread (orientation groups of 256; clusters in the nodes column; CPU s per grouping 25.000)
"""
CALLGRIND = """case method   pixels exec          rays             Ir       Ir/ray  events
2    ref         100 per_ray      10000     25,320,000          844  3ba8b370a309
2    ref         100 warp         10000     30,660,000        1,022  3ba8b370a309
1    obb          64 per_ray       4096    211,000,000       17,216  0000deadbeef
"""


def run_folder(directory):
    """A run folder as `make_benchmark.py --run` leaves it, figures made by hand."""
    os.makedirs(directory)
    bench = {"threads": 2, "thread_counts": [1, 2], "cores": 2, "repeat": 3, "load_average_start": 0.5,
             "cases": [{"id": 2, "title": "bundle tilt 0", "note": "", "load_average_end": 0.6,
                        "runs": [{"label": "capsules", "kind": "capsules", "primitives": 1000, "triangles": 0,
                                  "load_seconds": 0.01, "methods": [method("ref", 9.5e6, 18.3e6)]}]},
                       {"id": 4, "title": "Sintel", "note": "", "skipped": "no data/hair/sintel_hair_16pts.tfx"}],
             "peak_rss_mib": 42.0, "huge_pages": "auto: on"}
    with open(os.path.join(directory, "bench.json"), "w") as f:
        json.dump(bench, f)
    texts = {"embree": EMBREE, "embree3": EMBREE3, "warp_price": WARP, "builder": BUILDER, "fur": FUR,
             "callgrind": CALLGRIND}
    for name, text in texts.items():  # the printed tables: --from parses what has no STEP.json
        with open(os.path.join(directory, name + ".txt"), "w") as f:
            f.write(text)
    step = {"exit_code": 0, "seconds": 12.0, "date": "2026-11-28 10:00 UTC", "load_average": [0.5, 0.6],
            "commit": "abc1234"}
    meta = {"machine": {"cpu": "Test CPU 9000", "cores": 2, "memory_gib": 24, "os": "Debian GNU/Linux 12 (bookworm)",
                        "kernel": "6.1.0", "arch": "x86_64"},
            "build": {"commit": "abc1234", "build_type": "Release", "compiler": "g++ 12", "x86_64_v3": True,
                      "embree": "3.13.5"},
            "quick": False,
            "steps": {name: dict(step, command=f"nice -n 10 build/{name} --demo") for name in ["bench", *texts]}}
    with open(os.path.join(directory, "run.json"), "w") as f:
        json.dump(meta, f)


def test_tables_hold_the_figures_and_computed_verdicts(tmp_path):
    run_folder(str(tmp_path / "run"))
    m = script()
    meta, figures = m.load(str(tmp_path / "run"))
    texts = m.blocks(meta, figures)
    targets = texts["targets"].splitlines()

    def row(start):
        return next(line for line in targets if line.startswith("| " + start))

    # 0.79x on one thread: case 2 misses 0.9x; case 3 (5.72x) meets 1.0x.
    assert "case 2 ref 1t 0.79x" in row("case 2 >=") and row("case 2 >=").endswith("| **no** |")
    assert "case 3 obb 1t 5.72x" in row("cases 1 and 3") and row("cases 1 and 3").endswith("| yes |")
    # 844 <= 850 but case 1 obb's event hash is not issue 39's: not met, and said why.
    assert "844 instructions per ray" in row("case 2 ref <=") and "changed: case 1 obb" in row("case 2 ref <=")
    assert row("case 2 ref <=").endswith("| **no** |")
    assert "bundle 3.12" in row("bench_build >= 2") and row("bench_build >= 2").endswith("| yes |")
    # hair scales 1.65x: the scaling target is missed, with the machine's ceiling beside it.
    scaling = row("bench_build 2-thread")
    assert "hair 1.65x (ceiling 1.70x)" in scaling and scaling.endswith("| **no** |")
    assert "not measured" in row("head frame")
    assert "case 1 obb 0.992" in row("warp within") and "**no** (1 of 2)" in row("warp within")
    assert "25.0 CPU-s" in row("the 20 M fur") and row("the 20 M fur").endswith("| yes |")
    # The figures themselves, and each table's provenance.
    assert "| 2 | ref | 1 | 7.12 [6.5-7.4] | 9 [8.8-9.2] | 0.79x [0.70-0.85] |" in texts["embree"]
    assert "| 2 | capsules (1,000 prims) | ref | 0.012 | 640,000 | 9.5 / 8.55 | 18.3 / 16.5 | 1.93x |" in texts["bench"]
    assert "skipped: no data/hair/sintel_hair_16pts.tfx" in texts["bench"]
    assert "| 2 | ref | 100 x 100 | 844 | 1,022 (+21.1 %) | 3ba8b370a309 | yes |" in texts["callgrind"]
    assert "| bundle | 1,000,000 | 540ee8098c45bdaf | 0.320 (3.12) | 0.170 | 1.88x | 1.85x [1.70-1.95] |" \
        in texts["builder"]
    assert "| 20,000,000 | 78,125 | bf86c7a260fcc0b0 | 79.00 | 25.00 |" in texts["fur"]
    assert "| 1 | ref | 1 | 0.61 [0.6-0.62] | 0.495 [0.48-0.5] | 1.231 [0.999-1.338] | yes |" in texts["warp-price"]
    for name in ("bench", "embree", "callgrind", "warp-price", "builder", "fur"):
        assert "`nice -n 10 build/" in texts[name] and "at commit abc1234 on Test CPU 9000 (2 cores, 24 GiB)" in \
            texts[name], name
    assert "| CPU | Test CPU 9000 |" in texts["machine"] and "| commit | abc1234 |" in texts["machine"]
    assert "oversubscribed" not in texts["targets"]
    # A builder run on a machine with more runnable tasks than cores: its absolute verdicts say so.
    meta["steps"]["builder"]["load_average"] = [5.0, 6.0]
    loaded = m.blocks(meta, figures)["targets"]
    assert "| **no** (at load average 6.0 on 2 cores) |" in loaded and "oversubscribed" in loaded


def test_update_rewrites_only_the_generated_blocks(tmp_path):
    run_folder(str(tmp_path / "run"))
    doc = tmp_path / "benchmark.md"
    before = ("# Benchmark\n\nHand-written text, kept as it is.\n\n"
              "<!-- generated by scripts/make_benchmark.py targets: begin -->\nold verdicts\n"
              "<!-- generated by scripts/make_benchmark.py targets: end -->\n\nMore text | with a pipe.\n\n"
              "<!-- generated by scripts/make_benchmark.py embree: begin -->\n"
              "<!-- generated by scripts/make_benchmark.py embree: end -->\nThe end, no newline")
    doc.write_text(before)
    assert script().main(["--from", str(tmp_path / "run"), "--update", str(doc)]) == 0
    after = doc.read_text()
    assert "old verdicts" not in after and "| case 2 >= 0.9x Embree" in after and "0.79x [0.70-0.85]" in after
    # Outside the blocks nothing moved: the text between and around them is byte for byte the same.
    def outside(text):
        return re.sub(r"(: begin -->\n).*?(<!-- generated by scripts/make_benchmark.py [\w-]+: end -->)", r"\1\2",
                      text, flags=re.S)
    assert outside(after) == outside(before)
    # A second pass over its own output changes nothing.
    script().main(["--from", str(tmp_path / "run"), "--update", str(doc)])
    assert doc.read_text() == after
