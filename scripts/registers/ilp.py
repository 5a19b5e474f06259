#!/usr/bin/env python3
"""Dependent-chain length of one program path, from its PTX.

The machine has no SASS disassembler (no cuobjdump or nvdisasm in the CUDA 13
pip toolkit), so the chain is found in PTX, where each value has its own
virtual register: an instruction waits for the last instruction that wrote
each register it reads. A kernel of paths.cu is one path of a program (its
branches are short exits, so both sides are counted as if run: an upper
bound on the instruction count, the same critical path). Each instruction is
priced by the latency of its class (LATENCY, cycles, sources in
configs/hw/evidence/turing-sm.json); the critical path is the longest chain
of such waits. Reported per path:
  instructions     PTX instructions (ld.param and declarations excluded)
  all_dependent    the sum of every instruction's latency: the price if each
                   waited for the one before
  chain_cycles     the critical path's latency
  chain_length     instructions on the critical path, and their classes
  ilp              all_dependent / chain_cycles: independent work per cycle
                   of chain that a warp offers (what other warps need not
                   hide)
  issue_cycles     SM cycles the path's warp instructions take at the
                   Guide's CC 7.5 throughputs (ISSUE): the issue-bound price
Usage: ilp.py FILE.ptx [--json]
"""
import json
import re
import sys

# class -> latency in cycles (dependent issue), Turing TU102/TU104.
LATENCY = {
    "f32": 4,        # FADD/FMUL/FFMA/FSETP/FMNMX: Guide 'about 4' on 7.x; Arafa et al. 2019 FMUL 4
    "int": 4,        # IADD/ISETP/IMAD/LOP/SEL/MOV: Arafa et al. 2019 IADD 4, ISETP 4
    "f64": 45,       # DADD/DMUL/DFMA/DSETP: Arafa et al. 2019 TITAN RTX 45
    "cvt64": 45,     # F2F to or from f64: run by the FP64 unit on TU10x [I]
    "div32": 39,     # div.rn.f32, inline fast path: Accel-Sim SM75 fp div 39 [C]
    "rcp32": 70,     # rcp.rn.f32: Arafa 70
    "sqrt32": 72,    # sqrt.rn.f32: Arafa 72
    "mufu": 25,      # rsqrt/sqrt/rcp .approx.f32, sin/cos/ex2/lg2: Arafa 25 (rsqrt, sqrt.approx)
    "div64": 1165,   # div.rn.f64: Arafa 1165 (an in-core benchmark on a 2080 Ti found ~455)
    "rcp64": 251,    # rcp.rn.f64: Arafa 251
    "sqrt64": 366,   # sqrt.rn.f64: Arafa 366
    "load": 32,      # ld.global / ld.local hitting L1: Jia et al. 2019, Accel-Sim l1_latency 32
    "store": 0,      # nothing waits on a store
    "control": 0,    # bra, ret
}


def classify(op: str) -> str:
    base = op.split(".")[0]
    if base in ("bra", "ret", "exit", "bar"):
        return "control"
    if base == "st":
        return "store"
    if base == "ld":
        return "load"
    if base == "cvt":
        return "cvt64" if ".f64" in op else "int" if not ".f32" in op else "f32"
    if base == "div":
        return "div64" if op.endswith(".f64") else "div32" if op.endswith(".f32") else "int"
    if base == "rcp":
        return "mufu" if ".approx" in op else "rcp64" if op.endswith(".f64") else "rcp32"
    if base == "sqrt":
        return "mufu" if ".approx" in op else "sqrt64" if op.endswith(".f64") else "sqrt32"
    if base in ("rsqrt", "sin", "cos", "ex2", "lg2", "tanh"):
        return "mufu"
    if op.endswith(".f64") and base in ("add", "sub", "mul", "fma", "mad", "min", "max", "abs", "neg", "setp", "testp"):
        return "f64"
    if op.endswith(".f32") or op.endswith(".ftz.f32"):
        return "f32"
    return "int"


