"""A Scene captured again reuses the renderable scene (Embree BVH, materials, lights) its
previous capture built when only the camera pose, exposure, f-number, ISO, sensor, seeds or
spp changed, and its arrays equal, byte for byte, a fresh camsim.load with the same
overrides; meta["scene_reused"] says which happened. Keyframed motion over another
exposure window is rebuilt."""
import numpy as np
import pytest

import camsim
from conftest import BOX, small_scene

# Wall time and the reuse flag itself differ between a reused and a fresh capture.
_VOLATILE = ("render_seconds", "scene_reused")


def assert_same_capture(a, b, where="capture"):
    """Every array (dtype, shape, bytes) and the meta of two captures are the same."""
    if isinstance(a, dict):
        keys = set(a) - (set(_VOLATILE) if where.endswith("meta") else set())
        assert keys == set(b) - (set(_VOLATILE) if where.endswith("meta") else set()), where
        for k in keys:
            assert_same_capture(a[k], b[k], f"{where}.{k}")
    elif isinstance(a, list):
        assert len(a) == len(b), where
        for i, (x, y) in enumerate(zip(a, b)):
            assert_same_capture(x, y, f"{where}[{i}]")
    elif isinstance(a, np.ndarray):
        assert a.dtype == b.dtype and a.shape == b.shape, where
        assert a.tobytes() == b.tobytes(), where
    else:
        assert a == b, where


# Each override as a function of a Scene, applied in turn to one Scene (cumulatively) and
# to a fresh load of the box together with every override before it.
OVERRIDES = [
    ("exposure", lambda s: s.set_exposure(exposure_time_s=0.01)),
    ("seed", lambda s: s.set_seed(5, noise_seed=9)),
    ("pose", lambda s: s.set_pose(position=[0.3, 0.25, -0.7], look_at=[0.27, 0.28, 0.1])),
    ("f_number and iso", lambda s: s.set_exposure(f_number=2.8, iso=800)),
    ("spp", lambda s: s.set_spp(3)),
    ("sensor", lambda s: s.set_sensor("fullframe-d850")),
]


def test_overrides_reuse_the_built_scene_with_the_arrays_of_a_fresh_load():
    scene = camsim.load(BOX)
    first = scene.render(threads=2)
    assert first["meta"]["scene_reused"] is False  # nothing built before
    previous = first
    for i, (what, override) in enumerate(OVERRIDES):
        override(scene)
        reused = scene.render(threads=2)
        assert reused["meta"]["scene_reused"] is True, what
        fresh_scene = camsim.load(BOX)
        for _, o in OVERRIDES[: i + 1]:
            o(fresh_scene)
        fresh = fresh_scene.render(threads=2)
        assert fresh["meta"]["scene_reused"] is False
        assert_same_capture(reused, fresh, what)
        # The override changed the capture: a stale scene would not pass unnoticed.
        assert reused["xyz"].tobytes() != previous["xyz"].tobytes() or \
            reused["raw"].tobytes() != previous["raw"].tobytes(), what
        previous = reused


def test_reuse_false_builds_afresh_and_keeps_nothing():
    scene = camsim.load(BOX, overrides={"spp": 1})
    assert scene.render(threads=2)["meta"]["scene_reused"] is False
    kept = scene.render(threads=2)
    assert kept["meta"]["scene_reused"] is True
    fresh = scene.render(threads=2, reuse=False)
    assert fresh["meta"]["scene_reused"] is False
    assert_same_capture(kept, fresh)
    assert camsim.capture(scene, threads=2)["meta"]["scene_reused"] is False  # dropped
    assert camsim.capture(scene, threads=2)["meta"]["scene_reused"] is True


def test_a_copy_does_not_share_the_built_scene():
    scene = camsim.Scene.from_dict(small_scene())
    scene.render(threads=1)
    twin = scene.copy()
    assert twin.render(threads=1)["meta"]["scene_reused"] is False
    assert scene.render(threads=1)["meta"]["scene_reused"] is True


def moving_ball():
    d = small_scene(spp=2, resolution=(24, 16))
    d["camera"]["shutter"] = {"open": 0.0, "close": 0.02}
    d["shapes"][0]["motion"] = [{"time": 0.0, "translate": [-0.1, 0, 0]},
                                {"time": 0.02, "translate": [0.1, 0, 0]}]
    return d


def test_motion_is_rebuilt_in_place_for_another_exposure_window_and_reused_for_a_pose():
    scene = camsim.Scene.from_dict(moving_ball())
    scene.render(threads=2)
    # Another exposure window: the Scene is reused and only what depends on the window (the
    # ball's motion steps, its BVH) is rebuilt (Scene::setCamera); checked against a fresh
    # Scene below.
    scene.set_exposure(exposure_time_s=0.01)
    longer = scene.render(threads=2)
    assert longer["meta"]["scene_reused"] is True
    assert "time" in longer["meta"]["render"]["modelled"]
    scene.set_pose(position=[0.1, 0, -3], look_at=[0, 0, 0])  # same window: reused
    moved = scene.render(threads=2)
    assert moved["meta"]["scene_reused"] is True
    fresh = camsim.Scene.from_dict(moving_ball()).set_exposure(exposure_time_s=0.01)
    fresh.set_pose(position=[0.1, 0, -3], look_at=[0, 0, 0])
    assert_same_capture(moved, fresh.render(threads=2))


@pytest.mark.parametrize("threads", [1, 2])
def test_a_sequence_reports_no_reuse(threads):
    d = small_scene()
    d["frames"] = {"count": 2, "rate_hz": 10}
    scene = camsim.Scene.from_dict(d)
    frames = scene.render(threads=threads)
    assert [f["meta"]["scene_reused"] for f in frames] == [False, False]
