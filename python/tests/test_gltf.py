"""glTF assets through the Python module: a scene that includes a glTF file loads and
renders, reports the loader's notes, and a malformed asset raises camsim.InputError naming
the file and the JSON path (the same text as the CLI's exit-2 message)."""
import pathlib

import numpy as np
import pytest

import camsim

GLTF = pathlib.Path(__file__).resolve().parents[2] / "tests" / "data" / "gltf"


def cube_scene():
    return {
        "render": {"spp": 2, "seed": 1},
        "camera": {"position": [0, 0, 4], "look_at": [0, 0, 0], "resolution": [32, 24]},
        "include": [{"gltf": str(GLTF / "Cube" / "Cube.gltf"), "scale": 0.8}],
        "lights": [{"type": "point", "position": [0, 0, 4], "intensity": 50}],
    }


def test_gltf_cube_renders_and_lists_its_files():
    scene = camsim.Scene.from_dict(cube_scene())
    assert any(f.endswith("Cube_BaseColor.png") for f in scene.input_files)
    result = scene.render(threads=1)
    xyz = np.asarray(result["xyz"])
    assert np.isfinite(xyz).all()
    assert xyz[12, 16, 1] > 0.0  # the cube fills the image centre


def test_gltf_notes_are_exposed():
    scene = camsim.Scene.from_dict({
        "render": {"spp": 1},
        "camera": {"gltf": {"camera": 0}, "resolution": [16, 12]},
        "include": [{"gltf": str(GLTF / "khronos" / "Cameras.gltf")}],
    })
    assert any("aspectRatio" in n for n in scene.notes)


def test_malformed_gltf_raises_input_error_with_json_path():
    d = cube_scene()
    d["include"] = [{"gltf": str(GLTF / "BoundsChecking" / "integer-out-of-bounds.gltf")}]
    with pytest.raises(camsim.InputError, match=r"integer-out-of-bounds\.gltf: key 'bufferViews\[0\]\.byteLength'"):
        camsim.Scene.from_dict(d)
