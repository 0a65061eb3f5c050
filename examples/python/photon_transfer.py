#!/usr/bin/python3
"""Photon transfer from one render: many noise draws of one noise-free electrons image.

Renders the Cornell box once with the smartphone sensor (camsim.capture: the expected,
noise-free electrons per photosite), then for a series of exposure levels scales those
electrons (a static scene: electrons are linear in the exposure time) and draws FRAMES raw
frames of each with camsim.expose(). Per level it takes the EMVA 1288 statistics over a
flat patch of the back wall: mean signal mu_y (DN, dark level subtracted) and temporal
variance sigma_y^2 (DN^2, per photosite over the frames, ddof=1, averaged). The photon
transfer curve sigma_y^2 = K mu_y + K^2 sigma_d^2 + 1/12 gives the system gain K from its
slope; the script fits K below saturation, prints it against the sensor's configured
K = (ISO / base ISO) / conversion gain, and plots the curve (ptc.png, python3-matplotlib).

Run (from the repository, after README's first command):
  PYTHONPATH=build/python /usr/bin/python3 examples/python/photon_transfer.py out/ptc
Options: --iso ISO (100), --frames N (32), --levels N (16), --threads N (0: all cores).
Prints one line per level and "fitted K ... configured K ... (error %)"; exits 1 if the
fit is off by more than 3 %.
"""
import argparse
import pathlib

import numpy as np
import yaml

import camsim

ROOT = pathlib.Path(__file__).resolve().parents[2]
SCENE = ROOT / "scenes" / "cornell_box_smartphone.yaml"


def noise_free_electrons(threads):
    """One 128 x 128 render of the scene at its own exposure: expected e- per photosite."""
    d = yaml.safe_load(SCENE.read_text())
    d["camera"]["resolution"] = [128, 128]
    d["camera"]["focal_length_mm"] *= 128 / 512
    d["render"]["spp"] = 64
    del d["sensor"]["auto_exposure"]
    scene = camsim.Scene.from_dict(d, base_dir=SCENE.parent)
    r = scene.render(threads=threads)
    return scene, r["sensor_film"], r["meta"]["pose"]["exposure_time_s"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out", type=pathlib.Path)
    ap.add_argument("--iso", type=float, default=100.0)
    ap.add_argument("--frames", type=int, default=32)
    ap.add_argument("--levels", type=int, default=16)
    ap.add_argument("--threads", type=int, default=0)
    args = ap.parse_args()

    scene, electrons, t0 = noise_free_electrons(args.threads)
    sensor = camsim.Sensor.of(scene)
    k_model = sensor.system_gain(args.iso)
    patch = (slice(40, 72), slice(56, 88))  # 32 x 32 px of the back wall
    wall = float(electrons[patch].mean())
    # Levels from ~20 e- to past saturation, at the patch's mean.
    top = 1.5 * sensor.saturation_electrons(args.iso)
    scales = np.geomspace(20.0 / wall, top / wall, args.levels)
    dark = camsim.expose(np.zeros_like(electrons), sensor, seed=7, frames=args.frames,
                         exposure_time=t0, iso=args.iso, threads=args.threads)[(slice(None),) + patch]
    mu_dark = dark.astype(float).mean()
    rows = []
    for i, s in enumerate(scales):
        frames = camsim.expose(electrons * np.float32(s), sensor, seed=1000 + i, frames=args.frames,
                               exposure_time=t0 * s, iso=args.iso, threads=args.threads)
        y = frames[(slice(None),) + patch].astype(float)
        mu_y, var_y = y.mean() - mu_dark, y.var(axis=0, ddof=1).mean()
        saturated = (frames[(slice(None),) + patch] >= sensor.white_level_dn).mean()
        rows.append((wall * s, mu_y, var_y, saturated))
        print(f"level {i:2d}: {wall * s:9.1f} e-  mu_y {mu_y:8.2f} DN  var_y {var_y:8.3f} DN^2"
              f"  saturated {100 * saturated:5.1f} %")
    rows = np.array(rows)
    # Fit below 70 % of saturation (the EMVA 1288 linear range), no saturated photosites.
    fit = (rows[:, 0] < 0.7 * sensor.saturation_electrons(args.iso)) & (rows[:, 3] == 0)
    k_fit, offset = np.polyfit(rows[fit, 1], rows[fit, 2], 1)
    err = k_fit / k_model - 1.0
    print(f"fitted K {k_fit:.5f} DN/e-, configured K {k_model:.5f} DN/e- ({100 * err:+.2f} %);"
          f" dark variance {offset:.3f} DN^2 (model {k_model ** 2 * sensor.read_noise_e ** 2 + 1 / 12:.3f})")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    args.out.mkdir(parents=True, exist_ok=True)
    fig, ax = plt.subplots(figsize=(6, 4.2))
    ax.loglog(rows[:, 1], rows[:, 2], "o", label=f"{args.frames} frames per level (camsim.expose)")
    mu = np.geomspace(max(rows[:, 1].min(), 0.1), rows[:, 1].max(), 100)
    ax.loglog(mu, k_model * mu + k_model ** 2 * sensor.read_noise_e ** 2 + 1 / 12, "-",
              label=f"model: K = {k_model:.4f} DN/e-")
    ax.set_xlabel("mean signal mu_y - mu_dark (DN)")
    ax.set_ylabel("temporal variance sigma_y^2 (DN^2)")
    ax.set_title(f"{sensor.name}, ISO {args.iso:g}: fitted K = {k_fit:.4f} ({100 * err:+.2f} %)")
    ax.legend()
    fig.tight_layout()
    fig.savefig(args.out / "ptc.png", dpi=110)
    print(f"wrote {args.out / 'ptc.png'}")
    return 0 if abs(err) < 0.03 else 1


if __name__ == "__main__":
    raise SystemExit(main())
