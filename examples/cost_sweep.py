#!/usr/bin/env python3
"""A cost sweep without re-tracing: trace the quickstart scene once, then
re-price its event counts with the context-switch cost and the fixed per-ray
cost swept over a range, starting from each cost preset, and plot the
speedup of the masquerade (obb) over the reference (ref) against them.

Pricing is a pure function of the counts (cycles = sum count x cost; under
a warp preset, of the recorded waves), so the sweep costs a fraction of a
trace.

    python3 examples/cost_sweep.py [--threads N] [--out DIR] [--size PIXELS]
"""
import argparse
import os
import time

from rtcsim_import import ROOT, import_rtcsim

rtcsim = import_rtcsim()  # first: it may re-run this script under the interpreter rtcsim was built for
import numpy as np  # noqa: E402
from matplotlib.figure import Figure  # noqa: E402

SWEPT = {"context_switch": np.geomspace(25, 1600, 25), "ray": np.geomspace(50, 5000, 25)}


def speedups(result, preset, event, values):
    """Speedup of obb over ref with `event` priced at each of `values`."""
    model = rtcsim.load_cost_model(preset).copy()
    out = []
    for v in values:
        cycles = model.cycles
        cycles[rtcsim.EVENT_INDEX[event]] = v
        model.cycles = cycles
        out.append(rtcsim.price(result["ref"], model).total_cycles / rtcsim.price(result["obb"], model).total_cycles)
    return np.array(out)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--threads", type=int, default=None)
    parser.add_argument("--out", default="out/cost_sweep")
    parser.add_argument("--size", type=int, default=200, help="image width and height (default 200)")
    args = parser.parse_args()

    config = os.path.join(ROOT, "configs", "runs", "quickstart.json")
    # Warp presets (an "execution" block) price the recorded waves: keep them.
    result = rtcsim.run(config, threads=args.threads, record_warps=True,
                        sets={"workload.width": args.size, "workload.height": args.size, "output.images": False})
    start = time.perf_counter()
    curves = {(p, e): speedups(result, p, e, v) for p in result.cost_presets for e, v in SWEPT.items()}
    seconds = time.perf_counter() - start
    n = sum(len(v) for v in SWEPT.values()) * len(result.cost_presets)
    print(f"{n} re-pricings of {result['ref'].rays_traced:,} rays per method in {seconds * 1e3:.1f} ms")

    fig = Figure(figsize=(11, 4.2), layout="constrained")
    axes = fig.subplots(1, len(SWEPT))
    for ax, (event, values) in zip(axes, SWEPT.items()):
        for preset in result.cost_presets:
            line, = ax.plot(values, curves[(preset, event)], label=f"from {preset}")
            own = rtcsim.load_cost_model(preset).cycles[rtcsim.EVENT_INDEX[event]]
            ax.plot([own], [result.speedup("obb", preset)], "o", color=line.get_color())
        ax.set_xscale("log")
        ax.axhline(1.0, color="#888888", lw=0.8, ls="--")
        ax.set_xlabel(f"cost of {event} (cycles)")
        ax.set_ylabel("speedup of obb over ref")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle(f"{result.name}: speedup when one cost changes (dots: the presets' own values)")
    os.makedirs(args.out, exist_ok=True)
    path = os.path.join(args.out, "speedup_vs_costs.png")
    fig.savefig(path, dpi=120)
    print("wrote", path)
    for preset in result.cost_presets:
        cs = curves[(preset, "context_switch")]
        print(f"{preset}: speedup {cs.min():.2f}x .. {cs.max():.2f}x as context_switch goes "
              f"{SWEPT['context_switch'][0]:.0f} .. {SWEPT['context_switch'][-1]:.0f} cycles")


if __name__ == "__main__":
    main()
