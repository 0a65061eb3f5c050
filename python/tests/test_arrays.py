"""Arrays from Python equal, bit for bit, what `camsim render` writes for the same scene and
seed (the CLI at one thread, Python at two: the bytes do not depend on the thread count),
and they view camsim's buffers without a copy."""
import json
import subprocess

import numpy as np
import pytest

import camsim
from conftest import BOX, small_scene


@pytest.fixture(scope="module")
def py_box():
    return camsim.load(BOX, overrides={"seed": 3}).render(threads=2)


def exr(path):
    return camsim.read_exr(path)["channels"]


def test_film_layers_equal_the_cli_exr(cli_box, py_box):
    ch = exr(cli_box / "box_sensor.exr")
    for i, c in enumerate("RGB"):
        np.testing.assert_array_equal(py_box["rgb"][..., i], ch[c])
    for i, c in enumerate("XYZ"):
        np.testing.assert_array_equal(py_box["xyz"][..., i], ch["XYZ." + c])
    aovs = py_box["aovs"]
    np.testing.assert_array_equal(aovs["depth"], ch["depth.Z"])
    for i, c in enumerate("XYZ"):
        np.testing.assert_array_equal(aovs["N"][..., i], ch["N." + c])
    assert aovs["instance"].dtype == np.uint32
    np.testing.assert_array_equal(aovs["instance"], ch["instance.id"].astype(np.uint32))
    assert aovs["instance"].max() > 0  # the shapes are seen


def test_raw_electrons_acescg_and_picture_equal_the_cli_files(cli_box, py_box):
    assert [b["ev"] for b in py_box["brackets"]] == [-1.0, 0.0]
    for b, stem in zip(py_box["brackets"], ("box_sensor_ev-1", "box_sensor_ev+0")):
        raw = exr(cli_box / f"{stem}_raw.exr")
        assert b["raw"].dtype == np.uint16 and b["raw"].shape == (40, 48)
        np.testing.assert_array_equal(b["raw"], raw["raw.DN"].astype(np.uint16))
        np.testing.assert_array_equal(b["electrons"], raw["electrons.electrons"])  # mosaic: one channel
    assert py_box["raw"] is not None and py_box["meta"]["reference_frame"] == 1
    acescg = exr(cli_box / "box_sensor_acescg.exr")
    for i, c in enumerate("RGB"):
        np.testing.assert_array_equal(py_box["acescg"][..., i], acescg[c])
    png = camsim.read_png(cli_box / "box_sensor.png")
    np.testing.assert_array_equal(py_box["display8"], png[..., :3])


def test_meta_is_the_cli_sidecar(cli_box, py_box):
    sidecar = json.loads((cli_box / "box_sensor.json").read_text())
    meta = dict(py_box["meta"])
    for key in ("pose", "color", "reference_frame", "threads", "render_seconds", "scene_reused"):
        meta.pop(key)
    sidecar.pop("color")
    assert meta == sidecar
    assert "modelled" in meta["render"] and len(meta["camera"]["derived"]["opencv_fx_fy_cx_cy"]) == 4
    assert np.asarray(py_box["meta"]["pose"]["world_from_camera_opencv"]).shape == (4, 4)
    # The camera model as cameras.json writes it (integrator/capture/camera_export.h).
    projection = py_box["meta"]["pose"]["projection"]
    assert projection["model"] == "opencv" and projection == meta["camera"]["derived"]["projection"]
    assert list(projection)[1:6] == ["k1", "k2", "p1", "p2", "k3"]


def test_meta_says_none_for_what_a_capture_does_not_have(py_box):
    # Issue 34: without a sensor the pose gave ISO and gain 0, and focus at infinity was
    # written as a focus distance of 0 m.
    meta = camsim.Scene.from_dict(small_scene()).render()["meta"]
    assert meta["pose"]["iso"] is None
    assert meta["pose"]["system_gain_dn_per_e"] is None
    derived = meta["camera"]["derived"]  # the scene inputs hold no focus_distance_m then
    assert "focus_distance_m" not in meta["camera"]
    assert derived["focus_distance_m"] is None  # no focus_distance_m: infinity
    assert derived["image_distance_m"] == derived["focal_length_m"]
    pose = py_box["meta"]["pose"]  # with a sensor: its ISO and gain
    assert pose["iso"] == py_box["meta"]["sensor"]["iso"] > 0
    assert pose["system_gain_dn_per_e"] == py_box["meta"]["sensor"]["derived"]["system_gain_dn_per_e"] > 0
    focused = small_scene()
    focused["camera"].update({"f_number": 2, "focus_distance_m": 3})
    meta = camsim.Scene.from_dict(focused).render()["meta"]
    assert meta["camera"]["focus_distance_m"] == meta["camera"]["derived"]["focus_distance_m"] == 3


def test_arrays_view_the_capture_without_copies(py_box):
    rgb, xyz = py_box["rgb"], py_box["xyz"]
    assert rgb.dtype == np.float32 and rgb.shape == (40, 48, 3)
    assert not rgb.flags.owndata and not xyz.flags.owndata
    # rgb is a view into the interleaved R, G, B, X, Y, Z image the EXR writer writes.
    assert rgb.strides == (48 * 6 * 4, 6 * 4, 4)
    assert type(rgb.base).__name__ == "PyCapsule"
    depth = py_box["aovs"]["depth"]
    assert depth.base is not None and not depth.flags.owndata


def test_arrays_outlive_their_dict():
    result = camsim.load(BOX, overrides={"spp": 1}).render(threads=1)
    raw, expected = result["raw"], result["raw"].copy()
    del result
    np.testing.assert_array_equal(raw, expected)


def test_overrides_equal_the_cli_flags(camsim_binary, tmp_path):
    subprocess.run([camsim_binary, "render", str(BOX), "-o", str(tmp_path), "--seed", "5",
                    "--spp", "2", "--exposure-time", "0.01", "--f-number", "2.8", "--iso",
                    "800", "--noise", "photon", "--noise-seed", "9", "--reproducible"],
                   check=True, capture_output=True)
    scene = camsim.load(BOX, overrides={"seed": 5, "spp": 2, "exposure_time_s": 0.01,
                                        "f_number": 2.8, "iso": 800, "noise": "photon",
                                        "noise_seed": 9})
    r = scene.render()
    np.testing.assert_array_equal(r["xyz"][..., 1], exr(tmp_path / "box_sensor.exr")["XYZ.Y"])
    np.testing.assert_array_equal(r["raw"], exr(tmp_path / "box_sensor_ev+0_raw.exr")["raw.DN"])
    # The same through the Scene methods on a scene loaded without overrides.
    s2 = camsim.load(BOX, overrides={"noise": "photon"}).set_seed(5, noise_seed=9).set_spp(2)
    s2.set_exposure(exposure_time_s=0.01, f_number=2.8, iso=800)
    np.testing.assert_array_equal(camsim.capture(s2)["raw"], r["raw"])
