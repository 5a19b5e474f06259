"""Imports rtcsim from wherever it is: installed, or the build tree
(build/python, made by scripts/setup). When the module was built for
another interpreter than the one running (e.g. a pyenv python3 without NumPy
first on PATH), re-runs the script under the interpreter CMake used."""
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def _cmake_python(build):
    try:
        with open(os.path.join(build, "CMakeCache.txt")) as f:
            for line in f:
                if line.startswith("Python_EXECUTABLE:"):
                    return line.split("=", 1)[1].strip()
    except OSError:
        pass
    return None


def import_rtcsim():
    try:
        import rtcsim
        return rtcsim
    except ImportError:
        pass
    build = os.environ.get("RTCSIM_BUILD", os.path.join(ROOT, "build"))
    sys.path.insert(0, os.path.join(build, "python"))
    try:
        import rtcsim
        return rtcsim
    except ImportError as e:
        exe = _cmake_python(build)
        if exe and os.path.exists(exe) and os.path.realpath(exe) != os.path.realpath(sys.executable) \
                and not os.environ.get("RTCSIM_REEXEC"):
            os.environ["RTCSIM_REEXEC"] = "1"
            os.execv(exe, [exe] + sys.argv)
        raise SystemExit(f"cannot import rtcsim ({e}); build it with scripts/setup "
                         "(needs pybind11-dev, python3-numpy, python3-matplotlib)")
