"""Calibration from Python fits what `simulate calibrate` fits, on runs
traced once (per-ray counts, or recorded waves under a warp preset)."""
import json

import pytest

import rtcsim
from conftest import TINY
from test_pricing import warp_preset

BLOCK = {
    "parameters": [{"events": ["context_switch"], "min": 20, "max": 2000},
                   {"events": ["ray"], "min": 50, "max": 5000}],
    "targets": [{"match": {"scene.tilt_deg": 0}, "speedup": 1.1},
                {"match": {"scene.tilt_deg": 30}, "speedup": 1.6},
                {"match": {"scene.tilt_deg": 60}, "speedup": 2.2}],
}
SETS = {"workload.width": 16, "workload.height": 16, "output.images": False,
        "sweep": {"scene.tilt_deg": [0, 30, 60]}, "calibrate": BLOCK}


def cli_sets(sets):
    return [a for k, v in sets.items() for a in ("--set", f"{k}={json.dumps(v)}")]


@pytest.mark.parametrize("execution", ["per_ray", "warp"])
def test_calibrate_matches_cli(simulate, tmp_path, execution):
    sets = dict(SETS)
    if execution == "warp":
        sets["cost"] = [str(warp_preset(tmp_path / "warp.json", lanes=8, context_switch=200))]
    cli = simulate("calibrate", TINY, "--quiet", "--out", tmp_path / "cli", *cli_sets(sets))
    assert cli.returncode == 0, cli.stderr
    runs = rtcsim.sweep(TINY, progress=False, sets=sets, record_warps=execution == "warp")
    if execution == "warp":
        assert all(r["obb"].recorded_waves > 0 for r in runs)
    fit = rtcsim.calibrate(runs)
    assert fit.preset_json() == (tmp_path / "cli" / "calibrated_preset.json").read_text()
    assert fit.report_markdown() in cli.stdout
    assert [r["label"] for r in fit.runs] == [r.label for r in runs]
    assert fit.rms_log_error <= fit.rms_log_error_start
    assert [p["events"] for p in fit.parameters] == [["context_switch"], ["ray"]]
    # The fitted model prices the runs to the fitted speedups.
    model = fit.model
    for r, row in zip(runs, fit.runs):
        ref, obb = rtcsim.price(r["ref"], model), rtcsim.price(r["obb"], model)
        assert ref.total_cycles / obb.total_cycles == pytest.approx(row["fitted"], rel=1e-9)


def test_calibrate_block_errors_match_cli(simulate, tmp_path):
    sets = dict(SETS, calibrate=dict(BLOCK, targets=[{"match": {"scene.tilt_deg": 15}, "speedup": 1.5}]))
    cli = simulate("calibrate", TINY, "--quiet", "--out", tmp_path, *cli_sets(sets))
    assert cli.returncode == 2
    runs = rtcsim.sweep(TINY, progress=False, sets=sets)
    with pytest.raises(rtcsim.InputError) as err:
        rtcsim.calibrate(runs)
    assert str(err.value) == cli.stderr.strip()
    with pytest.raises(rtcsim.InputError, match=r"^tests/configs/tiny.json: /calibrate/parameters/0/bogus: unknown key"):
        rtcsim.calibrate(runs, {"parameters": [{"events": ["ray"], "bogus": 1}], "targets": BLOCK["targets"]})
