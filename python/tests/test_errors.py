"""Every malformed-scene case of the loader's C++ tests (tests/integrator/scene/
scene_loader_error_cases.h, printed by the scene_error_cases program) raises
camsim.InputError with the same location text; as a dict, with the same key path."""
import json
import math
import os
import subprocess

import numpy as np
import pytest
import yaml

import camsim


def _cases():
    exe = os.environ.get("CAMSIM_SCENE_ERROR_CASES")
    if not exe:
        return [pytest.param(None, id="no-cases")]  # each test then fails, saying why
    out = subprocess.run([exe], check=True, capture_output=True, text=True).stdout
    cases = [json.loads(line) for line in out.splitlines()]
    assert len(cases) >= 40
    return [pytest.param(c, id=c["name"]) for c in cases]


CASES = _cases()


def require(case):
    if case is None:
        pytest.fail("$CAMSIM_SCENE_ERROR_CASES is not set (CTest sets it; see conftest.py)")


def expected_text(c, file):
    where = f"{file}:{c['line']}" + (f":{c['column']}" if c["column"] else "")
    return where + ": " + (f"key '{c['key']}': " if c["key"] else "")


@pytest.mark.parametrize("case", CASES)
def test_text_case_raises_input_error_at_the_same_location(case, tmp_path):
    require(case)
    with pytest.raises(camsim.InputError) as info:
        camsim.Scene.from_yaml(case["text"], name="test.yaml", base_dir=tmp_path)
    e = info.value
    assert isinstance(e, ValueError)
    assert (e.file, e.line, e.column, e.key) == ("test.yaml", case["line"], case["column"],
                                                 case["key"])
    assert case["message"] in e.detail
    assert str(e) == expected_text(case, "test.yaml") + e.detail


@pytest.mark.parametrize("case", CASES)
def test_file_case_names_the_file(case, tmp_path):
    require(case)
    path = tmp_path / "test.yaml"
    path.write_text(case["text"])
    with pytest.raises(camsim.InputError) as info:
        camsim.load(path)
    assert str(info.value).startswith(expected_text(case, str(path)))


def _as_dict(text):
    """The case as a Python dict, or None where the text is no single YAML mapping to
    PyYAML (the syntax errors and the second document)."""
    try:
        d = yaml.safe_load(text)
    except yaml.YAMLError:
        return None
    if not isinstance(d, dict):
        return None
    return d


@pytest.mark.parametrize("case", CASES)
def test_dict_case_raises_input_error_naming_the_key_path(case, tmp_path):
    require(case)
    d = _as_dict(case["text"])
    if d is None or case["name"] in DICT_DIFFERS:
        pytest.skip("not a single YAML mapping to PyYAML, or read differently by it")
    with pytest.raises(camsim.InputError) as info:
        camsim.Scene.from_dict(d, base_dir=tmp_path)
    e = info.value
    assert (e.file, e.line, e.column, e.key) == ("<dict>", 0, 0, case["key"])
    assert case["message"] in e.detail
    assert str(e) == "<dict>: " + (f"key '{case['key']}': " if case["key"] else "") + e.detail


# PyYAML reads this one differently from camsim's loader (yaml-cpp): it keeps the second of
# two equal keys silently, so the dict is a valid scene (a dict cannot hold a key twice).
DICT_DIFFERS = {"DuplicateKey"}


def test_dict_key_path_of_a_nested_error():
    with pytest.raises(camsim.InputError, match=r"^<dict>: key 'shapes\[0\]\.radius': ") as info:
        camsim.Scene.from_dict({
            "camera": {"position": [0, 0, -1], "look_at": [0, 0, 0]},
            "shapes": [{"type": "sphere", "centre": [0, 0, 0], "radius": -1}]})
    assert info.value.key == "shapes[0].radius"
    with pytest.raises(camsim.InputError, match=r"key 'shapes\[0\]\.centre\[1\]'.*not a finite"):
        camsim.Scene.from_dict({
            "camera": {"position": [0, 0, -1], "look_at": [0, 0, 0]},
            "shapes": [{"type": "sphere", "centre": [0, math.nan, 0], "radius": 1}]})


@pytest.mark.parametrize("name", ["a\tb", "a\x00b", "a\x07b"], ids=["tab", "nul", "bel"])
def test_a_control_character_in_a_dict_name_is_refused_as_in_yaml(name):
    # Found by probing: the dict's JSON text turned every control character but a newline
    # into a space, and the name 'a b' was taken; a YAML scene refuses it.
    with pytest.raises(camsim.InputError, match=r"key 'name'.*control characters"):
        camsim.Scene.from_dict({
            "name": name,
            "camera": {"position": [0, 0, -1], "look_at": [0, 0, 0]},
            "materials": {"m": {"type": "diffuse"}},
            "shapes": [{"type": "sphere", "centre": [0, 0, 0], "radius": 1, "material": "m"}]})


@pytest.mark.parametrize("threads", [-1, 1025, 100000, 2**40, -2**40, 2**70])
def test_a_thread_count_out_of_range_is_an_input_error(threads):
    # Found by probing: 65537 threads or more crashed the interpreter in TBB (SIGSEGV).
    scene = camsim.default_scene(overrides={"spp": 1})
    with pytest.raises(camsim.InputError, match=r"key 'threads'.*up to 1024"):
        camsim.capture(scene, threads=threads)
    with pytest.raises(camsim.InputError, match=r"key 'threads'"):
        camsim.expose(np.full((8, 8), 100, np.float32), camsim.Sensor("smartphone-1.4um"),
                      seed=1, threads=threads)
    # Found by probing: past 32 bits (2**40) pybind11's TypeError, not camsim.InputError.
    with pytest.raises(camsim.InputError, match=r"<expose_file>: key 'threads'"):
        camsim.expose_file("no_such_raw.exr", threads=threads)


