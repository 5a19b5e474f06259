#!/usr/bin/env python3
"""Tables from scripts/registers/measure's build: registers, stack, spills
and SASS size per kernel (ptxas -v and the cubin), occupancy per pipeline by
NVIDIA's occupancy rules (occupancy.cpp), and optionally the `measured`
block of the evidence JSON."""
import argparse
import json
import pathlib
import re
import subprocess

PROGRAMS = ["cylinder", "capsule", "link", "phantom_paper", "phantom_bracketed", "triangle"]


def parse_ptxas(log: pathlib.Path):
    """{(prec, src, kernel): {...}} from ptxas -v output lines."""
    out, cur = {}, None
    for line in log.read_text().splitlines():
        prec, src, rest = line.split(" ", 2)
        m = re.search(r"Compiling entry function '(\w+)'", rest)
        if m:
            cur = (prec, src, m.group(1))
            out[cur] = {}
            continue
        if cur is None:
            continue
        m = re.search(r"(\d+) bytes stack frame, (\d+) bytes spill stores, (\d+) bytes spill loads", rest)
        if m and not out[cur].get("stack_seen"):
            out[cur].update(stack_bytes=int(m.group(1)), spill_store_bytes=int(m.group(2)),
                            spill_load_bytes=int(m.group(3)), stack_seen=True)
        m = re.search(r"Used (\d+) registers", rest)
        if m:
            out[cur]["registers"] = int(m.group(1))
    for v in out.values():
        v.pop("stack_seen", None)
    return out


