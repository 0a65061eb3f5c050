"""Error per sample of the Cornell box at 128 px, 9 scattering events (the peer bench's depth):
rMSE and MRAE of luminance Y and the mean rMSE of linear Rec.709 R, G, B, each over 4 seeds
at 64 and 256 spp, against a 2 x 4096-spp reference rendered once and kept in OUT_DIR.
Error per sample does not depend on the machine's load, so two builds (their Python modules
on PYTHONPATH in turn) can be compared on a busy machine. Metrics as camsim bench's
(docs/bench.md): rMSE = mean e^2/(r^2 + eps^2), MRAE = mean |e|/(|r| + eps), eps = 1 % of
the reference's mean. docs/performance.md, "Error per sample: what Cycles does differently".

Usage: PYTHONPATH=build/python /usr/bin/python3 bench/light_point_noise.py LABEL [OUT_DIR [SEEDS]]
(SEEDS: how many seeds per spp, 4 by default; se is the standard error of their mean)
"""
import os
import re
import sys

import numpy as np

import camsim

HERE = os.path.dirname(os.path.abspath(__file__))
XYZ_TO_REC709 = np.array([[3.2404542, -1.5371385, -0.4985314],
                          [-0.9692660, 1.8760108, 0.0415560],
                          [0.0556434, -0.2040259, 1.0572252]])


def metrics(x, r):
    eps = 0.01 * abs(r.mean())
    e = x - r
    return (e * e / (r * r + eps * eps)).mean(), (np.abs(e) / (np.abs(r) + eps)).mean()


def main():
    label = sys.argv[1] if len(sys.argv) > 1 else "build"
    out = sys.argv[2] if len(sys.argv) > 2 else "light-point-noise"
    seeds = int(sys.argv[3]) if len(sys.argv) > 3 else 4
    os.makedirs(out, exist_ok=True)
    text = open(os.path.join(HERE, "..", "scenes", "cornell_box.yaml")).read()
    text = re.sub(r"resolution: \[512, 512\]", "resolution: [128, 128]", text)
    text = re.sub(r"max_depth: 16", "max_depth: 9", text)
    scene_file = os.path.join(out, "cornell_128.yaml")
    with open(scene_file, "w") as f:
        f.write(text)
    scene = camsim.load(scene_file)
    ref_file = os.path.join(out, "reference.npz")
    if not os.path.exists(ref_file):
        a = scene.render(spp=4096, seed=1001, threads=2)["xyz"]
        b = scene.render(spp=4096, seed=1002, threads=2)["xyz"]
        np.savez(ref_file, a=a, b=b)
    halves = np.load(ref_file)
    ref = 0.5 * (halves["a"] + halves["b"])
    ref_rgb = ref @ XYZ_TO_REC709.T
    for spp in (64, 256):
        rows = []
        for seed in range(1, seeds + 1):
            x = scene.render(spp=spp, seed=seed, threads=2)["xyz"]
            rmse_y, mrae_y = metrics(x[..., 1], ref[..., 1])
            rgb = x @ XYZ_TO_REC709.T
            rmse_rgb = np.mean([metrics(rgb[..., c], ref_rgb[..., c])[0] for c in range(3)])
            rows.append((rmse_y, mrae_y, rmse_rgb))
        o = np.array(rows)
        se = o.std(axis=0, ddof=1) / np.sqrt(len(o)) if len(o) > 1 else 0 * o[0]
        print(f"{label} spp {spp}: rMSE Y {o[:, 0].mean():.4e} (+-{o[:, 0].std():.1e}, "
              f"se {se[0]:.1e}), MRAE Y {o[:, 1].mean():.4f}, rMSE RGB {o[:, 2].mean():.4e} "
              f"(+-{o[:, 2].std():.1e}, se {se[2]:.1e})", flush=True)


if __name__ == "__main__":
    main()
