"""Shared fixtures of the camsim Python tests (run by CTest as Python.Pytest, or by hand:
PYTHONPATH=<build>/python CAMSIM_BINARY=<build>/camsim \
CAMSIM_SCENE_ERROR_CASES=<build>/tests/scene_error_cases /usr/bin/python3 -m pytest python/tests).
"""
import os
import pathlib
import subprocess

import pytest

DATA = pathlib.Path(__file__).parent / "data"
BOX = DATA / "box_sensor.yaml"


def _required_env(name):
    value = os.environ.get(name)
    if not value:
        pytest.fail(f"${name} is not set (CTest sets it; see conftest.py)")
    return value


@pytest.fixture(scope="session")
def camsim_binary():
    return _required_env("CAMSIM_BINARY")


@pytest.fixture(scope="session")
def cli_box(camsim_binary, tmp_path_factory):
    """The files `camsim render` writes for the test box at --seed 3, with one thread."""
    out = tmp_path_factory.mktemp("cli_box")
    subprocess.run([camsim_binary, "render", str(BOX), "-o", str(out), "--seed", "3",
                    "--threads", "1", "--reproducible"], check=True, capture_output=True)
    return out


def small_scene(seed=0, spp=1, resolution=(16, 12), radius=0.4):
    """A sensorless sphere under a point light, as a dict (tiny: for many-capture tests)."""
    return {
        "render": {"spp": spp, "seed": seed},
        "camera": {"position": [0, 0, -3], "look_at": [0, 0, 0], "resolution": list(resolution)},
        "materials": {"m": {"type": "diffuse", "reflectance": 0.5}},
        "shapes": [{"type": "sphere", "centre": [0, 0, 0], "radius": radius, "material": "m"}],
        "lights": [{"type": "point", "position": [0, 2, -2], "intensity": 100}],
    }
