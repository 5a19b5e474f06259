"""Shared fixtures: the repository, the `simulate` program of the same build,
and the tiny config (a 60-cylinder bundle, 48 x 48 paths) traced once per
test file. ctest runs each file as its own test with PYTHONPATH set to the
build tree (python/CMakeLists.txt); run by hand with
    PYTHONPATH=build/python python3 -m pytest python/tests
"""
import os
import subprocess

import pytest

import rtcsim

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
TINY = "tests/configs/tiny.json"


@pytest.fixture(autouse=True)
def _at_root(monkeypatch):
    monkeypatch.chdir(ROOT)  # configs name their presets relative to the repository


@pytest.fixture(scope="session")
def simulate():
    """Runs the CLI: simulate(*args) -> CompletedProcess (text)."""
    exe = os.environ.get("RTCSIM_SIMULATE") or os.path.join(ROOT, "build", "simulate")
    if not os.path.exists(exe):
        pytest.skip("no simulate executable (set RTCSIM_SIMULATE)")

    def call(*args):
        return subprocess.run([exe, *map(str, args)], cwd=ROOT, capture_output=True, text=True)
    return call


@pytest.fixture(scope="session")
def tiny():
    """The tiny config traced once (2 threads, rays and hits kept)."""
    cwd = os.getcwd()
    os.chdir(ROOT)
    try:
        return rtcsim.run(TINY, threads=2, progress=False, sets={"output.images": False})
    finally:
        os.chdir(cwd)
