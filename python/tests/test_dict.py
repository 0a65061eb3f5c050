"""A dict scene equals its YAML twin (same arrays, bit for bit); overrides reuse what was
loaded (no mesh file is read again)."""
import numpy as np
import yaml

import camsim
from conftest import BOX, small_scene


def assert_same_arrays(a, b):
    for key in ("xyz", "rgb", "acescg", "display8", "electrons", "raw"):
        np.testing.assert_array_equal(a[key], b[key], err_msg=key)
    for layer in a["aovs"]:
        np.testing.assert_array_equal(a["aovs"][layer], b["aovs"][layer], err_msg=layer)


def test_dict_scene_equals_its_yaml_twin():
    from_file = camsim.load(BOX).render(threads=1)
    d = yaml.safe_load(BOX.read_text())
    from_dict = camsim.Scene.from_dict(d, base_dir=BOX.parent).render(threads=1)
    assert_same_arrays(from_file, from_dict)
    # NumPy values and tuples are scene values too.
    d["camera"]["position"] = np.array(d["camera"]["position"])
    d["camera"]["resolution"] = tuple(d["camera"]["resolution"])
    d["render"]["spp"] = np.int64(d["render"]["spp"])
    assert_same_arrays(from_file, camsim.Scene.from_dict(d).render(threads=1))


def test_same_seed_same_arrays_for_any_thread_count():
    a = camsim.Scene.from_dict(small_scene(seed=4, spp=8)).render(threads=1)
    b = camsim.Scene.from_dict(small_scene(seed=4, spp=8)).render(threads=2)
    c = camsim.Scene.from_dict(small_scene(seed=5, spp=8)).render(threads=2)
    np.testing.assert_array_equal(a["xyz"], b["xyz"])
    assert not np.array_equal(a["xyz"], c["xyz"])
    assert a["meta"]["render"]["spp"] == 8
    assert (a["meta"]["threads"], b["meta"]["threads"]) == (1, 2)  # threads= honoured


def test_the_sidecar_says_where_russian_roulette_starts():
    d = small_scene(spp=1)
    assert camsim.Scene.from_dict(d).render(threads=1)["meta"]["render"]["rr_depth"] == 4
    d["render"]["rr_depth"] = 7
    assert camsim.Scene.from_dict(d).render(threads=1)["meta"]["render"]["rr_depth"] == 7


def test_a_sequence_returns_one_result_per_frame():
    d = small_scene(spp=2)
    d["frames"] = {"count": 3, "rate_hz": 24}
    d["shapes"][0]["motion"] = [{"time": 0, "translate": [0, 0, 0]},
                                {"time": 0.2, "translate": [0.3, 0, 0]}]
    calls = []
    frames = camsim.Scene.from_dict(d).render(progress=lambda done, total: calls.append(total))
    assert isinstance(frames, list) and len(frames) == 3
    assert not np.array_equal(frames[0]["xyz"], frames[2]["xyz"])  # the sphere moved
    t = [f["meta"]["pose"]["reference_time_s"] for f in frames]
    assert t[0] < t[1] < t[2]
    assert calls and calls[-1] == calls[0]


def test_pose_override_reads_no_mesh_again(tmp_path):
    (tmp_path / "quad.obj").write_text("v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n")
    d = small_scene()
    d["shapes"].append({"type": "mesh", "file": "quad.obj", "material": "m"})
    scene = camsim.Scene.from_dict(d, base_dir=tmp_path)
    assert scene.input_files == [str(tmp_path / "quad.obj")]
    (tmp_path / "quad.obj").unlink()  # a reload would fail now
    scene.set_pose(position=[0.5, 0, -3], look_at=[0, 0, 0]).set_exposure(exposure_time_s=0.02)
    r = scene.render(threads=1)
    np.testing.assert_allclose(scene.world_from_camera[:3, 3], [0.5, 0, -3])
    assert r["meta"]["camera"]["derived"]["exposure_time_s"] == 0.02
    # The pose it loaded with, set again, gives the very same picture as the original.
    d2 = small_scene()
    again = camsim.Scene.from_dict(d2).set_pose(position=[1, 0, -3], look_at=[0, 0, 0])
    again.set_pose(position=[0, 0, -3], look_at=[0, 0, 0])
    np.testing.assert_array_equal(again.render()["xyz"],
                                  camsim.Scene.from_dict(d2).render()["xyz"])


