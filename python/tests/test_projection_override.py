"""The camera model as an override (issue 36, item 6): Scene.set_projection, the projection
keyword of capture()/Scene.render() and the overrides dict set camera.projection on a loaded
scene through the library's override table (integrator/scene/overrides.h), checked by the
scene loader.

The scene: a lamp (an emissive sphere of radius 2 at 3 m) that fills the view of the
scene's own pinhole (32 × 32 px, fx = 33.6 / 24 · 32 = 44.8 px, ±19.6°). Through an
equidistant fisheye imaging up to 15° the image is a disc of radius fx · 15° = 11.73 px about
(cx, cy) = (15.5, 15.5) (pixel centres at integers): black outside, lit inside, and the
valid AOV is 1 inside and 0 outside, its sum the disc's area.
"""
import math

import numpy as np
import pytest

import camsim

FISHEYE = {"model": "equidistant", "max_field_angle_deg": 15}
RADIUS = 44.8 * math.radians(15)


def lamp(spp=4):
    return {
        "name": "lamp",
        "render": {"spp": spp, "aovs": ["valid"]},
        "camera": {"position": [0, 0, -3], "look_at": [0, 0, 0], "resolution": [32, 32],
                   "sensor_width_mm": 24, "sensor_height_mm": 24, "focal_length_mm": 33.6},
        "materials": {"m": {"type": "diffuse", "reflectance": 0.5}},
        "shapes": [{"type": "sphere", "centre": [0, 0, 0], "radius": 2, "material": "m",
                    "emission": {"luminance": 100}}],
    }


def pixel_distances():
    """Each pixel's nearest and farthest distance from the image circle's centre."""
    y, x = np.mgrid[0:32, 0:32].astype(float)
    dx, dy = np.abs(x - 15.5), np.abs(y - 15.5)
    near = np.hypot(np.maximum(dx - 0.5, 0), np.maximum(dy - 0.5, 0))
    far = np.hypot(dx + 0.5, dy + 0.5)
    return near, far


def check_fisheye(frame):
    luminance = frame["rgb"].sum(axis=2)
    valid = frame["aovs"]["valid"]
    near, far = pixel_distances()
    outside, inside = near > RADIUS, far < RADIUS
    assert outside.sum() > 400 and inside.sum() > 300
    assert np.all(luminance[outside] == 0) and np.all(valid[outside] == 0)
    assert np.all(luminance[inside] > 0) and np.all(valid[inside] == 1)
    # The valid fraction's sum is the disc's area (432.3 px²); 4 spp on ~80 edge pixels.
    assert valid.sum() == pytest.approx(math.pi * RADIUS**2, rel=0.03)


def test_set_projection_renders_through_the_model():
    scene = camsim.Scene.from_dict(lamp())
    own = camsim.capture(scene)
    assert np.all(own["rgb"].sum(axis=2) > 0) and np.all(own["aovs"]["valid"] == 1)
    assert scene.set_projection(FISHEYE) is scene
    check_fisheye(camsim.capture(scene))


def test_keyword_dict_and_text_agree():
    scene = camsim.Scene.from_dict(lamp())
    by_keyword = camsim.capture(scene, projection=FISHEYE)
    check_fisheye(by_keyword)
    # For that capture only: the scene keeps its own pinhole.
    assert np.all(scene.render()["aovs"]["valid"] == 1)
    # The same model as YAML text through load()'s overrides dict, and as JSON text with
    # NumPy numbers through set_projection: the same bytes, reused or built afresh.
    text = camsim.Scene.from_dict(
        lamp(), overrides={"projection": "{model: equidistant, max_field_angle_deg: 15}"})
    np.testing.assert_array_equal(text.render()["rgb"], by_keyword["rgb"])
    numpy = camsim.Scene.from_dict(lamp()).set_projection(
        {"model": "equidistant", "max_field_angle_deg": np.float32(15)})
    np.testing.assert_array_equal(numpy.render(reuse=False)["rgb"], by_keyword["rgb"])
    np.testing.assert_array_equal(numpy.render()["rgb"], by_keyword["rgb"])


def test_kannala_brandt_with_calibrated_intrinsics():
    scene = camsim.Scene.from_dict(lamp()).set_projection(
        {"model": "kannala_brandt", "k1": 0.02, "k2": -0.003, "max_field_angle_deg": 10,
         "fx": 60, "fy": 60, "cx": 12.5, "cy": 18.5})
    valid = scene.render()["aovs"]["valid"]
    # The disc now sits about (12.5, 18.5): ρ = θ(1 + k1θ² + k2θ⁴) at 10°, times 60 px.
    theta = math.radians(10)
    r = 60 * theta * (1 + 0.02 * theta**2 - 0.003 * theta**4)
    assert valid.sum() == pytest.approx(math.pi * r**2, rel=0.05)
    y, x = np.mgrid[0:32, 0:32]
    assert np.average(x, weights=valid) == pytest.approx(12.5, abs=0.1)
    assert np.average(y, weights=valid) == pytest.approx(18.5, abs=0.1)


@pytest.mark.parametrize("value,key,detail", [
    ({"model": "fisheye9"}, "camera.projection.model", "unknown projection model 'fisheye9'"),
    ({"model": "opencv", "k1": 2000}, "camera.projection.k1", "out of range"),
    ({"model": "opencv", "kk": 1}, "camera.projection.kk", "unknown key"),
    ({"model": "opencv", "fx": 1, "fy": 1, "cx": 1}, "camera.projection", "all four"),
    ({"model": "opencv", "k1": "big"}, "camera.projection.k1", ""),
    ("{model: opencv", "camera.projection", "syntax"),
])
def test_bad_projection_names_the_key(value, key, detail):
    for apply in (lambda s: s.set_projection(value),
                  lambda s: camsim.capture(s, projection=value, display="none")):
        scene = camsim.Scene.from_dict(lamp())
        with pytest.raises(camsim.InputError, match=detail) as e:
            apply(scene)
        assert e.value.key == key
        assert scene.render()["aovs"]["valid"].min() == 1  # the scene unchanged


def test_wrong_type_and_flat_pupil():
    with pytest.raises(camsim.InputError, match="expected a dict") as e:
        camsim.capture(camsim.Scene.from_dict(lamp()), projection=5)
    assert e.value.key == "projection"
    flat = lamp()
    flat["camera"]["aperture"] = {"pupil": "flat"}
    with pytest.raises(camsim.InputError, match="flat") as e:
        camsim.Scene.from_dict(flat).set_projection(FISHEYE)
    assert e.value.key == "camera.projection.model"


def test_an_array_value_is_refused_without_a_traceback():
    # Found by probing: the message carried json/encoder.py's traceback frames.
    import numpy as np
    with pytest.raises(camsim.InputError, match=r"neither a str nor a number \(TypeError: ") as e:
        camsim.capture(camsim.Scene.from_dict(lamp()),
                       projection={"model": "kannala_brandt", "k1": np.array([0.02, 1])})
    assert e.value.key == "projection"
    assert "encoder.py" not in str(e.value) and "At:" not in str(e.value), str(e.value)


def test_override_settings_reports_the_type():
    s = next(s for s in camsim.override_settings() if s["key"] == "projection")
    assert (s["type"], s["scene_key"], s["flag"]) == ("projection", "camera.projection",
                                                      "--projection")
