#!/usr/bin/env python3
"""The low-light pair of docs/examples.md: one render, its noise-free electrons developed,
and one noisy raw made from them by `camsim expose` at ISO 6400, developed the same way.

Usage: scripts/make_lowlight_figures.py BUILD_DIR [OUT_DIR]
  BUILD_DIR: a camsim build (BUILD_DIR/camsim and BUILD_DIR/python/camsim*.so)
  OUT_DIR:   where the PNG goes (default docs/images)

Runs: camsim render scenes/lowlight_cornell_a7s2.yaml (64 spp), then
camsim expose NAME_raw.exr --iso 6400 --seed 2. Both pictures go through camsim.develop()
(white balance D65, Malvar demosaic) and camsim.display() with one common exposure factor
(the clean picture's mean to 0.18), side by side in lowlight_pair.png.
"""
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent


def main():
    if len(sys.argv) not in (2, 3):
        raise SystemExit(__doc__)
    build = Path(sys.argv[1]).resolve()
    out_dir = Path(sys.argv[2]) if len(sys.argv) == 3 else ROOT / "docs" / "images"
    sys.path.insert(0, str(build / "python"))
    import camsim  # noqa: E402
    import matplotlib.image as mpimg  # noqa: E402

    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        subprocess.run([str(build / "camsim"), "render", str(ROOT / "scenes" / "lowlight_cornell_a7s2.yaml"),
                        "-o", str(tmp / "render")], check=True)
        raw_exr = tmp / "render" / "lowlight_cornell_a7s2_raw.exr"
        subprocess.run([str(build / "camsim"), "expose", str(raw_exr), "--iso", "6400", "--seed", "2",
                        "-o", str(tmp / "expose")], check=True)
        sensor = camsim.Sensor("eld-sony-a7s2")
        electrons = camsim.read_exr(str(raw_exr))["channels"]["electrons.electrons"]
        clean = camsim.expose(electrons.astype(np.float32), sensor, seed=0, iso=6400,
                              exposure_time=0.0333, noise="none")
        noisy_dn = camsim.read_exr(str(tmp / "expose" / "lowlight_cornell_a7s2_f0000_raw.exr"))["channels"]["raw.DN"]
        noisy = np.round(noisy_dn).astype(np.uint16)
        print(f"electrons: median {np.median(electrons):.2f} e-, mean {electrons.mean():.2f} e-")
        developed = [camsim.develop(r, sensor) for r in (clean, noisy)]
        scale = 0.18 / float(np.mean(developed[0]))
        pictures = [camsim.display(np.ascontiguousarray(d * scale, dtype=np.float32), dtype="uint8")
                    for d in developed]
        pair = np.concatenate([pictures[0], np.full((pictures[0].shape[0], 8, 3), 255, np.uint8), pictures[1]],
                              axis=1)
        out = out_dir / "lowlight_pair.png"
        mpimg.imsave(out, pair)
        print("wrote", out)


if __name__ == "__main__":
    main()
