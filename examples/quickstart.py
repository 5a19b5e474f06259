#!/usr/bin/env python3
"""The quickstart from Python: the run `build/simulate configs/runs/quickstart.json`
makes (wavy hair on a sphere, capsules, both methods), the same summary table
and speedup, and its figures with matplotlib.

    python3 examples/quickstart.py [--threads N] [--out DIR] [--size PIXELS]
"""
import argparse
import os
import time

from rtcsim_import import ROOT, import_rtcsim

rtcsim = import_rtcsim()
from rtcsim import plot  # noqa: E402  (after the import path is set)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--threads", type=int, default=None, help="cores to trace on (default: all)")
    parser.add_argument("--out", default="out/quickstart_py", help="directory for the figures")
    parser.add_argument("--size", type=int, default=None, help="image width and height (default: the config's)")
    args = parser.parse_args()

    config = os.path.join(ROOT, "configs", "runs", "quickstart.json")
    sets = {"workload.width": args.size, "workload.height": args.size} if args.size else None
    start = time.perf_counter()
    result = rtcsim.run(config, threads=args.threads, sets=sets)  # progress bars on stderr
    seconds = time.perf_counter() - start

    print(rtcsim.summary_table(result), end="")
    preset = result.cost_presets[0]
    print(f"\nspeedup of obb over ref ({preset}): {result.speedup('obb'):.2f}x "
          f"(traced and priced in {seconds:.1f} s)")
    ref, obb = result["ref"], result["obb"]
    print(f"intersection-program calls per ray: ref {result.is_per_ray('ref'):.3f}, "
          f"obb {result.is_per_ray('obb'):.3f}; per-pixel counts: {obb.pixel_counts.shape} "
          f"{obb.pixel_counts.dtype}, summing to the totals: "
          f"{bool((obb.pixel_counts.sum(axis=(0, 1)) == obb.totals).all())}")
    for p in result.cost_presets[1:]:
        print(f"under {p}: {result.speedup('obb', p):.2f}x "
              f"(ref {rtcsim.price(ref, p).total_cycles:.4g} cycles, obb {rtcsim.price(obb, p).total_cycles:.4g})")

    os.makedirs(args.out, exist_ok=True)
    figures = {
        "render": plot.render(result),
        "heat_cycles": plot.heatmaps(result, "cycles"),
        "heat_is_calls": plot.heatmaps(result, "is_call"),
        "ratio_cycles_ref_over_obb": plot.ratio_map(result),
        "speedup_table": plot.speedup_table(result),
        "cycles_by_event": plot.cycle_breakdown(result),
    }
    for name, fig in figures.items():
        path = os.path.join(args.out, name + ".png")
        fig.savefig(path, dpi=120)
        print("wrote", path)


if __name__ == "__main__":
    main()
