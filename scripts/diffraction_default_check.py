#!/usr/bin/env python3
"""Does diffraction change pixels at f/8 on a 5 um pixel? The measurement behind
camera.aperture.diffraction's default (docs/camera.md, "Diffraction at the stop").

Renders scenes/diffraction_f8.yaml (a bar target and a slanted edge in focus, 50 mm f/8,
5 um pitch) three times with one camsim binary: diffraction off at seeds 0 and 1, and on at
seed 0, all with --reproducible and the same spp. The two off renders give the noise: a
pixel counts as changed when |on - off| exceeds 5 x the RMS of (off0 - off1) over the
image's pixels of the same brightness class (the noise of two independent renders, larger
than that of on - off, which share every random number but the jitter). Prints the counts,
the largest change relative to the white level, the bar groups' modulation and the slanted
edge's 10-90 % rise, off and on, and the quick-look PNGs' 8-bit differences.

usage: scripts/diffraction_default_check.py CAMSIM [--spp N] [--out DIR]
"""
import argparse
import os
import pathlib
import re
import subprocess
import sys

import cv2
import numpy as np

ROOT = pathlib.Path(__file__).resolve().parent.parent


def render(camsim, scene_text, out, name, spp, seed):
    scene = out / f"{name}.yaml"
    scene.write_text(scene_text.replace("name: diffraction_f8", f"name: {name}"))
    subprocess.run([camsim, "render", str(scene), "-o", str(out), "--reproducible", "--spp",
                    str(spp), "--seed", str(seed)], check=True, stdout=subprocess.DEVNULL)
    rgb = cv2.imread(str(out / f"{name}.exr"), cv2.IMREAD_UNCHANGED).astype(np.float64)
    y = 0.2126 * rgb[..., 2] + 0.7152 * rgb[..., 1] + 0.0722 * rgb[..., 0]  # Rec.709 Y
    png = cv2.imread(str(out / f"{name}.png"), cv2.IMREAD_UNCHANGED).astype(np.int32)
    return y, png


def modulation(y, x0, x1):
    """(max - min)/(max + min) of the rows 110-130 averaged, columns x0..x1."""
    profile = y[110:130, x0:x1].mean(axis=0)
    return (profile.max() - profile.min()) / (profile.max() + profile.min())


def edge_rise(y):
    """10-90 % rise of the slanted edge (px), from rows 75-165 aligned on the edge (an
    oversampled edge profile, 4 bins per px), black square left of the edge."""
    rows = range(75, 165)
    xs, vs = [], []
    for r in rows:
        line = y[r, 140:180]
        white, black = line[-5:].mean(), line[:5].mean()
        half = np.argmax(line > 0.5 * (white + black))
        # sub-pixel centre by linear interpolation around the half level
        a, b = line[half - 1], line[half]
        centre = half - 1 + (0.5 * (white + black) - a) / (b - a)
        for i, v in enumerate(line):
            xs.append(i - centre)
            vs.append((v - black) / (white - black))
    xs, vs = np.array(xs), np.array(vs)
    bins = np.arange(-6, 6.01, 0.25)
    idx = np.digitize(xs, bins)
    esf = np.array([vs[idx == k].mean() for k in range(1, len(bins))])
    centres = 0.5 * (bins[1:] + bins[:-1])
    lo = centres[np.argmax(esf > 0.1)]
    hi = centres[np.argmax(esf > 0.9)]
    return hi - lo


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("camsim")
    ap.add_argument("--spp", type=int, default=1024)
    ap.add_argument("--out", default="out/diffraction_default_check")
    args = ap.parse_args()
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    text = (ROOT / "scenes" / "diffraction_f8.yaml").read_text()
    off_text = re.sub(r"aperture: \{\}.*", "aperture: {diffraction: false}", text)
    on_text = re.sub(r"aperture: \{\}.*", "aperture: {diffraction: true}", text)
    off0, png_off = render(args.camsim, off_text, out, "f8_off_seed0", args.spp, 0)
    off1, _ = render(args.camsim, off_text, out, "f8_off_seed1", args.spp, 1)
    on0, png_on = render(args.camsim, on_text, out, "f8_on_seed0", args.spp, 0)

    white = np.percentile(off0, 95)
    # Noise per brightness class (dark: the black targets, bright: the card, between: edges).
    noise = np.empty_like(off0)
    classes = [off0 < 0.2 * white, (off0 >= 0.2 * white) & (off0 < 0.8 * white),
               off0 >= 0.8 * white]
    for c in classes:
        noise[c] = np.sqrt(np.mean((off0[c] - off1[c]) ** 2))
    change = np.abs(on0 - off0)
    changed = change > 5.0 * noise
    n = off0.size
    print(f"pixels: {n}; white level {white:.4g} (Y, lm*s)")
    print(f"noise (RMS of off seed 0 - seed 1) relative to white: "
          f"{', '.join(f'{np.sqrt(np.mean((off0[c] - off1[c]) ** 2)) / white:.2e}' for c in classes)}"
          " (dark, mid, bright)")
    print(f"changed by diffraction (> 5 x that): {changed.sum()} pixels "
          f"({100.0 * changed.sum() / n:.1f} %); the same test on seed 0 vs seed 1: "
          f"{(np.abs(off1 - off0) > 5.0 * noise).sum()} pixels")
    for level in (0.01, 0.1):
        print(f"changed by more than {100 * level:g} % of white: {(change > level * white).sum()} "
              f"pixels ({100.0 * (change > level * white).sum() / n:.1f} %)")
    print(f"largest change: {change.max() / white:.3f} of white; mean |change| "
          f"{change.mean() / white:.4f} of white")
    print(f"mean level on / off: {on0.mean() / off0.mean():.5f}")
    for name, x0, x1 in [("2.5 px bars", 179, 194), ("3 px bars", 200, 217),
                         ("4 px bars", 225, 248), ("6 px bars", 256, 289)]:
        print(f"{name}: modulation off {modulation(off0, x0, x1):.3f}, "
              f"on {modulation(on0, x0, x1):.3f}")
    print(f"slanted edge 10-90 % rise: off {edge_rise(off0):.2f} px, on {edge_rise(on0):.2f} px")
    d = np.abs(png_on - png_off).max(axis=2)
    print(f"quick-look PNG (8-bit sRGB): {(d >= 2).sum()} pixels differ by 2 codes or more "
          f"({100.0 * (d >= 2).sum() / d.size:.1f} %), largest difference {d.max()} codes")
    return 0


if __name__ == "__main__":
    sys.exit(main())
