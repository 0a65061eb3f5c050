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

import numpy as np

import camsim

SEEDS = range(1, 17)


def metrics(e, r, mean):
    eps = 0.01 * abs(mean)
    return (e * e / (r * r + eps * eps)).mean(), (np.abs(e) / (np.abs(r) + eps)).mean()


def fail(message):
    """A clear message and exit 2 (bad input), as camsim's own tools."""
    print(f"error_estimate_seeds: {message}", file=sys.stderr)
    sys.exit(2)


def load_at(scene_file, sampler):
    """The scene at the bench's sweep size (cli/bench_args.cpp, reducedResolution) with
    `sampler`, from the file's text (its relative paths resolved beside it)."""
    try:
        with open(scene_file, encoding="utf-8") as f:
            text = f.read()
    except OSError as e:
        fail(f"{scene_file}: {e.strerror}")
    except UnicodeDecodeError as e:
        fail(f"{scene_file}: not UTF-8 text ({e.reason} at byte {e.start})")
    m = re.search(r"resolution: \[(\d+), (\d+)\]", text)
    if not m:
        fail(f"{scene_file}: no 'resolution: [W, H]' line to scale")
    w, h = int(m.group(1)), int(m.group(2))
    side = max(w, h)
    # int(v * 128 / side + 0.5): lround's rounding of halves away from zero
    size = [max(1, int(v * 128 / side + 0.5)) for v in (w, h)] if side > 128 else [w, h]
    text = text.replace(m.group(0), f"resolution: [{size[0]}, {size[1]}]")
    text, n = re.subn(r"\nrender:\n", f"\nrender:\n  sampler: {sampler}\n", text, count=1)
    if n != 1:
        fail(f"{scene_file}: no block-style 'render:' section to set the sampler in")
    try:
        return camsim.Scene.from_yaml(text, name=scene_file,
                                      base_dir=os.path.dirname(os.path.abspath(scene_file)))
    except camsim.InputError as e:
        fail(str(e))


def main():
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    scene_file, ref_file = sys.argv[1:]
    try:
        ref = camsim.read_exr(ref_file)["channels"]
    except camsim.InputError as e:  # names the file
        fail(str(e))
    if not {"Y", "A.Y", "B.Y"} <= ref.keys():
        fail(f"{ref_file}: not a camsim bench reference (channels Y, A.Y, B.Y)")
    r = ref["Y"].astype(float)
    a, b = ref["A.Y"].astype(float), ref["B.Y"].astype(float)
    if not r.mean() > 0.0:
        fail(f"{ref_file}: the reference is black (mean Y {r.mean()}): no relative error")
    floor = metrics(0.5 * (a - b), 0.5 * (a + b), 0.5 * (a.mean() + b.mean()))
    name = os.path.splitext(os.path.basename(scene_file))[0]
    for sampler in ("independent", "sobol"):
        scene = load_at(scene_file, sampler)
        for spp in (16, 64, 256):
            ratios = []
            for seed in SEEDS:
                try:
                    out = scene.render(spp=spp, seed=seed, threads=2)
                except camsim.InputError as e:
                    fail(str(e))
                x = out["xyz"][..., 1].astype(float)
                if x.shape != r.shape:
                    fail(f"{ref_file}: {r.shape[1]}x{r.shape[0]} px, the render "
                         f"{x.shape[1]}x{x.shape[0]}: not this scene's reference")
                rmse, mrae = metrics(x - r, r, r.mean())
                true_rmse = rmse - floor[0]
                true_mrae = np.sqrt(max(mrae ** 2 - floor[1] ** 2, 0.0))
                if not (true_rmse > 0.0 and true_mrae > 0.0):
                    fail(f"{ref_file}: the render at {spp} spp is within the reference's "
                         "noise: render a reference of more spp (camsim bench --ref-spp)")
                est = out["meta"]["render"]["estimated_error"]
                if est["channel"] != "Y":
                    fail(f"{scene_file}: the render estimates its error on {est['channel']}, "
                         "not the XYZ film's Y the reference holds (a scene with a sensor)")
                ratios.append((est["rmse"] / true_rmse, est["mrae"] / true_mrae))
            o = np.array(ratios)
            cells = [f"{np.median(o[:, k]):.2f} [{o[:, k].min():.2f}, {o[:, k].max():.2f}]"
                     for k in (0, 1)]
            print(f"{name} {sampler:11s} {spp:3d} spp: rMSE {cells[0]}, MRAE {cells[1]}",
                  flush=True)


if __name__ == "__main__":
    main()