def sass_sizes(cubin: pathlib.Path):
    """Kernel -> (SASS instructions, registers from the section's sh_info):
    a Turing instruction is 16 bytes; the cubin keeps the register count in
    the top byte of each kernel's .text section info field."""
    txt = subprocess.run(["readelf", "-S", "-W", str(cubin)], capture_output=True, text=True).stdout
    res = {}
    for line in txt.splitlines():
        m = re.search(r"\.text\.(\w+)\s+PROGBITS\s+\w+\s+\w+\s+(\w+)\s+\w+\s+\w+\s+(\d+)\s+(\d+)", line)
        if m:
            res[m.group(1)] = (int(m.group(2), 16) // 16, int(m.group(4)) >> 24)
    return res


def ptx_f64(ptx: pathlib.Path):
    """Kernel -> number of f64 arithmetic instructions in its PTX (static)."""
    res, cur = {}, None
    for line in ptx.read_text().splitlines():
        m = re.match(r"\.visible \.entry (\w+)\(", line.strip())
        if m:
            cur = m.group(1)
            res[cur] = 0
        elif cur and re.match(r"\s*(@%p\d+ )?(add|sub|mul|fma|div|sqrt|rcp|rsqrt|min|max|abs|neg|setp)\.\w*\.?f64", line.strip()):
            res[cur] += 1
    return res


def occupancy(occ: str, regs: dict):
    lines = "".join(f"{k} {v}\n" for k, v in regs.items())
    out = subprocess.run([occ], input=lines, capture_output=True, text=True, check=True).stdout
    res = {}
    for line in out.splitlines():
        name, _, *cols = line.split()
        res[name] = {bs: {"warps": int(c.split(":")[0]), "limit": c.split(":")[1]}
                     for bs, c in zip([1, 2, 4, 8], cols)}
    return res


def warps_by_regs(r: int) -> int:
    """The register limit alone (CC 7.5): 256-register allocation units per
    warp, 16 K registers in each of 4 sub-partitions, at most 32 warps."""
    per_warp = -(-r * 32 // 256) * 256
    return min(32, 4 * (16384 // per_warp))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--build", required=True)
    ap.add_argument("--occ", required=True)
    ap.add_argument("--arch", default="sm_75")
    ap.add_argument("--nvcc-version", default="")
    ap.add_argument("--json")
    a = ap.parse_args()
    b = pathlib.Path(a.build)
    k = parse_ptxas(b / "ptxas.log")
    sass, f64 = {}, {}
    for prec in ("f64", "f32"):
        for src in ("programs", "pipeline", "paths"):
            for name, v in sass_sizes(b / f"{src}_{prec}.cubin").items():
                sass[(prec, name)] = v
            for name, n in ptx_f64(b / f"{src}_{prec}.ptx").items():
                f64[(prec, name)] = n
    kernels = {}
    for (prec, src, name), v in k.items():
        n_sass, regs_elf = sass.get((prec, name), (None, None))
        v.update(sass_instructions=n_sass, ptx_f64_ops=f64.get((prec, name)))
        assert regs_elf in (None, v["registers"]), (name, regs_elf, v)
        kernels[f"{prec}/{name}"] = v
    # The float variant must be float: any f64 instruction left in a program
    # or path kernel means devicify.py missed a double.
    stray = [n for n, v in kernels.items()
             if n.startswith("f32/") and not n.startswith("f32/pt_") and v["ptx_f64_ops"]]
    if stray:
        raise SystemExit(f"f64 instructions left in the float variant: {stray}")
    occ = occupancy(a.occ, {n: v["registers"] for n, v in kernels.items()})
    for n, v in kernels.items():
        v["warps_per_sm_by_regs"] = warps_by_regs(v["registers"])
        v["occupancy_by_block_warps"] = occ[n]

    print(f"# Register footprints, {a.arch}, nvcc -O3, default maxrregcount ({a.nvcc_version.strip()})")
    print(f"{'kernel':40} {'regs':>5} {'stack B':>8} {'spill st/ld B':>14} {'SASS instr':>10} {'f64 PTX ops':>11} {'warps/SM':>9}")
    for n, v in sorted(kernels.items()):
        print(f"{n:40} {v['registers']:5} {v['stack_bytes']:8} "
              f"{str(v['spill_store_bytes']) + '/' + str(v['spill_load_bytes']):>14} "
              f"{v['sass_instructions']:10} {v['ptx_f64_ops']:11} {v['warps_per_sm_by_regs']:9}")

    pipelines = {}
    print("\n# Pipelines: shading (pt_shade) + one intersection program")
    print(f"{'precision/program':28} {'IS regs':>7} {'shade':>5} {'max':>4} {'warps/SM':>8} {'fused regs':>10} {'warps/SM':>8}")
    for prec in ("f64", "f32"):
        shade = kernels[f"{prec}/pt_shade"]["registers"]
        for p in PROGRAMS + ["none"]:
            is_regs = kernels[f"{prec}/is_{p}"]["registers"] if p != "none" else 0
            mx = max(shade, is_regs)
            fused = kernels.get(f"{prec}/pt_{p}_fused", {}).get("registers")
            pipelines[f"{prec}/{p}"] = {
                "is_registers": is_regs or None, "shade_registers": shade, "max_registers": mx,
                "warps_per_sm_max": warps_by_regs(mx),
                "fused_registers": fused, "warps_per_sm_fused": warps_by_regs(fused) if fused else None}
            print(f"{prec + '/' + p:28} {is_regs:7} {shade:5} {mx:4} {warps_by_regs(mx):8} "
                  f"{fused if fused else '-':>10} {warps_by_regs(fused) if fused else '-':>8}")
    ilp = {prec: json.loads((b / f"ilp_{prec}.json").read_text()) for prec in ("f64", "f32")}
    print("\n# Dependent chains per program path (PTX; scripts/registers/ilp.py, latencies in its LATENCY)")
    print(f"{'precision/path':34} {'instr':>6} {'all-dep cyc':>11} {'chain cyc':>9} {'chain len':>9} {'ILP':>5} {'issue cyc':>9}  chain classes")
    for prec in ("f64", "f32"):
        for name, v in ilp[prec]["paths"].items():
            cc = " ".join(f"{c}:{n}" for c, n in sorted(v["chain_by_class"].items(), key=lambda x: -x[1]))
            print(f"{prec + '/' + name:34} {v['instructions']:6} {v['all_dependent_cycles']:11} "
                  f"{v['chain_cycles']:9} {v['chain_length']:9} {v['ilp']:5} {v['issue_cycles']:9}  {cc}")
    sass = {prec: json.loads((b / f"sass_{prec}.json").read_text()) for prec in ("f64", "f32")}
    print("\n# The same paths as ptxas scheduled them (scripts/registers/sass.py: control bits of each SASS instruction)")
    print(f"{'precision/path':34} {'SASS':>5} {'stall sum':>9} {'waits':>5} {'4 x issue':>9} {'PTX chain':>9}")
    for prec in ("f64", "f32"):
        for name, v in sass[prec].items():
            c = ilp[prec]["paths"].get(name, {})
            print(f"{prec + '/' + name:34} {v['sass_instructions']:5} {v['stall_sum_cycles']:9} "
                  f"{v['barrier_waits']:5} {4 * c.get('issue_cycles', 0):9.0f} {c.get('chain_cycles', 0):9}")
    print("\nwarps/SM: register limit alone, CC 7.5 (256-register units per warp, 4 sub-partitions of 16 K")
    print("registers, 32 warps max); with blocks of 1/2/4/8 warps (16 blocks max per SM) see the JSON.")
    if a.json:
        path = pathlib.Path(a.json)
        doc = json.loads(path.read_text()) if path.exists() else {}
        doc["measured"] = {
            "source": f"[M] scripts/registers/measure: ptxas -v of {a.arch}, -O3, default maxrregcount, "
                      f"{a.nvcc_version.strip()}; SASS instructions = .text bytes / 16; occupancy by "
                      "cuda_occupancy.h's CC 7.5 rules (scripts/registers/occupancy.cpp)",
            "kernels": kernels, "pipelines": pipelines,
            "chains": {"source": "[M/I] scripts/registers/ilp.py over the PTX of scripts/registers/paths.cu: "
                                 "critical path of register dependences, each instruction at its class latency "
                                 "(latency_cycles below; [I] for the class mapping)",
                       "latency_cycles": ilp["f64"]["latency_cycles"],
                       "issue_cycles": ilp["f64"]["issue_cycles"],
                       "f64": ilp["f64"]["paths"], "f32": ilp["f32"]["paths"]},
            "sass_schedule": {"source": "[M] scripts/registers/sass.py: per path kernel, SASS instructions, the sum "
                                        "of ptxas's stall counts (a lone warp's fixed-latency schedule) and the "
                                        "instructions that wait on a scoreboard barrier, read from the control "
                                        "bits of each 128-bit instruction, up to the kernel's first EXIT (the "
                                        "division and square-root slow-path subroutines after it excluded; "
                                        "with_subroutines counts them); both sides of short branches included",
                              "f64": sass["f64"], "f32": sass["f32"]}}
        path.write_text(json.dumps(doc, indent=1) + "\n")


if __name__ == "__main__":
    main()
