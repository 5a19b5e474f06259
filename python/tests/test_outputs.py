"""The CLI's tidy outputs read by the standard tools, with no clean-up:
results.csv through numpy.genfromtxt and csv, the .npy arrays through
numpy.load, their sums against report.json's totals (docs/outputs.md)."""
import csv
import json

import numpy as np
import pytest

SWEEP = ('sweep={"scene":[{"count":1,"radius":0.1},{"count":20,"radius":0.01}],'
         '"scene.tilt_deg":[0,45]}')
PRESETS = 'cost=["../../configs/hw/turing-calibrated.json","../../configs/hw/turing-per-ray-guess.json"]'


@pytest.fixture(scope="module")
def sweep_out(simulate, tmp_path_factory):
    out = tmp_path_factory.mktemp("outputs") / "sweep"
    done = simulate("tests/configs/tiny.json", "--quiet", "--threads", "2", "--out", out, "--set", SWEEP,
                    "--set", PRESETS, "--set", 'output={"images":false}',
                    "--set", "workload.width=20", "--set", "workload.height=16")
    assert done.returncode == 0, done.stderr
    return out


def test_results_csv_loads_as_numbers(sweep_out):
    data = np.genfromtxt(sweep_out / "results.csv", names=True, delimiter=",", dtype=None, encoding=None)
    assert len(data) == 4 * 2 * 2  # points x methods x presets
    # numpy drops the dots of "scene.count" from field names
    for field in ("scenecount", "sceneradius", "scenetilt_deg", "rays", "cycles", "cycles_per_ray", "speedup",
                  "is_calls_per_ray", "memory_bytes", "memory_mib", "memory_overhead_percent"):
        assert np.issubdtype(data[field].dtype, np.number), field
    assert sorted(set(data["scenecount"])) == [1, 20]
    assert set(data["cost_preset"]) == {"turing-calibrated", "turing-per-ray-guess"}
    assert set(data["execution"]) == {"warp", "per_ray"}
    assert np.allclose(data["cycles_per_ray"], data["cycles"] / data["rays"])
    assert np.all(data["speedup"][data["method"] == "ref"] == 1.0)
    assert np.allclose(data["memory_mib"], data["memory_bytes"] / 2**20)

    with open(sweep_out / "results.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    assert len(rows) == len(data)
    for row in rows:
        for key in ("scene.count", "scene.radius", "scene.tilt_deg", "cycles", "speedup", "memory_bytes"):
            float(row[key])  # raw numbers: no separators, no suffixes


def test_combined_report_and_arrays_sum_to_totals(sweep_out):
    combined = json.loads((sweep_out / "report.json").read_text())
    assert [p["index"] for p in combined["points"]] == [0, 1, 2, 3]
    for point in combined["points"]:
        directory = sweep_out / point["dir"]
        report = json.loads((directory / "report.json").read_text())
        assert report["methods"] == point["report"]["methods"]
        side = json.loads((directory / "arrays.json").read_text())
        events = side["events"]
        for name, method in report["methods"].items():
            counts = np.load(directory / f"counts_{name}.npy")
            assert counts.dtype == np.uint32
            assert counts.shape == (report["camera"]["height"], report["camera"]["width"], len(events))
            totals = counts.sum(axis=(0, 1), dtype=np.uint64)
            for i, event in enumerate(events):
                assert totals[i] == method["events"][event]["total"], event
            for preset, priced in method["cycles"].items():
                cycles = np.load(directory / side["methods"][name]["cycles"][preset]["file"])
                assert cycles.dtype == np.float64 and cycles.shape == counts.shape[:2]
                assert cycles.sum() == pytest.approx(priced["total"], rel=1e-5)


def test_rtcsim_plot_reads_the_combined_report(sweep_out):
    import rtcsim
    reports = rtcsim.load_reports(sweep_out)
    assert [r.sweep_point["scene.tilt_deg"] for r in reports] == [0, 45, 0, 45]


def test_na_rows_load_as_nan(simulate, tmp_path):
    out = tmp_path / "na"
    done = simulate("tests/configs/tiny.json", "--quiet", "--threads", "2", "--out", out,
                    "--set", 'methods=["ref","obb","lss"]', "--set", "primitives.kind=phantom",
                    "--set", 'output={"images":false,"arrays":false}',
                    "--set", "workload.width=8", "--set", "workload.height=8")
    assert done.returncode == 0, done.stderr
    data = np.genfromtxt(out / "results.csv", names=True, delimiter=",", dtype=None, encoding=None)
    lss = data["method"] == "lss"
    assert lss.sum() == 1
    for field in ("rays", "cycles", "speedup", "memory_bytes"):
        assert np.issubdtype(data[field].dtype, np.floating), field
        assert np.isnan(data[field][lss]).all() and not np.isnan(data[field][~lss]).any(), field
    assert "not linear swept spheres" in data["reason"][lss][0]


def test_relative_rays_file_is_beside_the_config(simulate, tmp_path, monkeypatch):
    """A ray file named relative to a config in a subdirectory is the one
    beside the config, from any working directory (it was resolved twice:
    sub/sub/rays.bin, where a decoy with other rays sits here)."""
    import rtcsim
    record, decoy = tmp_path / "record", tmp_path / "decoy"
    for out, size in ((record, 48), (decoy, 16)):
        done = simulate("tests/configs/tiny.json", "--quiet", "--out", out, "--set", "output.images=false",
                        "--set", f"workload.width={size}", "--set", f"workload.height={size}")
        assert done.returncode == 0, done.stderr
    sub = tmp_path / "sub"
    (sub / "sub").mkdir(parents=True)
    (sub / "rays.bin").write_bytes((record / "rays.bin").read_bytes())
    (sub / "sub" / "rays.bin").write_bytes((decoy / "rays.bin").read_bytes())
    (sub / "run.json").write_text(json.dumps({
        "scene": {"type": "bundle", "count": 60, "radius": 0.01, "tilt_deg": 30, "seed": 2},
        "cost": ["turing-per-ray-guess"], "memory": "memory-optix7",
        "workload": {"type": "rays", "rays_file": "rays.bin"},
        "output": {"images": False, "hits": True}}))
    rays = (record / "rays.bin").stat().st_size // 32
    hits = []
    for cwd, config in ((tmp_path, "sub/run.json"), (sub, "run.json")):
        monkeypatch.chdir(cwd)
        result = rtcsim.run(config, threads=2, progress=False)
        assert result.method("ref").rays_traced == rays
        assert result.data["config"]["workload"]["rays_file"] == "rays.bin"
        assert result.data["provenance"]["effective_config"]["workload"]["rays_file"] == str(sub / "rays.bin")
        hits.append(result.method("ref").hits.copy())
    assert np.array_equal(hits[0], hits[1])