def test_a_thread_count_may_be_any_integer_type_but_not_a_float():
    scene = camsim.default_scene(overrides={"spp": 1})
    # Nor a bool (found by probing: threads=True ran one thread, spp=True rendered 1 spp).
    with pytest.raises(camsim.InputError, match=r"key 'threads'"):
        camsim.capture(scene, threads=True)
    with pytest.raises(camsim.InputError, match=r"key 'spp'.*got bool"):
        camsim.capture(scene, spp=True)
    # An on/off setting takes one.
    assert camsim.capture(scene, threads=1, guiding=False)["xyz"].shape[-1] == 3
    with pytest.raises(camsim.InputError, match=r"key 'threads'.*got 2.0"):
        camsim.capture(scene, threads=2.0)
    with pytest.raises(camsim.InputError, match=r"no such file"):  # past the thread check
        camsim.expose_file("no_such_raw.exr", threads=np.int64(2))


def test_seeds_and_frame_indices_out_of_range_are_input_errors():
    # Found by probing: a negative seed or first_frame raised pybind11's TypeError
    # ("incompatible function arguments"), not camsim.InputError naming the argument.
    electrons = np.full((8, 8), 100, np.float32)
    sensor = camsim.Sensor("smartphone-1.4um")
    for bad in (-1, 2**64, 1.5, True, "1"):
        with pytest.raises(camsim.InputError, match=r"<expose>: key 'seed'"):
            camsim.expose(electrons, sensor, seed=bad)
        with pytest.raises(camsim.InputError, match=r"<expose>: key 'first_frame'"):
            camsim.expose(electrons, sensor, seed=1, first_frame=bad)
        with pytest.raises(camsim.InputError, match=r"<expose_file>: key 'seed'"):
            camsim.expose_file("no_such_raw.exr", seed=bad)
    assert camsim.expose(electrons, sensor, seed=np.uint8(3), first_frame=np.int64(2)).shape == (8, 8)
    for iso in (0.5, 1e12):  # camsim render's and expose's range, [1, 1e7]
        with pytest.raises(camsim.InputError, match=r"<expose>: key 'iso'"):
            camsim.expose(electrons, sensor, seed=1, iso=iso)


def test_sensor_errors_name_the_function_and_argument():
    # Found by probing: these said "<input>" with an empty file and no key.
    with pytest.raises(camsim.InputError, match=r"^<Sensor>: key 'name_or_path'") as info:
        camsim.Sensor("no-such-sensor")
    assert (info.value.file, info.value.key) == ("<Sensor>", "name_or_path")
    sensor = camsim.Sensor("smartphone-1.4um")
    with pytest.raises(camsim.InputError, match=r"^<system_gain>: key 'iso'"):
        sensor.system_gain(0)
    with pytest.raises(camsim.InputError, match=r"^<saturation_electrons>: key 'iso'"):
        sensor.saturation_electrons(float("nan"))


def test_a_capture_beyond_the_memory_limit_is_an_input_error():
    # Found by probing: capture() had no memory guard (camsim render had): a 32768 x 8192
    # scene raised MemoryError std::bad_alloc. max_memory_gb sets the limit, as
    # --max-memory-gb does.
    scene = camsim.default_scene(overrides={"spp": 1})
    with pytest.raises(camsim.InputError, match=r"needs an estimated .* set by max_memory_gb"):
        camsim.capture(scene, threads=1, max_memory_gb=0.001)
    for bad in (0, -1, 2e9, "x", True, 1j, 10**400, float("nan")):
        with pytest.raises(camsim.InputError, match=r"<capture>: key 'max_memory_gb'"):
            camsim.capture(scene, threads=1, max_memory_gb=bad)


def test_bad_overrides_name_the_key():
    with pytest.raises(camsim.InputError, match="key 'overrides.spp'"):
        camsim.default_scene(overrides={"spp": "many"})
    with pytest.raises(camsim.InputError, match="key 'overrides.frobnicate'"):
        camsim.default_scene(overrides={"frobnicate": 1})
    with pytest.raises(camsim.InputError, match="key 'sensor.iso'.*needs a scene with a sensor"):
        camsim.default_scene().set_exposure(iso=200)
    with pytest.raises(camsim.InputError, match="key 'camera.look_at'.*look_at equals position"):
        camsim.default_scene().set_pose(position=[1, 1, 1], look_at=[1, 1, 1])
    with pytest.raises(camsim.InputError, match="key 'sensor.model'"):
        camsim.default_scene().set_sensor("no-such-sensor")


@pytest.mark.parametrize("top", [[{"camera": {}}], "camera: {}", 3, None],
                         ids=["list", "str", "int", "none"])
def test_a_top_level_that_is_no_dict_is_an_input_error(top):
    # Issue 34: a list raised pybind11's TypeError (incompatible function arguments).
    with pytest.raises(camsim.InputError) as info:
        camsim.Scene.from_dict(top)
    e = info.value
    assert (e.file, e.line, e.column, e.key) == ("<dict>", 0, 0, "")
    assert str(e).startswith("<dict>: the scene's top level must be a dict"), str(e)
    assert type(top).__name__ in e.detail
