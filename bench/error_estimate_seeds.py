"""A render's estimate of its own error against its true error, over seeds: the bench's
scene at its sweep resolution (128 px long side), both samplers, 16, 64 and 256 spp, 16
seeds each, against a reference `camsim bench` cached (run it first with --ref-spp 16384 for
a converged one). Prints, per cell, est / true per seed as median [min, max] for rMSE and
MRAE, true = beyond the reference's noise (rMSE - floor, sqrt(MRAE^2 - floor^2)) as the
bench's table. docs/performance.md, "Error estimate".

Usage: PYTHONPATH=build/python /usr/bin/python3 bench/error_estimate_seeds.py SCENE.yaml REF.exr
  REF.exr: the bench cache's NAME-KEY.exr (channels Y, A.Y, B.Y) for SCENE at 128 px
"""
import os
import re
import sys
import tempfile

import numpy as np

import camsim

SEEDS = range(1, 17)


def metrics(e, r, mean):
    eps = 0.01 * abs(mean)
    return (e * e / (r * r + eps * eps)).mean(), (np.abs(e) / (np.abs(r) + eps)).mean()


def load_at(scene_file, sampler):
    """The scene at the bench's sweep size with `sampler`: a copy of the file beside it (its
    relative paths), loaded and removed."""
    text = open(scene_file).read()
    m = re.search(r"resolution: \[(\d+), (\d+)\]", text)
    w, h = int(m.group(1)), int(m.group(2))
    side = max(w, h)
    size = [max(1, round(v * 128 / side)) for v in (w, h)] if side > 128 else [w, h]
    text = text.replace(m.group(0), f"resolution: [{size[0]}, {size[1]}]")
    text, n = re.subn(r"\nrender:\n", f"\nrender:\n  sampler: {sampler}\n", text, count=1)
    if n != 1:
        sys.exit(f"{scene_file}: no block-style render: section to set the sampler in")
    fd, path = tempfile.mkstemp(suffix=".yaml", dir=os.path.dirname(os.path.abspath(scene_file)))
    try:
        with os.fdopen(fd, "w") as f:
            f.write(text)
        return camsim.load(path)
    finally:
        os.remove(path)


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    scene_file, ref_file = sys.argv[1:]
    ref = camsim.read_exr(ref_file)["channels"]
    r = ref["Y"].astype(float)
    a, b = ref["A.Y"].astype(float), ref["B.Y"].astype(float)
    floor = metrics(0.5 * (a - b), 0.5 * (a + b), 0.5 * (a.mean() + b.mean()))
    name = os.path.splitext(os.path.basename(scene_file))[0]
    for sampler in ("independent", "sobol"):
        scene = load_at(scene_file, sampler)
        for spp in (16, 64, 256):
            ratios = []
            for seed in SEEDS:
                out = scene.render(spp=spp, seed=seed, threads=2)
                x = out["xyz"][..., 1].astype(float)
                if x.shape != r.shape:
                    sys.exit(f"{ref_file}: {r.shape} pixels, the render {x.shape}")
                rmse, mrae = metrics(x - r, r, r.mean())
                est = out["meta"]["render"]["estimated_error"]
                ratios.append((est["rmse"] / (rmse - floor[0]),
                               est["mrae"] / np.sqrt(max(mrae ** 2 - floor[1] ** 2, 0.0))))
            o = np.array(ratios)
            cells = [f"{np.median(o[:, k]):.2f} [{o[:, k].min():.2f}, {o[:, k].max():.2f}]"
                     for k in (0, 1)]
            print(f"{name} {sampler:11s} {spp:3d} spp: rMSE {cells[0]}, MRAE {cells[1]}",
                  flush=True)


if __name__ == "__main__":
    main()
