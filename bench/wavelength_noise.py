#!/usr/bin/python3
"""Colour noise against wavelengths per path: camsim builds with 4 and 8 wavelengths
(CMake -DCAMSIM_WAVELENGTHS=4 / 8) render the same scene, and each render's error is
measured against a converged reference, on linear Rec.709 RGB and on luminance Y.

  /usr/bin/python3 bench/wavelength_noise.py --camsim build/camsim \\
      --camsim build-w8/camsim --scene scenes/cornell_box.yaml --resolution 256 \\
      --max-depth 8 --spp 64 256 --reference-spp 2048

The reference is the first binary's render at --reference-spp, made twice (two seeds) and
kept in --cache; r = (a + b)/2 and (a − b)/2 gives the floor that a measured error cannot go
below (the bench's reference noise, integrator/measure/bench_metrics.h), subtracted from
each error. Errors: rMSE, the mean over pixels (and over R, G, B for "rgb") of
e²/(r² + ε²) with ε = 1 % of the reference channel's mean (as the bench defines it).
Time: the render's CPU seconds (user + system of the camsim process), which a busy machine
disturbs less than wall time. Efficiency: 1/(rMSE · time), higher is better; its ratio to
the first binary's is the equal-error speed-up (rMSE of plain Monte Carlo falls as 1/time).
"""
import argparse
import os
import pathlib
import resource
import subprocess

os.environ.setdefault("OPENCV_IO_ENABLE_OPENEXR", "1")
import cv2  # noqa: E402 (the environment variable must be set first)
import numpy as np  # noqa: E402
import yaml  # noqa: E402


def load_rgb(path):
    image = cv2.imread(str(path), cv2.IMREAD_UNCHANGED)
    if image is None:
        raise SystemExit(f"cannot read {path}")
    return image[..., ::-1].astype(np.float64)  # OpenCV's BGR order → R, G, B


def luminance(rgb):  # Y of linear Rec.709 (D65)
    return (0.2126 * rgb[..., 0] + 0.7152 * rgb[..., 1] + 0.0722 * rgb[..., 2])[..., None]


def rmse(x, r):
    per_channel = []
    for c in range(r.shape[2]):
        eps = 0.01 * abs(r[..., c].mean())
        per_channel.append(((x[..., c] - r[..., c]) ** 2 / (r[..., c] ** 2 + eps**2)).mean())
    return float(np.mean(per_channel)), per_channel


def render(camsim, scene, spp, seed, out, threads):
    """Renders; returns (EXR path, CPU seconds of the child)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run([camsim, "render", str(scene), "--spp", str(spp), "--seed", str(seed),
                    "-o", str(out), "--reproducible", "--threads", str(threads)],
                   check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    name = yaml.safe_load(scene.read_text())["name"]
    return out / f"{name}.exr", cpu


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--camsim", action="append", required=True,
                    help="a camsim binary (give it twice or more: 4- and 8-wavelength builds)")
    ap.add_argument("--scene", type=pathlib.Path, default=pathlib.Path("scenes/cornell_box.yaml"))
    ap.add_argument("--resolution", type=int, default=256, help="px per side")
    ap.add_argument("--max-depth", type=int, default=8, help="scattering events per path")
    ap.add_argument("--spp", type=int, nargs="+", default=[64, 256])
    ap.add_argument("--reference-spp", type=int, default=2048, help="per reference half")
    ap.add_argument("--seed", type=int, default=7)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--cache", type=pathlib.Path, default=pathlib.Path("build/bench-cache/wavelengths"))
    args = ap.parse_args()

    scene = yaml.safe_load(args.scene.read_text())
    scene["camera"]["resolution"] = [args.resolution, args.resolution]
    scene.setdefault("render", {})["max_depth"] = args.max_depth
    args.cache.mkdir(parents=True, exist_ok=True)
    scene_file = args.cache / f"{scene['name']}_{args.resolution}_d{args.max_depth}.yaml"
    scene_file.write_text(yaml.safe_dump(scene))

    halves = []
    for k in (1, 2):
        out = args.cache / f"{scene_file.stem}_ref{args.reference_spp}_{k}"
        exr = out / f"{scene['name']}.exr"
        if not exr.exists():
            render(args.camsim[0], scene_file, args.reference_spp, 1000 + k, out, args.threads)
        halves.append(load_rgb(exr))
    a, b = halves
    ref = (a + b) / 2
    floor_rgb, floor_ch = rmse(ref + (a - b) / 2, ref)
    floor_y, _ = rmse(luminance(ref + (a - b) / 2), luminance(ref))

    print(f"{scene['name']} {args.resolution}², {args.max_depth} bounces; reference "
          f"2 × {args.reference_spp} spp (floor rMSE rgb {floor_rgb:.2e}, Y {floor_y:.2e})")
    print("| build | spp | CPU s | rMSE RGB | R | G | B | rMSE Y | eff. RGB | eff. Y |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    base = {}
    for i, camsim in enumerate(args.camsim):
        for spp in args.spp:
            out = args.cache / f"run_{i}_{spp}"
            exr, cpu = render(camsim, scene_file, spp, args.seed, out, args.threads)
            x = load_rgb(exr)
            e_rgb, ch = rmse(x, ref)
            e_y, _ = rmse(luminance(x), luminance(ref))
            e_rgb -= floor_rgb
            e_y -= floor_y
            ch = [c - f for c, f in zip(ch, floor_ch)]
            eff = (1 / (e_rgb * cpu), 1 / (e_y * cpu))
            base.setdefault(spp, eff)
            ratio = [e / b for e, b in zip(eff, base[spp])]
            print(f"| {camsim} | {spp} | {cpu:.1f} | {e_rgb:.4f} | {ch[0]:.4f} | {ch[1]:.4f} | "
                  f"{ch[2]:.4f} | {e_y:.4f} | {ratio[0]:.2f} | {ratio[1]:.2f} |")


if __name__ == "__main__":
    main()
