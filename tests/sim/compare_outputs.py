#!/usr/bin/env python3
"""compare_outputs.py A B: every file of output directory A is in B with the
same bytes; report.json files are compared as JSON without what differs
between identical runs (provenance, wall_seconds, simulator timings). Exit 1
with the differences listed, else print how many files matched."""
import json
import os
import sys

DROP = {"provenance", "wall_seconds", "simulator"}


def comparable(v):
    if isinstance(v, dict):
        return {k: comparable(x) for k, x in v.items() if k not in DROP}
    if isinstance(v, list):
        return [comparable(x) for x in v]
    return v


def main(a, b):
    bad, files = [], 0
    for root, _, names in os.walk(a):
        for name in names:
            pa = os.path.join(root, name)
            rel = os.path.relpath(pa, a)
            pb = os.path.join(b, rel)
            files += 1
            if not os.path.exists(pb):
                bad.append(f"{rel}: missing in {b}")
                continue
            if name == "report.json":
                with open(pa) as fa, open(pb) as fb:
                    if comparable(json.load(fa)) != comparable(json.load(fb)):
                        bad.append(f"{rel}: reports differ")
            else:
                with open(pa, "rb") as fa, open(pb, "rb") as fb:
                    if fa.read() != fb.read():
                        bad.append(f"{rel}: bytes differ")
    if bad or files == 0:
        print(f"{a} vs {b}: " + ("; ".join(bad) if bad else "no files"), file=sys.stderr)
        return 1
    print(f"{files} files identical ({a} vs {b})")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