# class -> SM cycles one warp instruction takes of its unit's throughput
# (CUDA Programming Guide, arithmetic throughput, CC 7.5: 32 / results per
# clock per SM), for the issue-bound side of a path's price.
ISSUE = {
    "f32": 0.5,      # 64 FP32 results per clock per SM
    "int": 0.5,      # 64 INT32 add/compare per clock per SM
    "f64": 16,       # 2 FP64 results per clock per SM
    "cvt64": 16,     # conversions to or from 64-bit types: taken as the FP64 rate [I]
    "div32": 6,      # MUFU.RCP (16/clock: 2) + ~8 FP32 [I]
    "rcp32": 4.5,    # MUFU.RCP + ~5 FP32 [I]
    "sqrt32": 4.5,   # MUFU.RSQ + ~5 FP32 [I]
    "mufu": 2,       # 16 MUFU results per clock per SM
    "div64": 160,    # MUFU.RCP64H + ~10 DFMA at 16 [I]; 162 measured on a 2080 Ti
    "rcp64": 130,    # MUFU.RCP64H + ~8 DFMA [I]
    "sqrt64": 160,   # MUFU.RSQ64H + ~10 DFMA [I]
    "load": 1,       # one LSU issue of a 4-byte-per-lane load (128 B: 1 L1 wavefront) [I]
    "store": 1,
    "control": 0.25, # one of the SM's 4 issue slots per clock
}

REG = re.compile(r"%[a-z]+\d*")


def parse(ptx: str):
    """entry name -> list of (op, dsts, srcs)."""
    kernels, cur, body = {}, None, False
    for raw in ptx.splitlines():
        line = raw.split("//")[0].strip()
        m = re.match(r"\.visible \.entry (\w+)\(", line)
        if m:
            cur, body = m.group(1), False
            kernels[cur] = []
            continue
        if cur is None:
            continue
        if line == "{" and not body:
            body = True
            continue
        if line == "}":
            cur = None
            continue
        if not body or not line or line.startswith(".") or line.endswith(":") or line in ("{", "}"):
            continue
        line = line.rstrip(";")
        guard = []
        if line.startswith("@"):
            g, line = line.split(None, 1)
            guard = REG.findall(g)
        parts = line.split(None, 1)
        op = parts[0]
        args = parts[1] if len(parts) > 1 else ""
        if op.startswith("ld.param") or op.startswith("cvta") and "param" in args:
            kernels[cur].append((op, REG.findall(args.split(",")[0]), [], True))
            continue
        if op.split(".")[0] in ("st", "bra", "ret", "bar", "call", "exit"):
            kernels[cur].append((op, [], REG.findall(args) + guard, False))
            continue
        m = re.match(r"\s*(\{[^}]*\}|[^,]+),(.*)", args)
        if not m:
            kernels[cur].append((op, [], REG.findall(args) + guard, False))
            continue
        kernels[cur].append((op, REG.findall(m.group(1)), REG.findall(m.group(2)) + guard, False))
    return kernels


def analyse(instrs):
    writer, finish, pred = {}, [], []
    classes, n = {}, 0
    total, issue = 0, 0.0
    for i, (op, dsts, srcs, free) in enumerate(instrs):
        cls = "free" if free else classify(op)
        lat = 0 if free else LATENCY[cls]
        ready, best = 0, None
        for r in srcs:
            j = writer.get(r)
            if j is not None and finish[j] > ready:
                ready, best = finish[j], j
        finish.append(ready + lat)
        pred.append(best)
        for r in dsts:
            writer[r] = i
        if not free:
            issue += ISSUE[cls]
        if not free and cls != "control":
            n += 1
            total += lat
            classes[cls] = classes.get(cls, 0) + 1
    end = max(range(len(finish)), key=lambda k: finish[k])
    chain, k = {}, end
    length = 0
    while k is not None:
        op = instrs[k][0]
        if not instrs[k][3]:
            cls = classify(op)
            chain[cls] = chain.get(cls, 0) + 1
            length += 1
        k = pred[k]
    return {"instructions": n, "by_class": classes, "all_dependent_cycles": total,
            "chain_cycles": finish[end], "chain_length": length, "chain_by_class": chain,
            "ilp": round(total / finish[end], 2) if finish[end] else None,
            "issue_cycles": round(issue, 1)}


def main():
    path = sys.argv[1]
    res = {k: analyse(v) for k, v in parse(open(path).read()).items()}
    if "--json" in sys.argv:
        print(json.dumps({"latency_cycles": LATENCY, "issue_cycles": ISSUE, "paths": res}, indent=1))
        return
    print(f"{'path':28} {'instr':>6} {'all-dep cyc':>11} {'chain cyc':>9} {'chain len':>9} {'ILP':>5} {'issue cyc':>9}  chain classes")
    for k, v in res.items():
        cc = " ".join(f"{c}:{n}" for c, n in sorted(v["chain_by_class"].items(), key=lambda x: -x[1]))
        print(f"{k:28} {v['instructions']:6} {v['all_dependent_cycles']:11} {v['chain_cycles']:9} "
              f"{v['chain_length']:9} {v['ilp']:5} {v['issue_cycles']:9}  {cc}")


if __name__ == "__main__":
    main()
