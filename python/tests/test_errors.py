"""Bad input fails from Python with exactly the CLI's one-line message."""
import json
import os
import subprocess

import pytest

import rtcsim
from conftest import ROOT, TINY

BAD_SETS = [
    ["workload.spp=-4"],
    ["workload.width=0"],
    ["methods=[\"ref\",\"nope\"]"],
    ["scene.count=0"],
    ["bogus_key=1"],
    ["primitives.kind=\"spline\""],
    ["cost=\"no/such/preset.json\""],
    ["workload.type=\"film\""],
    ["sweep={\"scene.tilt_deg\": []}"],
    ["workload.spp=10000000"],  # the work estimate: above --max-rays
]


@pytest.mark.parametrize("sets", BAD_SETS, ids=[s[0] for s in BAD_SETS])
def test_bad_config_message_matches_cli(simulate, sets, tmp_path):
    cli = simulate(TINY, "--quiet", "--out", tmp_path, *[a for s in sets for a in ("--set", s)])
    assert cli.returncode == 2, cli.stderr
    with pytest.raises(rtcsim.InputError) as err:
        rtcsim.run(TINY, progress=False, sets=sets)
    assert str(err.value) == cli.stderr.strip()


def test_limits_as_the_cli():
    sets = ["workload.spp=10000000"]
    p = rtcsim.plan(TINY, sets, limits={"force": True})  # planned, not run
    assert p.estimate["rays"] > 1e10
    with pytest.raises(rtcsim.InputError, match="--max-rays"):
        rtcsim.plan(TINY, ["workload.spp=100"], limits={"max_rays": 1000})
    with pytest.raises(ValueError, match="unknown key"):
        rtcsim.plan(TINY, limits={"max_ray": 1})


def test_missing_file_matches_cli(simulate, tmp_path):
    cli = simulate("no/such/config.json", "--quiet", "--out", tmp_path)
    assert cli.returncode == 2
    with pytest.raises(rtcsim.InputError) as err:
        rtcsim.run("no/such/config.json", progress=False)
    assert str(err.value) == cli.stderr.strip()


