"""The examples in examples/python/ run as a user runs them, and say something true:
- random_dataset.py writes every capture's picture, raw, ground truth and metadata, and a
  transforms.json whose intrinsics and camera-to-world matrices agree with each capture's
  meta (OpenGL = OpenCV with y and z negated), the same bytes for the same seed;
- photon_transfer.py fits the system gain K from expose() frames of one render within 3 %
  of the sensor's configured K (it exits 1 otherwise) and writes its plot.
"""
import json
import os
import pathlib
import subprocess
import sys

import numpy as np

EXAMPLES = pathlib.Path(__file__).resolve().parents[2] / "examples" / "python"


def run(script, *args):
    return subprocess.run([sys.executable, str(EXAMPLES / script), *map(str, args)],
                          env=dict(os.environ, MPLBACKEND="Agg"), capture_output=True,
                          text=True, check=False)


def test_random_dataset_writes_consistent_items(tmp_path):
    out = tmp_path / "ds"
    p = run("random_dataset.py", out, "--count", 3, "--size", 32, "--spp", 2, "--threads", 2)
    assert p.returncode == 0, p.stderr
    transforms = json.loads((out / "transforms.json").read_text())
    assert transforms["w"] == 32 and len(transforms["frames"]) == 3
    for i, frame in enumerate(transforms["frames"]):
        item = out / f"{i:04d}"
        assert frame["file_path"] == f"{i:04d}/image.png" and (out / frame["file_path"]).stat().st_size > 0
        meta = json.loads((item / "meta.json").read_text())
        cv = np.array(meta["pose"]["world_from_camera_opencv"])
        np.testing.assert_allclose(np.array(frame["transform_matrix"]), cv @ np.diag([1, -1, -1, 1]))
        np.testing.assert_allclose(cv[:3, 3], meta["parameters"]["position_m"], atol=1e-9)
        assert np.load(item / "raw.npy").dtype == np.uint16
        gt = np.load(item / "gt.npz")
        assert gt["depth"].shape == (32, 32) and gt["instance"].dtype == np.uint32
    again = tmp_path / "again"
    assert run("random_dataset.py", again, "--count", 3, "--size", 32, "--spp", 2,
               "--threads", 1).returncode == 0
    for name in ("0002/raw.npy", "0002/gt.npz", "0002/image.png"):
        assert (out / name).read_bytes() == (again / name).read_bytes(), name


def test_photon_transfer_recovers_the_system_gain(tmp_path):
    p = run("photon_transfer.py", tmp_path, "--frames", 16, "--levels", 10, "--threads", 2)
    assert p.returncode == 0, p.stdout + p.stderr
    assert "fitted K" in p.stdout and (tmp_path / "ptc.png").stat().st_size > 0
