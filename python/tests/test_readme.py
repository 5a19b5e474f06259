"""A newcomer's first hour: the README's own code lines, extracted from the
README (not copied here), each checked to exist and to run. The long ones
(set-up and run, the test suites) run with --help, which each script
answers without setting up or building; the Python example runs as written."""
import os
import re
import subprocess
import sys
import time

from conftest import ROOT

README = os.path.join(ROOT, "README.md")


def code_lines():
    """Every line of the README's indented code blocks, without the indent."""
    lines, previous_blank = [], True
    in_block = False
    with open(README) as f:
        for line in f.read().splitlines():
            if line.startswith("    ") and (previous_blank or in_block):
                lines.append(line[4:])
                in_block = True
            elif line.strip():
                in_block = False
            previous_blank = not line.strip()
    return lines


def commands(prefix):
    return [line for line in code_lines() if line.startswith(prefix)]


def test_the_readme_has_the_two_commands_and_the_ci_one():
    scripts = {line.split("#")[0].strip() for line in commands("scripts/")}
    assert {"scripts/run", "scripts/test", "scripts/test --ci"} <= scripts
    with open(os.path.join(ROOT, ".ci", "run")) as f:
        assert "exec scripts/test --ci" in f.read()  # CI runs the README's test command


def test_every_script_line_runs(tmp_path):
    for line in sorted({line.split("#")[0].strip() for line in commands("scripts/")}):
        words = line.split()
        script = os.path.join(ROOT, words[0])
        assert os.access(script, os.X_OK), f"{words[0]} (README) is not an executable file"
        # --help: the script's usage (and simulate's, for scripts/run), with
        # no set-up and no build, so it is safe beside the other tests.
        out = subprocess.run([script, *words[1:], "--help"], cwd=ROOT, capture_output=True, text=True,
                             timeout=60)
        assert out.returncode == 0, f"{line} --help: {out.stderr[-2000:]}"
        assert out.stdout.startswith(f"usage: {words[0]}"), line


def test_every_documented_simulate_option_exists():
    help_text = subprocess.run([os.path.join(ROOT, "build", "simulate"), "--help"], capture_output=True,
                               text=True).stdout
    options = set()
    for line in commands("build/simulate") + [line for line in code_lines() if line.strip().startswith("[--")]:
        options |= set(re.findall(r"--[a-z][a-z-]*", line))
    assert options, "no simulate options found in the README"
    for option in sorted(options):
        assert option in help_text, f"README names {option}, simulate --help does not"


def test_the_python_example_runs_as_written(tmp_path):
    block = []
    for line in code_lines():
        if line.startswith("import rtcsim"):
            block = [line]
        elif block and line.strip() and not line.startswith(("scripts/", "build/", "run ", "---")):
            block.append(line)
        elif block:
            break
    assert block, "the README's Python example (import rtcsim ...) is missing"
    # Relative paths as in the README: run from a directory whose configs/ is
    # the repository's, so its figure lands in tmp_path, not in the clone.
    os.symlink(os.path.join(ROOT, "configs"), tmp_path / "configs")
    code = "import rtcsim.plot\n" + "\n".join(block)
    start = time.monotonic()
    out = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, capture_output=True, text=True, timeout=600,
                         env=dict(os.environ, MPLBACKEND="Agg"))
    assert out.returncode == 0, out.stderr[-3000:]
    assert (tmp_path / "heat.png").stat().st_size > 0
    assert time.monotonic() - start < 120  # "in seconds" (README)
