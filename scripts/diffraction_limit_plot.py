#!/usr/bin/env python3
"""The measured MTF of an in-focus slanted edge against the diffraction limit.

Reads `camsim mtf` tables (mtf.csv) of edges rendered through an aberration-free thin lens
and plots their Y curves beside the analytic MTF for the same working f-number and pixel
pitch: the circular pupil's diffraction MTF (2/pi)(arccos v - v sqrt(1 - v^2)), v = f lambda
N_w, averaged over the spectrum with the weights of Y for a D65 scene (D65 times CIE 1931
y-bar, 5 nm steps), times the square photosite's aperture along the normal of an edge
tilted by the angle, sinc(f cos a) sinc(f sin a), times ISO 12233's quarter-pixel binning,
sinc(f/4). Prints each curve's largest deviation from its model up to Nyquist.

usage: scripts/diffraction_limit_plot.py --pitch-um P --angle-deg A --out PNG
                                         LABEL:N_W:MTF_CSV [LABEL:N_W:MTF_CSV ...]
N_W 0 means no diffraction (the photosite alone). docs/examples.md, docs/mtf.md.
"""
import argparse
import csv
import math
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parent.parent


def table(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return np.array([[float(x) for x in r] for r in rows[1:]])


def y_weights():
    d65 = table(ROOT / "luts/spectra/illuminants/illuminant_D65.csv")
    cmf = table(ROOT / "luts/spectra/cie1931_2deg_xyz.csv")
    lam = np.arange(380.0, 781.0, 5.0)
    w = np.interp(lam, d65[:, 0], d65[:, 1]) * np.interp(lam, cmf[:, 0], cmf[:, 2])
    return lam, w / w.sum()


def diffraction_mtf(nu):
    nu = np.clip(nu, 0.0, 1.0)
    return (2.0 / math.pi) * (np.arccos(nu) - nu * np.sqrt(1.0 - nu * nu))


def model(f_cy_px, pitch_um, angle_deg, n_w):
    a = math.radians(angle_deg)
    pixel = np.sinc(f_cy_px * math.cos(a)) * np.sinc(f_cy_px * math.sin(a)) * np.sinc(f_cy_px / 4)
    if n_w <= 0:
        return pixel
    lam, w = y_weights()
    f_per_m = f_cy_px / (pitch_um * 1e-6)
    diff = sum(wi * diffraction_mtf(f_per_m * li * 1e-9 * n_w) for li, wi in zip(lam, w))
    return pixel * diff


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--pitch-um", type=float, required=True)
    p.add_argument("--angle-deg", type=float, default=5.0)
    p.add_argument("--out", required=True)
    p.add_argument("curves", nargs="+")
    a = p.parse_args(argv[1:])
    fig, ax = plt.subplots(figsize=(7, 4.6), dpi=110)
    colours = iter(["tab:blue", "tab:red", "tab:green", "tab:purple"])
    for spec in a.curves:
        label, n_w, path = spec.split(":", 2)
        n_w = float(n_w)
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
        f_px = np.array([float(r["frequency_cy_px"]) for r in rows])
        mtf = np.array([float(r["mtf_Y"]) for r in rows])
        expected = model(f_px, a.pitch_um, a.angle_deg, n_w)
        inside = f_px <= 0.5 + 1e-9
        worst = np.max(np.abs(mtf[inside] - expected[inside]))
        print(f"{label}: N_w {n_w:g}, MTF at Nyquist {np.interp(0.5, f_px, mtf):.3f} "
              f"(model {np.interp(0.5, f_px, expected):.3f}), largest deviation to Nyquist "
              f"{worst:.4f}")
        c = next(colours)
        ax.plot(f_px, mtf, color=c, lw=1.6, label=f"{label} (measured Y)")
        ax.plot(f_px, expected, color=c, lw=1, ls="--", label=f"{label} (model)")
    ax.axvline(0.5, color="0.5", ls="--", lw=1)
    ax.text(0.505, 1.02, "Nyquist", color="0.4", fontsize=8, va="bottom")
    ax.set_xlim(0, 1)
    ax.set_ylim(0, 1.05)
    ax.set_xlabel("spatial frequency (cycles/pixel, along the edge normal)")
    ax.set_ylabel("MTF (e-SFR, Y)")
    top = ax.secondary_xaxis("top", functions=(lambda f: f / (a.pitch_um * 1e-3),
                                               lambda n: n * a.pitch_um * 1e-3))
    top.set_xlabel("cycles/mm")
    ax.legend(fontsize=8, loc="upper right")
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(a.out, format="png")
    print(f"wrote {a.out}")


if __name__ == "__main__":
    sys.exit(main(sys.argv))
