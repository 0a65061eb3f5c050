"""Scenes that aborted the interpreter inside Embree (issue 34): a keyframed shape under a
short shutter that does not start at 0, and a 24 fps sequence from frame 36 with an 8.64°
shutter, render with finite pixels; a camera `up` of zero raises camsim.InputError naming
the key instead of aborting."""
import numpy as np
import pytest

import camsim


def short_shutter(open_s, close_s, frames=None):
    d = {
        "format": "camsim-scene/1",
        "name": "short_shutter",
        "render": {"spp": 16, "max_depth": 1},
        "camera": {"position": [0, 0, 5], "look_at": [0, 0, 0], "resolution": [64, 64],
                   "shutter": {"open": open_s, "close": close_s}},
        "lights": [{"type": "distant", "direction": [0, 0, -1], "illuminance": 1000}],
        "materials": {"m": {"type": "diffuse", "reflectance": 0.5}},
        "shapes": [{"name": "q", "type": "mesh", "material": "m",
                    "vertices": [[-0.5, -0.5, 0], [0.5, -0.5, 0], [0.5, 0.5, 0], [-0.5, 0.5, 0]],
                    "faces": [[0, 1, 2, 3]],
                    "motion": [{"time": 1.25, "translate": [0, 0, 0]},
                               {"time": 2.5, "translate": [0, 2, 0]}]}],
    }
    if frames:
        d["frames"] = frames
    return d


@pytest.mark.parametrize("window", [(1.5, 1.501), (1.5625, 1.5635), (0.0, 1e-45)])
def test_short_shutter_after_zero_renders(window):
    xyz = camsim.Scene.from_dict(short_shutter(*window)).render()["xyz"]
    assert np.isfinite(xyz).all()
    if window[1] - window[0] > 1e-30:
        assert xyz.sum() > 0


def test_sequence_from_frame_36_renders():
    frames = camsim.Scene.from_dict(short_shutter(0.0, 0.01, {
        "first": 36, "count": 2, "rate_hz": 24, "shutter_angle_deg": 8.64})).render()
    assert len(frames) == 2
    for f in frames:
        assert np.isfinite(f["xyz"]).all() and f["xyz"].sum() > 0


def test_zero_up_raises_input_error():
    d = short_shutter(0.0, 0.01)
    d["camera"]["up"] = [0, 0, 0]
    with pytest.raises(camsim.InputError, match=r"camera\.up"):
        camsim.Scene.from_dict(d)
