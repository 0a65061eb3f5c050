#!/usr/bin/python3
"""A randomised 20-capture dataset with ground truth, written to disk with its metadata.

The Cornell box seen by the smartphone sensor, loaded once; each capture draws a camera
position on an orbit around the box's centre, an exposure time (log-uniform 2-16 ms) and an
ISO, then renders with depth, normals and instance ids. Per capture DIR/NNNN/ gets:
  image.png       the display picture (OpenColorIO sRGB, the CLI's PNG bytes)
  raw.npy         raw DN, uint16 (H, W), RGGB mosaic, black level included
  gt.npz          depth (m, camera-space z), normal (world, unit), instance (uint32 id)
  meta.json       the capture's metadata (camsim's sidecar: exposure, sensor, pose,
                  OpenCV intrinsics) plus the drawn parameters
and DIR/transforms.json lists every frame NeRF-style (fl_x, fl_y, cx, cy, w, h; per frame
file_path and the OpenGL/Blender camera-to-world matrix, m).

Run (from the repository, after README's first command):
  PYTHONPATH=build/python /usr/bin/python3 examples/python/random_dataset.py out/py_dataset
Options: --count N (20), --size PX (128), --spp N (16), --seed S (0), --threads N (0: all).
The same seed gives the same dataset, byte for byte, on any thread count.
"""
import argparse
import json
import math
import pathlib
import sys
import time

import numpy as np
import yaml

import camsim

ROOT = pathlib.Path(__file__).resolve().parents[2]
SCENE = ROOT / "scenes" / "cornell_box_smartphone.yaml"
CENTRE = np.array([0.278, 0.273, 0.280])  # m, the middle of the box


def base_scene(size, spp):
    """The scene file at size x size px (focal length scaled to keep the field of view),
    with auto-exposure off so that each capture's exposure time is the drawn one."""
    d = yaml.safe_load(SCENE.read_text())
    full = d["camera"]["resolution"][0]
    d["camera"]["resolution"] = [size, size]
    d["camera"]["focal_length_mm"] *= size / full
    d["render"]["spp"] = spp
    d["render"]["aovs"] = ["depth", "normal", "instance_id"]
    del d["sensor"]["auto_exposure"]
    return camsim.Scene.from_dict(d, base_dir=SCENE.parent)


def orbit(rng):
    """A camera position 1.0-1.2 m from the box centre, -25..25 deg around it, -10..15 deg up."""
    radius = rng.uniform(1.0, 1.2)
    az, el = np.radians(rng.uniform(-25, 25)), np.radians(rng.uniform(-10, 15))
    offset = radius * np.array([math.sin(az) * math.cos(el), math.sin(el),
                                -math.cos(az) * math.cos(el)])
    return CENTRE + offset


def opengl_from_opencv(world_from_cv):
    """x right, y down, z forward (OpenCV) -> x right, y up, z backward (OpenGL/Blender)."""
    return np.asarray(world_from_cv) @ np.diag([1.0, -1.0, -1.0, 1.0])


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out", type=pathlib.Path)
    ap.add_argument("--count", type=int, default=20)
    ap.add_argument("--size", type=int, default=128)
    ap.add_argument("--spp", type=int, default=16)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--threads", type=int, default=0)
    args = ap.parse_args()
    import matplotlib.pyplot as plt  # only to write PNGs

    scene = base_scene(args.size, args.spp)
    rng = np.random.default_rng(args.seed)
    args.out.mkdir(parents=True, exist_ok=True)
    frames, start = [], time.monotonic()
    for i in range(args.count):
        params = {"position_m": orbit(rng).tolist(),
                  "exposure_time_s": float(math.exp(rng.uniform(math.log(0.002), math.log(0.016)))),
                  "iso": int(rng.choice([100, 200, 400]))}
        scene.set_pose(position=params["position_m"], look_at=CENTRE.tolist())
        scene.set_exposure(exposure_time_s=params["exposure_time_s"], iso=params["iso"])
        scene.set_seed(args.seed * 100003 + i, noise_seed=args.seed * 100003 + i + 1)
        r = scene.render(threads=args.threads)
        item = args.out / f"{i:04d}"
        item.mkdir(exist_ok=True)
        plt.imsave(item / "image.png", r["display8"])
        np.save(item / "raw.npy", r["raw"])
        aovs = r["aovs"]
        np.savez_compressed(item / "gt.npz", depth=aovs["depth"], normal=aovs["N"],
                            instance=aovs["instance"])
        meta = dict(r["meta"], parameters=params)
        (item / "meta.json").write_text(json.dumps(meta, indent=1))
        fx, fy, cx, cy = meta["pose"]["opencv_fx_fy_cx_cy"]
        frames.append({"file_path": f"{i:04d}/image.png",
                       "transform_matrix": opengl_from_opencv(meta["pose"]["world_from_camera_opencv"]).tolist(),
                       "fl_x": fx, "fl_y": fy, "cx": cx, "cy": cy})
        print(f"\r{i + 1}/{args.count} captures, {time.monotonic() - start:.1f} s",
              end="", file=sys.stderr, flush=True)
    print(file=sys.stderr)
    first = frames[0]
    transforms = {"w": args.size, "h": args.size, "fl_x": first["fl_x"], "fl_y": first["fl_y"],
                  "cx": first["cx"], "cy": first["cy"], "k1": 0.0, "k2": 0.0, "p1": 0.0, "p2": 0.0,
                  "frames": [{"file_path": f["file_path"], "transform_matrix": f["transform_matrix"]}
                             for f in frames]}
    (args.out / "transforms.json").write_text(json.dumps(transforms, indent=1))
    print(f"{args.count} captures in {args.out}", file=sys.stderr)


if __name__ == "__main__":
    main()
