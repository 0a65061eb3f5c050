#!/usr/bin/python3
"""Captures per second: one Python process against one `camsim render` process per capture.

The same N captures (default 200) of the smartphone Cornell box at 128 x 128 px, 4 spp,
each with its own camera position (an orbit around the box) and exposure time (2-16 ms,
log-uniform), auto-exposure off:
  python   one process: the scene loaded once, then set_pose / set_exposure / set_seed and
           scene.render() per capture; arrays in memory, no files written
  cli      per capture a scene file with that pose, then `camsim render FILE -o DIR
           --exposure-time T --seed S` (a new process that loads the scene and writes its
           files: EXR, raw EXR, DNG, PNG, JSON)
Both at --threads (default 0: all cores). The error column: the first --check captures'
Python arrays against the CLI's files (XYZ EXR channels and raw DN): how many values
differ and the largest XYZ difference relative to the image's maximum (a pose set on a
loaded scene keeps its render origin, so a moved camera matches a reloaded scene to float
rounding, docs/python.md); the script fails above 1e-4.

  PYTHONPATH=build/python /usr/bin/python3 bench/python_capture_rate.py --camsim build/camsim
Prints a table: wall time, captures/s, the ratio, and the differing values.
"""
import argparse
import math
import pathlib
import subprocess
import tempfile
import time

import numpy as np
import yaml

import camsim

ROOT = pathlib.Path(__file__).resolve().parents[1]
SCENE = ROOT / "scenes" / "cornell_box_smartphone.yaml"
CENTRE = [0.278, 0.273, 0.280]


def scene_dict(size, spp):
    d = yaml.safe_load(SCENE.read_text())
    full = d["camera"]["resolution"][0]
    d["camera"]["resolution"] = [size, size]
    d["camera"]["focal_length_mm"] *= size / full
    d["render"]["spp"] = spp
    del d["sensor"]["auto_exposure"]
    return d


def draws(n, seed=0):
    rng = np.random.default_rng(seed)
    out = []
    for i in range(n):
        r = rng.uniform(1.0, 1.2)
        az, el = math.radians(rng.uniform(-25, 25)), math.radians(rng.uniform(-10, 15))
        pos = [CENTRE[0] + r * math.sin(az) * math.cos(el), CENTRE[1] + r * math.sin(el),
               CENTRE[2] - r * math.cos(az) * math.cos(el)]
        t = math.exp(rng.uniform(math.log(0.002), math.log(0.016)))
        out.append({"position": pos, "exposure_time_s": t, "seed": i})
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--camsim", type=pathlib.Path, default=ROOT / "build" / "camsim")
    ap.add_argument("--count", type=int, default=200)
    ap.add_argument("--size", type=int, default=128)
    ap.add_argument("--spp", type=int, default=4)
    ap.add_argument("--threads", type=int, default=0)
    ap.add_argument("--check", type=int, default=3)
    args = ap.parse_args()
    d = scene_dict(args.size, args.spp)
    items = draws(args.count)

    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        # One Python process (this one): load once, override per capture.
        start = time.perf_counter()
        scene = camsim.Scene.from_dict(d, base_dir=SCENE.parent)
        kept = []
        for i, it in enumerate(items):
            scene.set_pose(position=it["position"], look_at=CENTRE)
            scene.set_exposure(exposure_time_s=it["exposure_time_s"])
            scene.set_seed(it["seed"])
            r = scene.render(threads=args.threads)
            if i < args.check:
                kept.append((r["xyz"].copy(), r["raw"].copy()))
        t_py = time.perf_counter() - start

        # One camsim render process per capture (scene files written beforehand, untimed).
        files = []
        for i, it in enumerate(items):
            di = dict(d, camera=dict(d["camera"], position=it["position"], look_at=CENTRE))
            f = tmp / f"item{i:04d}.yaml"
            f.write_text(yaml.safe_dump(di))
            files.append(f)
        start = time.perf_counter()
        for i, (it, f) in enumerate(zip(items, files)):
            cmd = [str(args.camsim), "render", str(f), "-o", str(tmp / f"out{i:04d}"),
                   "--exposure-time", repr(it["exposure_time_s"]), "--seed", str(it["seed"])]
            if args.threads > 0:  # the CLI's default is all cores; it takes no --threads 0
                cmd += ["--threads", str(args.threads)]
            subprocess.run(cmd, check=True, capture_output=True)
        t_cli = time.perf_counter() - start

        differing, values, worst = 0, 0, 0.0
        for i, (xyz, raw) in enumerate(kept):
            stem = tmp / f"out{i:04d}" / d["name"]
            ch = camsim.read_exr(f"{stem}.exr")["channels"]
            cli = np.stack([ch[n] for n in ("XYZ.X", "XYZ.Y", "XYZ.Z")], axis=-1)
            differing += int(np.count_nonzero(xyz != cli))
            values += xyz.size
            worst = max(worst, float(np.max(np.abs(xyz - cli)) / max(float(np.max(cli)), 1e-30)))
            rch = camsim.read_exr(f"{stem}_raw.exr")["channels"]
            differing += int(np.count_nonzero(raw != rch["raw.DN"].astype(np.uint16)))
            values += raw.size

    n = args.count
    print(f"{n} captures, {args.size}x{args.size} px, {args.spp} spp, threads {args.threads}")
    print(f"{'mode':<28}{'wall s':>9}{'captures/s':>12}")
    print(f"{'python, one process':<28}{t_py:>9.2f}{n / t_py:>12.1f}")
    print(f"{'camsim render per capture':<28}{t_cli:>9.2f}{n / t_cli:>12.1f}")
    print(f"ratio {t_cli / t_py:.2f}x; first {len(kept)} captures against the CLI's files: "
          f"{differing} of {values} values differ (XYZ, raw DN), largest XYZ difference "
          f"{worst:.2e} of the image's maximum")
    return 0 if worst < 1e-4 else 1


if __name__ == "__main__":
    raise SystemExit(main())
