"""Every override's boundary values through Python (issue 35, "settings defined once").

The table is the library's own (camsim.override_settings(), integrator/scene/overrides.h):
lo, hi and the nearest values just outside them (an open lower bound: lo refused, the next
double above accepted) go to load()'s overrides dict, to the set_* methods and to the
keyword arguments of camsim.capture() and Scene.render(); each accepts exactly the values in
range, as the CLI, the library and a dataset manifest do (tests/cli/override_ranges_test.cpp
feeds them the same table). capture() runs with a display that does not exist, so an
accepted value stops at the display check, before any rendering.
"""
import math

import pytest

import camsim
from conftest import BOX, small_scene

RANGED = [s for s in camsim.override_settings() if s["type"] in ("int", "float")]


def boundary_cases():
    cases = []
    for s in RANGED:
        lo, hi = s["lo"], s["hi"]
        if s["type"] == "int":
            cases += [(s, lo, True), (s, hi, True), (s, lo - 1, False), (s, hi + 1, False)]
        else:
            if s["lo_open"]:
                cases += [(s, lo, False), (s, math.nextafter(lo, math.inf), True)]
            else:
                cases += [(s, lo, True), (s, math.nextafter(lo, -math.inf), False)]
            cases += [(s, hi, True), (s, math.nextafter(hi, math.inf), False)]
    return cases


CASES = boundary_cases()
IDS = [f"{s['key']}={v!r}" for s, v, _ in CASES]


def test_table_has_every_ranged_setting():
    assert [s["key"] for s in RANGED] == ["spp", "seed", "target_error", "time_limit_s",
                                          "adaptive_threshold", "exposure_time_s", "f_number",
                                          "iso", "noise_seed", "guiding"]
    assert len(CASES) == 40
    f = next(s for s in RANGED if s["key"] == "f_number")
    assert (f["lo"], f["hi"], f["range"], f["flag"]) == (0.5, 1e4, "[0.5, 10000]", "--f-number")


@pytest.mark.parametrize("setting,value,accepted", CASES, ids=IDS)
def test_overrides_dict(setting, value, accepted):
    if accepted:
        camsim.load(BOX, overrides={setting["key"]: value})
    else:
        with pytest.raises(camsim.InputError,
                           match=f"'(overrides.{setting['key']}|{setting['scene_key']})'"):
            camsim.load(BOX, overrides={setting["key"]: value})


SETTERS = {
    "spp": lambda s, v: s.set_spp(v),
    "seed": lambda s, v: s.set_seed(v),
    "noise_seed": lambda s, v: s.set_seed(noise_seed=v),
    "target_error": lambda s, v: s.set_passes(target_error=v),
    "time_limit_s": lambda s, v: s.set_passes(time_limit_s=v),
    "adaptive_threshold": lambda s, v: s.set_adaptive(v),
    "exposure_time_s": lambda s, v: s.set_exposure(exposure_time_s=v),
    "f_number": lambda s, v: s.set_exposure(f_number=v),
    "iso": lambda s, v: s.set_exposure(iso=v),
    "guiding": lambda s, v: s.set_guiding(v),
}


@pytest.mark.parametrize("setting,value,accepted", CASES, ids=IDS)
def test_setters(setting, value, accepted):
    scene = camsim.load(BOX)
    if accepted:
        SETTERS[setting["key"]](scene, value)
    else:
        with pytest.raises(camsim.InputError, match=setting["scene_key"]):
            SETTERS[setting["key"]](scene, value)
    scene = camsim.load(BOX)
    with pytest.raises(camsim.InputError, match=setting["scene_key"]):
        SETTERS[setting["key"]](scene, "many")  # a wrong type: the same error type


@pytest.mark.parametrize("setting,value,accepted", CASES, ids=IDS)
@pytest.mark.parametrize("call", ["capture", "render"])
def test_keyword_arguments(setting, value, accepted, call):
    scene = camsim.load(BOX)
    run = camsim.capture if call == "capture" else (lambda sc, **kw: sc.render(**kw))
    with pytest.raises(camsim.InputError) as info:
        run(scene, display="no such display", **{setting["key"]: value})
    message = str(info.value)
    if accepted:
        assert "out of range" not in message and "no such display" in message, message
    else:
        assert setting["scene_key"] in message or setting["key"] in message, message
        if -2**63 <= value < 2**63:  # beyond int64 the type is refused before the range
            assert setting["range"] in message, message


def test_issue_examples():
    scene = camsim.load(BOX)
    with pytest.raises(camsim.InputError, match=r"camera.f_number.*out of range \[0.5, 10000\]"):
        camsim.capture(scene, f_number=0.3)
    with pytest.raises(camsim.InputError, match=r"sensor.iso.*out of range \[1, 10000000\]"):
        scene.render(iso=0.5)
    with pytest.raises(camsim.InputError, match=r"camera.f_number.*out of range"):
        camsim.load(BOX, overrides={"f_number": 0.3})


def test_keyword_overrides_are_for_one_capture():
    scene = camsim.Scene.from_dict(small_scene(seed=0, spp=1))
    a = camsim.capture(scene, spp=2, seed=7)
    assert (scene.spp, scene.seed) == (1, 0)  # the Scene keeps its own
    b = scene.copy().set_spp(2).set_seed(7).render()
    assert (a["xyz"] == b["xyz"]).all()
    assert a["meta"]["render"]["spp"] == 2


def test_a_pose_override_is_applied_as_set_pose():
    # Found by probing: every pose given as an override (a dict or a 4x4 matrix, to capture()
    # or load()) was refused, "expected a list of 3 numbers, got list" (the module's file
    # that converts overrides lacked pybind11's list conversions).
    scene = camsim.Scene.from_dict(small_scene(seed=0, spp=1))
    pose = {"position": [0.5, 0.0, -3.0], "look_at": [0, 0, 0], "up": (0.0, 1.0, 0.0)}
    a = camsim.capture(scene, pose=pose)
    b = scene.copy().set_pose(**pose).render()
    assert (a["xyz"] == b["xyz"]).all()
    # The matrix form is camsim's world_from_camera: OpenCV's with its y column negated.
    m = [list(row) for row in a["meta"]["pose"]["world_from_camera_opencv"]]
    for row in m:
        row[1] = -row[1]
    c = camsim.capture(scene, pose=m)
    assert (c["xyz"] == a["xyz"]).all()
    with pytest.raises(camsim.InputError, match=r"key 'pose.position'.*3 numbers"):
        camsim.capture(scene, pose={"position": [0, 0], "look_at": [0, 0, 0]})


def test_an_int_beyond_64_bits_names_its_value():
    # "expected an int, got int" before (found by probing).
    with pytest.raises(camsim.InputError, match=r"key 'overrides.seed'.*within 64 bits, got 9223372036854775808"):
        camsim.default_scene(overrides={"seed": 2**63})
