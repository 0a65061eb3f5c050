"""Arguments Python hands over in forms C++ did not expect: paths as bytes or os.PathLike
(and with a NUL), strings that are not valid Unicode, containers that contain themselves,
region sums past 32 bits, NumPy scalars. All found by probing the module: two segfaults,
pybind11's RuntimeError, a bytes path read as its repr "b'...'", a NUL that cut the path
so that another file was read."""
import os
import pathlib

import numpy as np
import pytest

import camsim

SOURCE = pathlib.Path(os.environ.get("CAMSIM_SOURCE_DIR", "."))
SENSOR_FILE = SOURCE / "luts" / "sensors" / "smartphone-1.4um.yaml"


def test_a_dict_or_list_that_contains_itself_is_an_input_error():
    d = {"camera": {}}
    d["camera"]["self"] = d  # a segfault: the C++ stack overflowed
    with pytest.raises(camsim.InputError, match=r"nested more than 400 levels deep") as info:
        camsim.Scene.from_dict(d)
    assert info.value.file == "<dict>" and info.value.key.startswith("camera.self.camera")
    assert len(info.value.key) < 200  # the path up to the limit, not 500 levels of it
    loop = []
    loop.append(loop)
    with pytest.raises(camsim.InputError, match=r"does a dict or list contain itself"):
        camsim.Scene.from_dict({"shapes": loop})


def test_text_that_is_not_unicode_names_its_key():
    with pytest.raises(camsim.InputError, match=r"<dict>: key 'name': is not valid Unicode"):
        camsim.Scene.from_dict({"name": "caf\udce9"})
    with pytest.raises(camsim.InputError, match=r"key 'projection': is not valid Unicode"):
        camsim.default_scene().render(threads=1, spp=1, projection="\udce9")


def test_paths_are_str_bytes_or_path_like_without_nul(tmp_path):
    scene = SOURCE / "scenes" / "cornell_box.yaml"
    for path in (str(scene), scene, os.fsencode(scene)):
        assert camsim.load(path).source_file == str(scene)
    with pytest.raises(camsim.InputError, match=r"<load>: key 'path': a path cannot contain a NUL"):
        camsim.load(str(scene) + "\x00ignored")  # it loaded the file before the NUL
    with pytest.raises(camsim.InputError, match=r"<load>: key 'path': expected a path .* got int"):
        camsim.load(3)
    with pytest.raises(camsim.InputError, match=r"<read_exr>: key 'path': a path cannot"):
        camsim.read_exr(str(tmp_path / "a.exr") + "\x00.exr")
    # A file whose name is not UTF-8 opens through its bytes; errors show it as os.fsdecode.
    odd = os.fsencode(tmp_path) + b"/box_\xff.yaml"
    with open(odd, "wb") as f:
        f.write(scene.read_bytes())
    assert camsim.load(odd).source_file == os.fsdecode(odd)
    with pytest.raises(camsim.InputError) as info:
        camsim.load(os.fsencode(tmp_path) + b"/missing_\xff.yaml")
    assert info.value.file == os.fsdecode(os.fsencode(tmp_path) + b"/missing_\xff.yaml")


def test_a_sensor_may_be_a_path_object():
    by_name = camsim.Sensor("smartphone-1.4um")
    by_path = camsim.Sensor(SENSOR_FILE)
    assert by_path.full_well_e == by_name.full_well_e
    with pytest.raises(camsim.InputError, match=r"<Sensor>: key 'name_or_path': a path cannot"):
        camsim.Sensor("smartphone-1.4um\x00")
    box = camsim.default_scene(overrides={"spp": 1})
    box.set_sensor(SENSOR_FILE)
    assert camsim.Sensor.of(box).full_well_e == by_name.full_well_e


def test_develop_region_sums_past_32_bits_are_outside_the_image():
    sensor = camsim.Sensor("smartphone-1.4um")
    raw = np.full((8, 8), 300, np.uint16)
    big = 2**31 - 1
    for region in [(big - 1, big - 1, big, big), (big, 0, 2, 2)]:  # a segfault; a wrong message
        with pytest.raises(camsim.InputError, match=r"<develop>: key 'region': extends outside"):
            camsim.develop(raw, sensor, white_balance="region", region=region)
    # The ISP's own errors name develop (they said "<input>").
    with pytest.raises(camsim.InputError, match=r"^<develop>: key 'white_balance'"):
        camsim.develop(np.full((4, 4), 64, np.uint16), sensor, white_balance="grey_world")


def test_max_memory_gb_takes_numpy_numbers():
    # np.float32 was refused as "expected a number of GB": now the estimate and the range
    # decide (messages the old code did not give for these).
    scene = camsim.default_scene(overrides={"spp": 1})
    with pytest.raises(camsim.InputError, match=r"needs an estimated .* set by max_memory_gb"):
        camsim.capture(scene, threads=1, max_memory_gb=np.float32(0.001))
    with pytest.raises(camsim.InputError, match=r"max_memory_gb.*must be a number of GB in \(0,"):
        camsim.capture(scene, threads=1, max_memory_gb=np.int64(0))


def test_noise_is_a_str_and_names_non_utf8_files_decode():
    with pytest.raises(camsim.InputError, match=r"key 'noise'.*expected a str, got bytes"):
        camsim.default_scene().render(threads=1, spp=1, noise=b"full")
    with pytest.raises(camsim.InputError, match=r"<load>: key 'path': the path is not valid"):
        camsim.load("\ud800.yaml")


def test_frame_counts_are_integers_named_as_frames():
    # frames=True gave one frame; 2**70 and 2.0 raised pybind11's TypeError.
    sensor = camsim.Sensor("smartphone-1.4um")
    electrons = np.full((4, 4), 100.0)
    for frames in (True, 2**70, 2.0, 0, 100001):
        with pytest.raises(camsim.InputError, match=r"^<expose>: key 'frames'"):
            camsim.expose(electrons, sensor, seed=1, frames=frames)
    assert camsim.expose(electrons, sensor, seed=1, frames=np.int64(2)).shape == (2, 4, 4)
    for frames in (True, 2**70, 2.0):
        with pytest.raises(camsim.InputError, match=r"<expose_file>: key 'frames'"):
            camsim.expose_file("unused_raw.exr", frames=frames)