def test_pose_override_matches_a_reload_at_that_pose():
    moved = camsim.Scene.from_dict(small_scene(spp=16)).set_pose(position=[0.3, 0.2, -2.5],
                                                                 look_at=[0, 0, 0])
    d = small_scene(spp=16)
    d["camera"]["position"] = [0.3, 0.2, -2.5]
    a, b = moved.render()["xyz"], camsim.Scene.from_dict(d).render()["xyz"]
    # Same samples; only the float rounding of the shifted render origin differs.
    np.testing.assert_allclose(a, b, rtol=1e-4, atol=1e-6 * float(b.max()))
    w = moved.world_from_camera
    matrix = camsim.Scene.from_dict(small_scene(spp=16)).set_pose(world_from_camera=w)
    np.testing.assert_array_equal(matrix.world_from_camera, w)


def test_sensor_override_equals_the_scene_with_that_sensor():
    d = small_scene(spp=2)
    with_sensor = dict(d, sensor={"model": "smartphone-1.4um", "noise_seed": 2})
    a = camsim.Scene.from_dict(d).set_sensor("smartphone-1.4um").set_seed(noise_seed=2)
    b = camsim.Scene.from_dict(with_sensor)
    assert a.sensor == b.sensor and a.iso == b.iso
    np.testing.assert_array_equal(a.render()["raw"], b.render()["raw"])


def test_every_capture_estimates_its_error_and_passes_reach_a_target():
    scene = camsim.Scene.from_dict(small_scene(seed=4, spp=4))
    r = camsim.capture(scene, threads=2)
    est = r["meta"]["render"]["estimated_error"]
    assert est["channel"] == "Y" and est["rmse"] > 0 and est["mrae"] > 0
    assert "passes" not in r["meta"]["render"]
    target = est["mrae"] / 3  # needs about 9x the samples: two passes (4x, then 4x or 2x)
    p = camsim.capture(scene, threads=1, target_error=target)
    assert p["meta"]["render"]["passes"]["stopped_by"] == "target_error"
    spp = p["meta"]["render"]["spp"]
    assert spp > 4 and p["meta"]["render"]["estimated_error"]["mrae"] <= target
    # The image is the one-pass render at that spp, bit for bit.
    q = camsim.capture(scene, threads=2, spp=spp)
    np.testing.assert_array_equal(p["xyz"], q["xyz"])
    assert q["meta"]["render"]["estimated_error"] == p["meta"]["render"]["estimated_error"]


def test_adaptive_sampling_is_recorded_and_the_same_on_any_thread_count():
    scene = camsim.Scene.from_dict(small_scene(seed=4, spp=32)).set_adaptive(0.3)
    a = camsim.capture(scene, threads=1)
    b = camsim.capture(scene, threads=2)
    np.testing.assert_array_equal(a["xyz"], b["xyz"])
    adaptive = a["meta"]["render"]["adaptive"]
    assert adaptive["threshold"] == 0.3 and adaptive["min_spp"] == 6  # max(4, ceil(sqrt 32)) even
    assert 6 <= adaptive["mean_spp"] < 32 and a["meta"]["render"]["spp"] == 32
    spp = a["spp"]  # each pixel's samples: their mean is mean_spp
    assert spp.shape == a["xyz"].shape[:2] and 6 <= spp.min() and spp.max() <= 32
    assert abs(float(spp.mean(dtype=np.float64)) - adaptive["mean_spp"]) < 1e-9
    plain = camsim.capture(camsim.Scene.from_dict(small_scene(seed=4, spp=32)), threads=2)
    assert "adaptive" not in plain["meta"]["render"] and "spp" not in plain
    assert camsim.capture(scene, threads=2, adaptive_threshold=1e-9)["xyz"].tobytes() == \
        plain["xyz"].tobytes()  # nothing converges: the fixed render


def test_a_pose_export_that_cannot_be_written_is_refused_before_rendering():
    """Two shapes of one BOP class (obj_id) with different models: the capture raises
    camsim.InputError at key `exports` before it renders, as `camsim render` exits 2."""
    d = small_scene()
    d["exports"] = ["bop"]
    d["shapes"][0]["class"] = 1
    d["shapes"].append(dict(d["shapes"][0], centre=[1, 0, 0], radius=0.25, name="small"))
    scene = camsim.Scene.from_dict(d)
    calls = []
    try:
        scene.render(threads=1, progress=lambda *a: calls.append(a))
    except camsim.InputError as e:
        assert e.key == "exports", str(e)
        assert "different models" in str(e), str(e)
    else:
        raise AssertionError("no error")
    assert calls == [], calls  # refused before any pixel was rendered: no progress reported
