"""The NumPy arrays: shapes, sums equal to the totals, views (no copy) that
keep the run alive, rays and hits when the config asks for them, scenes."""
import gc

import numpy as np
import pytest

import rtcsim
from conftest import TINY


def test_pixel_counts_sum_to_totals(tiny):
    h, w = tiny.shape
    assert (h, w) == (48, 48)
    for name, m in tiny.methods.items():
        counts = m.pixel_counts
        assert counts.shape == (h, w, len(rtcsim.EVENT_NAMES))
        assert counts.dtype == np.uint32
        assert np.array_equal(counts.sum(axis=(0, 1), dtype=np.uint64), m.totals)
        assert m.events == tiny.events(name)  # report.json's totals
        assert m.totals[rtcsim.EVENT_INDEX["ray"]] == m.rays_traced


def test_pixel_cycles_sum_to_priced_total(tiny):
    for p, preset in enumerate(tiny.cost_presets):
        for name, m in tiny.methods.items():
            cycles = tiny.pixel_cycles(name, preset)
            assert cycles.shape == tiny.shape
            assert cycles.sum() == pytest.approx(m.priced[p].total_cycles, rel=1e-12)
            assert cycles.sum() == pytest.approx(tiny.cycles(name, preset), rel=1e-12)


def test_pixel_cycles_are_the_cli_arrays(tiny, tmp_path):
    """Per-ray cycles per pixel are priced by the simulator's own call, so
    they equal its cycles_<method>_<preset>.npy bit for bit (no NumPy sum in
    another order)."""
    tiny.write_outputs(tmp_path)
    for preset in tiny.costs:
        for name in tiny.methods:
            cli = np.load(tmp_path / f"cycles_{name}_{preset.name}.npy")
            assert np.array_equal(tiny.pixel_cycles(name, preset.name), cli)
            assert np.array_equal(rtcsim.price(tiny[name].pixel_counts, preset), cli)
            # Any integer type and layout prices the same.
            wide = np.asfortranarray(tiny[name].pixel_counts.astype(np.int64))
            assert np.array_equal(rtcsim.price(wide, preset), cli)


def test_arrays_are_read_only_views_that_keep_the_run(tiny):
    m = tiny["obb"]
    counts = m.pixel_counts
    assert not counts.flags.owndata and not counts.flags.writeable
    with pytest.raises(ValueError):
        counts[0, 0, 0] = 1
    # Two views share the run's memory: no copy per access.
    assert np.shares_memory(counts, m.pixel_counts)
    # An array outlives every Python object of its run.
    run = rtcsim.run(TINY, threads=1, progress=False, sets={"workload.width": 8, "workload.height": 8})
    counts, radiance, totals = run["ref"].pixel_counts, run["ref"].radiance, run["ref"].totals.copy()
    del run
    gc.collect()
    assert np.array_equal(counts.sum(axis=(0, 1), dtype=np.uint64), totals)
    assert radiance.shape == (8, 8, 3) and np.isfinite(radiance).all()


def test_rays_and_hits_when_requested(tiny):
    for m in tiny.methods.values():
        assert len(m.rays) == len(m.hits) == m.rays_traced
        assert m.rays.dtype.names == ("origin", "tmin", "direction", "tmax")
        assert m.hits.dtype.names == ("t", "normal", "u", "prim", "geom")
    ref, obb = tiny["ref"].hits, tiny["obb"].hits
    assert np.array_equal(ref, obb)  # both methods find the same hits
    hit = ref["geom"] != 0xFFFFFFFF
    assert hit.any() and np.all(ref["t"][hit] > 0) and np.all(np.isinf(ref["t"][~hit]))
    assert np.allclose(np.linalg.norm(ref["normal"][hit], axis=1), 1, atol=1e-4)
    off = rtcsim.run(TINY, threads=2, progress=False, sets={"output": {"images": False}, "workload.width": 8})
    assert len(off["obb"].rays) == 0 and len(off["obb"].hits) == 0


def test_scene_arrays():
    scene = rtcsim.load_scene(TINY)
    assert scene.stats["strands"] == 60
    assert scene.points.shape == (120, 3) and scene.radii.shape == (120,)
    assert list(scene.offsets[:3]) == [0, 2, 4]
    assert scene.vertices.shape == (0, 3) and scene.triangles.shape == (0, 3)
    prims = scene.primitives("capsule")
    assert prims["data"].shape == (60,) and prims["data"].dtype.names == ("p0", "p1", "radius")
    assert np.allclose(prims["data"]["radius"], 0.01)
    assert np.array_equal(prims["strand"], np.arange(60))
    lo, hi = prims["aabb"][:, 0], prims["aabb"][:, 1]
    assert np.all(lo <= prims["data"]["p0"]) and np.all(prims["data"]["p0"] <= hi)
    assert prims["obb"].shape == (60, 4, 3)
    curves = scene.primitives("phantom", subdivision=2)
    assert curves["data"]["cp"].shape[1:] == (4, 3)
    with pytest.raises(ValueError, match="kind"):
        scene.primitives("spline")


def test_scene_matches_report(tiny):
    scene = rtcsim.load_scene(TINY)
    prims = scene.primitives(tiny.kind)
    assert len(prims["data"]) == tiny.primitives
    assert prims["areas"]["aabb_over_obb_paper"] == pytest.approx(tiny.area_ratio(), rel=1e-12)
    stats = tiny.data["scene"]
    assert scene.stats["segments"] == stats["segments"]


def test_scene_errors_name_the_key():
    with pytest.raises(rtcsim.InputError, match=r"^<dict>: /scene/count: "):
        rtcsim.load_scene({"type": "bundle", "count": -1})
    hair = rtcsim.load_scene({"type": "hair", "strands": 10, "points_per_strand": 4, "with_mesh": True})
    assert hair.triangles.shape[1] == 3 and hair.triangles.max() < len(hair.vertices)
    assert len(hair.offsets) == 11