def test_bad_json_matches_cli(simulate, tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text('{"name": "x", "scene": {"type": "bundle",}}')
    cli = simulate(bad, "--quiet", "--out", tmp_path / "out")
    assert cli.returncode == 2
    with pytest.raises(rtcsim.InputError) as err:
        rtcsim.run(bad, progress=False)
    assert str(err.value) == cli.stderr.strip()


def test_dict_config_names_the_key():
    with open(TINY) as f:
        config = json.load(f)
    config["workload"]["spp"] = -4
    # Its preset paths are relative to tests/configs: without `base`, name them.
    unanchored = dict(config, cost=["turing-per-ray-guess"], memory="memory-optix7")
    with pytest.raises(rtcsim.InputError, match=r"^<dict>: /workload/spp: expected a positive integer, got -4$"):
        rtcsim.run(unanchored, progress=False)
    # `base` names the config in messages and anchors its relative paths.
    with pytest.raises(rtcsim.InputError, match=r"^tests/configs/tiny.json: /workload/spp: "):
        rtcsim.run(config, progress=False, base=TINY)
    assert isinstance(rtcsim.InputError("x"), ValueError)


def test_sweep_needs_sweep():
    with pytest.raises(ValueError, match="sweep points"):
        rtcsim.run(TINY, progress=False, sets={"sweep": {"scene.tilt_deg": [0, 45]}})


def test_bad_preset_and_price_inputs():
    with pytest.raises(rtcsim.InputError, match="no-such-preset"):
        rtcsim.load_cost_model("no-such-preset")
    with pytest.raises(ValueError, match="events"):
        rtcsim.price([1, 2, 3], "turing-per-ray-guess")
    with pytest.raises(KeyError, match="unknown event"):
        rtcsim.price({"teleport": 1}, "turing-per-ray-guess")
    with pytest.raises(ValueError, match="threads"):
        rtcsim.run(TINY, threads=-1, progress=False)


def test_deep_nesting_is_refused_at_parse_time(simulate, tmp_path):
    # 100,000 nested arrays (200 KB): the CLI's message, not a stack overflow.
    config = tmp_path / "deep.json"
    config.write_text('{"name": "deep",\n"scene": ' + "[" * 100000 + "]" * 100000 + "}\n")
    message = f"{config}: line 2: JSON nested deeper than 128 levels"
    cli = simulate(config, "--quiet", "--out", tmp_path / "out")
    assert cli.returncode == 2 and cli.stderr.strip() == message
    with pytest.raises(rtcsim.InputError) as err:
        rtcsim.run(str(config), progress=False)
    assert str(err.value) == message
    # A report.json as deep: rtcsim.InputError, not a RecursionError.
    (tmp_path / "report.json").write_text("[" * 100000 + "]" * 100000)
    with pytest.raises(rtcsim.InputError, match="report.json: invalid JSON"):
        rtcsim.load_report(tmp_path / "report.json")


def test_a_cut_report_is_an_input_error(tmp_path):
    (tmp_path / "report.json").write_text('{"name": "cut", "meth')
    with pytest.raises(rtcsim.InputError, match=r"report.json: line 1: invalid JSON"):
        rtcsim.load_report(tmp_path)


def test_python_arguments_are_checked_as_the_cli_checks_its_options(tmp_path):
    with pytest.raises(ValueError, match="threads: expected 0 .* up to 1024, got 1000000000000"):
        rtcsim.run(TINY, threads=10**12, progress=False)
    with pytest.raises(rtcsim.InputError, match="limits: max_memory: expected a finite number >= 1, got nan"):
        rtcsim.plan(TINY, limits={"max_memory": float("nan")})
    with pytest.raises(rtcsim.InputError, match="limits: max_rays: expected a finite number >= 1, got -1"):
        rtcsim.plan(TINY, limits={"max_rays": -1})
    # An output directory that cannot be made: rtcsim.InputError naming it.
    (tmp_path / "file").write_text("not a directory")
    out = tmp_path / "file" / "out"
    with pytest.raises(rtcsim.InputError, match=f"{out}: cannot create output directory"):
        rtcsim.run(TINY, progress=False, out=out, sets={"workload.width": 8, "workload.height": 8})


# -- the work estimate bounds the peak ----------------------------------------------
# The work estimate bounds the measured peak of the run it estimates: the
# cluster method at size 2 on a small procedural fur (50,000 capsules in
# 25,000 clusters, each its own BLAS: the term the estimate lacked when the
# 20 M fur was killed at 24.3 GB against an estimate of 7.82 GiB). The peak is
# the child's own maximum resident set (os.wait4), not the test's. The strand
# strategy: since b7f2add (the orientation grouping in three buffers
# allocated once, no longer vectors at every split) the orientation run's
# peak here is 77-87 MB against 206 MB before (2 threads, measured; the
# cause not isolated), five times under the estimate's 16 KiB per cluster,
# while strand clusters still fragment the heap as measured (351 MB against
# 643 MB estimated).
FUR = "configs/runs/cluster_fur20m.json"
SMALL = ["--set", "sweep={}", "--set", "scene.strands=12500", "--set", "cluster.size=2",
         "--set", "cluster.strategy=\"strand\"",
         "--set", "workload.width=32", "--set", "workload.height=32", "--set", "workload.spp=1",
         "--set", "cost=[\"turing-per-ray-guess\"]"]


def peak_bytes(args):
    p = subprocess.Popen(args, cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    _, status, usage = os.wait4(p.pid, 0)
    p.returncode = os.waitstatus_to_exitcode(status)
    err = p.stderr.read().decode()
    p.stderr.close()
    assert p.returncode == 0, err
    return usage.ru_maxrss * 1024  # kB on Linux


def test_the_estimate_bounds_the_peak_of_small_clusters(simulate, tmp_path):
    exe = os.environ.get("RTCSIM_SIMULATE") or os.path.join(ROOT, "build", "simulate")
    estimate = simulate(FUR, "--estimate", *SMALL)
    assert estimate.returncode == 0, estimate.stderr
    memory = json.loads(estimate.stdout.strip().splitlines()[-1])["memory_bytes"]
    measured = peak_bytes([exe, FUR, *SMALL, "--quiet", "--threads", "2", "--out", str(tmp_path / "out")])
    assert measured <= memory, f"peak {measured / 2**20:.0f} MiB above the estimate {memory / 2**20:.0f} MiB"
    # Not a bound by a mile: within 4x (measured 13.5 KB per cluster at scale, 16 KiB estimated).
    assert memory < 4 * measured


DEEP_SETS = {"key": "description" + ".a" * 60000 + "=1",
             "value": "description=" + "[" * 65500 + "]" * 65500}


@pytest.mark.parametrize("which", sorted(DEEP_SETS))
def test_deep_set_is_refused_as_the_cli(simulate, which, tmp_path):
    # Issue 56: these overflowed the stack, killing the interpreter.
    spec = DEEP_SETS[which]
    cli = simulate(TINY, "--quiet", "--out", tmp_path, "--set", spec)
    assert cli.returncode == 2, cli.stderr[-300:]
    assert cli.stderr.count("\n") == 1 and "deeper than 128 levels" in cli.stderr
    with pytest.raises(rtcsim.InputError) as err:
        rtcsim.run(TINY, progress=False, sets=[spec])
    assert str(err.value) == cli.stderr.strip()


def test_price_refuses_negative_and_nan_counts():
    # Issue 56: cast to uint64, these priced as about 1e22 cycles.
    n = len(rtcsim.EVENT_NAMES)
    for bad in ({"ray": -1}, {"ray": float("nan")}, {"ray": 1.5}):
        with pytest.raises(ValueError, match=r"counts\['ray'\]: expected"):
            rtcsim.price(bad, "turing-per-ray-guess")
    counts = [0] * n
    counts[0] = -3
    with pytest.raises(ValueError, match="counts: expected counts >= 0, got -3"):
        rtcsim.price(counts, "turing-per-ray-guess")
    pixels = __import__("numpy").zeros((2, 2, n))
    pixels[1, 1, 0] = float("inf")
    with pytest.raises(ValueError, match="counts: expected whole numbers >= 0, got inf"):
        rtcsim.price(pixels, "turing-per-ray-guess")
    with pytest.raises(TypeError, match="counts: expected numbers"):
        rtcsim.price(["a"] * n, "turing-per-ray-guess")
    assert rtcsim.price({"ray": 2}, "turing-per-ray-guess").total_cycles >= 0


def test_bad_arguments_say_what_was_expected(tmp_path):
    with pytest.raises(TypeError, match="limits: expected a dict"):
        rtcsim.plan(TINY, limits=5)
    with pytest.raises(rtcsim.InputError, match="limits: max_rays: expected a finite number >= 1, got 'many'"):
        rtcsim.plan(TINY, limits={"max_rays": "many"})
    with pytest.raises(rtcsim.InputError, match="limits: force: expected True or False, got 'yes'"):
        rtcsim.plan(TINY, limits={"force": "yes"})
    with pytest.raises(TypeError, match="path: expected a report.json file or a CLI output directory"):
        rtcsim.load_report(42)
    with pytest.raises(TypeError, match="directory: expected a CLI output directory"):
        rtcsim.load_reports(None)
    with pytest.raises(rtcsim.InputError, match=f"{tmp_path / 'nope'}: not a directory"):
        rtcsim.load_reports(tmp_path / "nope")
    with pytest.raises(rtcsim.InputError, match=f"{tmp_path / 'nope.json'}"):
        rtcsim.load_scene(tmp_path / "nope.json")
    (tmp_path / "bad.json").write_text('{"scene": [1,')
    with pytest.raises(rtcsim.InputError, match=f"{tmp_path / 'bad.json'}: line 1: invalid JSON"):
        rtcsim.load_scene(tmp_path / "bad.json")
    with pytest.raises(TypeError, match="/scene: expected a scene block"):
        rtcsim.load_scene({"scene": 3})


def test_dir_of_a_method_result(tiny):
    names = dir(tiny.method("obb"))  # raised TypeError (a list | a set)
    assert "events" in names and "totals" in names


def test_deep_gltf_hierarchy_through_load_scene(tmp_path):
    # Issue 56: a million-level node chain crashed assimp (SEGV) through load_scene too.
    quad = json.load(open(os.path.join(ROOT, "tests/fixtures/gltf/quad.gltf")))
    leaf = quad["nodes"][0]
    quad["nodes"] = [{"children": [i + 1]} for i in range(999999)] + [leaf]
    (tmp_path / "deep.gltf").write_text(json.dumps(quad))
    with pytest.raises(rtcsim.InputError, match="deep.gltf: JSON key /nodes/255/children: node hierarchy nested "
                                                "deeper than 256 levels"):
        rtcsim.load_scene({"type": "file", "mesh": {"path": str(tmp_path / "deep.gltf")}})
