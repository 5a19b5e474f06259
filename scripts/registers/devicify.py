#!/usr/bin/env python3
"""Copy the project's intersector headers into a build folder with CUDA
execution-space annotations added, so nvcc compiles the very code the
simulator runs (not a port) as device functions.

Rules (textual, checked by the compile that follows; nothing else changes):
- a function declared `inline` gets `__host__ __device__` before `inline`
  (inline *variables*, `inline constexpr T kName = ...` / `{...}`, are left);
- a function template over a Sink (`template <class Sink>` then a
  `[[nodiscard]] ...(` line) gets `__host__ __device__` after its attributes;
- an `inline constexpr` constant of type Ops, double, float or int named
  k... becomes `static __device__ constexpr` (the programs bind some by reference);
- member functions written in a struct body (`[[nodiscard]] ... ) const {`)
  get `__host__ __device__`.
With --float, the single-precision variant (what an OptiX program written in
float, like the paper's, would be): `double` -> `float`, glm::dvec3 ->
glm::vec3, floating literals get an `f` suffix; the PTX is then checked for
f64 instructions by the caller.
Usage: devicify.py [--float] SRC_ROOT OUT_ROOT
"""
import pathlib
import re
import sys

HEADERS = [
    "core/ray.h", "core/aabb.h", "core/affine.h", "core/obb.h", "core/float_step.h",
    "core/enum_names.h", "core/events.h", "core/ops.h", "core/box_lanes.h",
    "intersectors/bezier.h", "intersectors/capsule.h", "intersectors/cylinder.h",
    "intersectors/frame.h", "intersectors/hit.h", "intersectors/kinds.h", "intersectors/link.h",
    "intersectors/phantom.h", "intersectors/phantom_bounds.h", "intersectors/phantom_curve.h",
    "intersectors/phantom_reshetov.h", "intersectors/span.h", "intersectors/triangle.h",
]
HOST_ONLY = {"core/box_lanes.h"}
HD = "__host__ __device__ "
SCALAR_CONST = re.compile(r"inline constexpr (Ops|double|float|int) k\w+")
INLINE = re.compile(r"(?<![\w:])inline\b")


def is_variable(after_inline: str) -> bool:
    # `inline constexpr Ops kX{...}` / `inline constexpr double kX = ...;`
    paren = after_inline.find("(")
    head = after_inline if paren < 0 else after_inline[:paren]
    return "=" in head or "{" in head or paren < 0 and after_inline.rstrip().endswith(";")


def transform(text: str) -> str:
    out = []
    lines = text.split("\n")
    for i, line in enumerate(lines):
        m = INLINE.search(line)
        if m and not line.lstrip().startswith("//") and "#" not in line[: m.start()]:
            if not is_variable(line[m.end():]):
                line = line[: m.start()] + HD + line[m.start():]
            elif SCALAR_CONST.match(line[m.start():]):
                # the programs bind these by reference (std::clamp, count_ops):
                # device code needs its own copy
                # (internal linkage: whole-program mode allows no inline
                # __device__ variable)
                line = line[: m.start()] + "static __device__ " + line[m.end():].lstrip()
        elif i > 0 and lines[i - 1].strip() == "template <class Sink>" and line.startswith("[[nodiscard]]"):
            line = line.replace("[[nodiscard]] ", "[[nodiscard]] " + HD, 1)
        elif re.match(r"^\s+\[\[nodiscard\]\] (?!constexpr).*\)( const)? \{", line):
            line = line.replace("[[nodiscard]] ", "[[nodiscard]] " + HD, 1)
        out.append(line)
    return "\n".join(out)


FLOAT_LITERAL = re.compile(r"(?<![\w.])((?:\d+\.\d*|\.\d+|\d+)(?:[eE][-+]?\d+)?|0x1p-?\d+)(?![\w.])")


def to_float(text: str) -> str:
    """The single-precision variant: every double becomes float, every
    floating literal gets an f suffix (integers stay integers)."""
    text = re.sub(r"\bdouble\b", "float", text).replace("glm::dvec3", "glm::vec3").replace("glm::dmat3", "glm::mat3")
    out = []
    for line in text.split("\n"):
        if line.lstrip().startswith("//") or line.lstrip().startswith("#"):
            out.append(line)
            continue
        code, sep, comment = line.partition("//")
        code = FLOAT_LITERAL.sub(lambda m: m.group(1) + "f" if re.search(r"[.eEp]", m.group(1)) else m.group(1), code)
        out.append(code + sep + comment)
    return "\n".join(out)


def main() -> None:
    single = "--float" in sys.argv
    args = [a for a in sys.argv[1:] if a != "--float"]
    src, dst = pathlib.Path(args[0]), pathlib.Path(args[1])
    for rel in HEADERS:
        target = dst / rel
        target.parent.mkdir(parents=True, exist_ok=True)
        text = (src / rel).read_text()
        # The SSE lanes are host-only (nvcc rejects vector types in device code);
        # the intersectors use them only under __AVX2__, which nvcc never defines.
        text = text if rel in HOST_ONLY else transform(text)
        target.write_text(to_float(text) if single and rel not in HOST_ONLY else text)


if __name__ == "__main__":
    main()
