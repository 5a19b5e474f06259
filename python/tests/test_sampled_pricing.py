"""Re-pricing a sampled run (docs/sampling.md) gives the CLI's whole-frame
totals: the traced tiles' cycles scaled by k, by the same C++ calls the run's
own pricing makes (issue 58), under the run's presets and under presets it
did not trace."""
import json

import pytest

import rtcsim

from conftest import TINY

FRACTION = 0.25  # k = 4: 18 of the tiny frame's 72 tiles
COMMON = {"output.images": False, "output.arrays": False, "output.rays": False, "output.hits": False,
          "sampling": {"fraction": FRACTION, "seed": 3}}
TRACED = ["turing-calibrated", "turing-per-ray-guess"]  # the Python run's presets
OTHERS = ["turing-warp-guess", "turing-per-ray-calibrated"]  # priced from its counts and waves only


def cli_report(simulate, out, presets):
    sets = dict(COMMON, cost=presets)
    args = [a for k, v in sets.items() for a in ("--set", f"{k}={json.dumps(v)}")]
    cli = simulate(TINY, "--quiet", "--threads", 2, "--out", out, *args)
    assert cli.returncode == 0, cli.stderr
    return json.loads((out / "report.json").read_text())


@pytest.fixture(scope="module")
def sampled():
    return rtcsim.run(TINY, threads=2, progress=False, record_warps=True, sets=dict(COMMON, cost=TRACED))


@pytest.mark.parametrize("presets", [TRACED, OTHERS], ids=["traced", "others"])
def test_price_of_a_sampled_run_is_the_cli_total(simulate, sampled, tmp_path, presets):
    report = cli_report(simulate, tmp_path / "cli", presets)
    sampling = report["sampling"]
    assert sampling["fraction"] == FRACTION and sampling["tiles_traced"] < sampling["tiles"]
    for name in ("ref", "obb"):
        for preset in presets:
            want = report["methods"][name]["cycles"][preset]
            got = rtcsim.price(sampled[name], preset)
            assert got.execution == want.get("execution", "per_ray")
            if got.warp is None:  # per-ray: the same products and sums, then x k
                assert got.total_cycles == want["total"]
            else:  # the recorded waves re-priced (to rounding), then x k
                assert got.total_cycles == pytest.approx(want["total"], rel=1e-12)
                assert got.per_ray_cycles == want["per_ray_model_total"]
                assert got.warp["waves"] == want["warp"]["waves"]
                for unit, cycles in want["warp"]["breakdown"].items():
                    assert got.warp[unit] == pytest.approx(cycles, rel=1e-12), unit
            if preset in TRACED:  # and the run's own pricing of it
                own = sampled[name].priced_by_preset()[preset]
                assert got.total_cycles == pytest.approx(own.total_cycles, rel=1e-12)
