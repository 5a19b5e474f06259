"""`pip install .`: the Python package rtcsim, its compiled module built by
this project's CMake build (no download: setuptools, CMake, pybind11 and
NumPy are Debian packages; docs/python.md).

No pyproject.toml on purpose: with one, pip would set up an isolated build
environment and try to download setuptools into it, which fails offline.
Without it pip builds with the setuptools already installed, which is what
a Debian machine without network has. In a venv made with
--system-site-packages, add --no-build-isolation.

The build: CMake configures build-pip/cmake (Release) for the interpreter
running pip and builds only the module's target, `_rtcsim`. To reuse a
build directory that already has it (the tests do),
RTCSIM_BUILD_DIR=build pip install . builds `_rtcsim` there instead (a
no-op when it is up to date) and takes the module from it.
"""
import glob
import os
import re
import shutil
import subprocess
import sys

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext
from setuptools.command.build_py import build_py

ROOT = os.path.dirname(os.path.abspath(__file__))


def version():
    with open(os.path.join(ROOT, "CMakeLists.txt")) as f:
        return re.search(r"project\(rtcsim VERSION ([0-9.]+)", f.read()).group(1)


class CMakeBuild(build_ext):
    """Builds the `_rtcsim` target with CMake and copies the module (and the
    build's record of its interpreter, _interpreter.py) into the package."""

    def build_extension(self, ext):
        build_dir = os.environ.get("RTCSIM_BUILD_DIR")
        if build_dir:
            build_dir = os.path.abspath(build_dir)
            if not os.path.isfile(os.path.join(build_dir, "CMakeCache.txt")):
                sys.exit(f"RTCSIM_BUILD_DIR={build_dir}: not a configured CMake build directory")
        else:
            build_dir = os.path.join(ROOT, "build-pip", "cmake")
            if not os.path.isfile(os.path.join(build_dir, "CMakeCache.txt")):
                subprocess.run(["cmake", "-S", ROOT, "-B", build_dir, "-DCMAKE_BUILD_TYPE=Release",
                                f"-DPython_EXECUTABLE={sys.executable}", "-DRTCSIM_PYTHON=ON"], check=True)
        jobs = os.environ.get("CMAKE_BUILD_PARALLEL_LEVEL") or str(min(os.cpu_count() or 1, 2))
        subprocess.run(["cmake", "--build", build_dir, "--target", "_rtcsim", "-j", jobs], check=True)
        package = os.path.join(build_dir, "python", "rtcsim")
        built = glob.glob(os.path.join(package, "_rtcsim*.so"))
        if len(built) != 1:
            sys.exit(f"expected one _rtcsim module in {package}, found {built}")
        target = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copyfile(built[0], target)
        shutil.copyfile(os.path.join(package, "_interpreter.py"),
                        os.path.join(os.path.dirname(target), "_interpreter.py"))


class BuildPyWithPresets(build_py):
    """The package carries the cost and memory presets (configs/hw), where
    rtcsim.PRESET_DIR and the compiled module look for them."""

    def run(self):
        super().run()
        presets = os.path.join(self.build_lib, "rtcsim", "configs", "hw")
        os.makedirs(presets, exist_ok=True)
        for f in glob.glob(os.path.join(ROOT, "configs", "hw", "*.json")):
            shutil.copyfile(f, os.path.join(presets, os.path.basename(f)))


setup(
    name="rtcsim",
    version=version(),
    description="A simulator of GPU ray-tracing hardware with a cost model",
    packages=["rtcsim"],
    package_dir={"rtcsim": "python/rtcsim"},
    ext_modules=[Extension("rtcsim._rtcsim", sources=[])],
    cmdclass={"build_ext": CMakeBuild, "build_py": BuildPyWithPresets},
    python_requires=">=3.8",
    install_requires=["numpy"],
    zip_safe=False,
)
