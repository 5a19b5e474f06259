#!/usr/bin/env python3
"""What ptxas itself scheduled, read from the cubin without a disassembler.

Every Turing (and Volta) SASS instruction is 128 bits and carries its own
scheduling control (Jia et al. 2018/2019, 'Dissecting the NVIDIA Volta/Turing
GPU', section on control information): bits 105-108 the stall count (cycles
the warp waits before its next instruction: ptxas's fixed-latency schedule),
109 yield, 110-112 the write barrier a variable-latency instruction (load,
MUFU, FP64 on TU10x, ...) will release, 113-115 the read barrier, 116-121
the barriers this instruction waits on, 122-125 operand reuse. The opcode is
in bits 0-11, bits 9-11 selecting operand kinds; the 9-bit base codes used
below are those of the TuringAs assembler's grammar (FFMA 0x223, FADD 0x221,
FMUL 0x220, MUFU 0x308, LDG 0x381, BRA 0x947, ...) plus FP64 (0x228 DMUL,
0x229 DADD, 0x22a DSETP, 0x22b DFMA) [C, opcodes not re-verified against
nvdisasm here].

Per kernel, up to its first EXIT (the division and square-root slow paths are
subroutines after it, rarely run): SASS instructions, the sum of stall
counts (a lone warp's cycles when every variable-latency result is already
there), the instructions that wait on a barrier (where it waits for a load,
MUFU or FP64 result), and instructions per unit class.
Usage: sass.py FILE.cubin [--json]
"""
import json
import re
import struct
import subprocess
import sys

CLASSES = {
    "fp32": {0x020, 0x021, 0x023, 0x009, 0x00b, 0x00a},   # FMUL FADD FFMA FMNMX FSETP FSEL
    "fp64": {0x028, 0x029, 0x02a, 0x02b},                 # DMUL DADD DSETP DFMA
    "mufu": {0x108},
    "conv": {0x104, 0x105, 0x106, 0x110, 0x111, 0x112},  # F2F, F2I, I2F, ...
    "load": {0x181, 0x183, 0x182, 0x184, 0x180},          # LDG LDL LDC LDS LD
    "store": {0x186, 0x187, 0x188, 0x185},                # STG STL STS ST
    "control": {0x147, 0x14d, 0x141, 0x145, 0x143, 0x144, 0x148, 0x149, 0x150, 0x14a, 0x14b, 0x146},
}


def base_class(op12: int) -> str:
    base = op12 & 0x1ff
    for cls, codes in CLASSES.items():
        if base in codes:
            return cls
    return "int/other"


def kernels(cubin: str):
    data = open(cubin, "rb").read()
    out = subprocess.run(["readelf", "-S", "-W", cubin], capture_output=True, text=True).stdout
    for line in out.splitlines():
        m = re.search(r"\.text\.(\w+)\s+PROGBITS\s+\w+\s+(\w+)\s+(\w+)", line)
        if not m:
            continue
        name, off, size = m.group(1), int(m.group(2), 16), int(m.group(3), 16)
        words = [struct.unpack_from("<QQ", data, off + k) for k in range(0, size, 16)]
        while words and (words[-1][0] & 0xfff) == 0x918:  # NOP padding
            words.pop()
        yield name, words


def analyse(words):
    stall = waits = 0
    by = {}
    for lo, hi in words:
        w = lo | (hi << 64)
        stall += (w >> 105) & 0xF
        if (w >> 116) & 0x3F:
            waits += 1
        cls = base_class(lo & 0xFFF)
        by[cls] = by.get(cls, 0) + 1
    return {"sass_instructions": len(words), "stall_sum_cycles": stall, "barrier_waits": waits,
            "by_class": by}


def body(words):
    """The kernel up to its first EXIT: the slow paths of IEEE division and
    square root are subroutines placed after it (CALL.REL ... RET)."""
    for i, (lo, _) in enumerate(words):
        if (lo & 0x1FF) == 0x14D:
            return words[: i + 1]
    return words


def main():
    res = {}
    for name, w in kernels(sys.argv[1]):
        res[name] = analyse(body(w))
        res[name]["with_subroutines"] = analyse(w)["sass_instructions"]
    if "--json" in sys.argv:
        print(json.dumps(res, indent=1))
        return
    print(f"{'kernel':28} {'SASS':>5} {'stall sum':>9} {'waits':>5}  classes")
    for k, v in res.items():
        cc = " ".join(f"{c}:{n}" for c, n in sorted(v["by_class"].items(), key=lambda x: -x[1]))
        print(f"{k:28} {v['sass_instructions']:5} {v['stall_sum_cycles']:9} {v['barrier_waits']:5}  {cc}")


if __name__ == "__main__":
    main()
