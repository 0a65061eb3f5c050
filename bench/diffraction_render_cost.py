"""What diffraction at the stop costs in a whole render, time and error: one scene rendered
with camera.aperture.diffraction off and on, on one thread, at equal spp, alternated over
PAIRS seeds, each against its own high-spp reference (the two converge to different images
by design: on is the geometric image convolved with the stop's PSF). docs/performance.md,
"Diffraction at the stop: cost per camera ray".

Time: CPU seconds (user + system) of each `camsim render` process (os.wait4), which a shared
host's waiting does not inflate; it includes the scene load and writing the outputs, the same
for off and on, so the extra per sample, (on - off) / samples, is the cleaner figure.
Error: rMSE and MRAE of luminance Y (Rec.709 Y of the EXR's linear RGB) against the
reference, as camsim bench's (docs/bench.md): rMSE = mean (x - r)^2 / (r^2 + eps^2), MRAE =
mean |x - r| / (|r| + eps), eps = 1 % of the reference's mean. Each reference is two renders
of REF_SPP/2 at seeds 1001 and 1002 (kept in OUT and reused: delete OUT after a change to
the scene or to camsim); its own error, the rMSE of (a - b)/2 against (a + b)/2, is the
floor printed and subtracted. Time to equal error: with rMSE proportional to 1/spp (Monte
Carlo's slope), the CPU time each needs for the same rMSE scales as time x rMSE, so
(t_on rMSE_on) / (t_off rMSE_off) is diffraction's cost at equal error; the Sobol' sampler
converges faster on smooth images, so the slope between SPP and REF_SPP is printed too, and
the time diffraction on needs at its own slope to reach the off render's rMSE.

usage: /usr/bin/python3 bench/diffraction_render_cost.py CAMSIM [--scene S] [--spp N]
           [--ref-spp N] [--pairs N] [--out DIR]
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


def variant(text, name, diffraction):
    """The scene named NAME with camera.aperture.diffraction set (the scene's aperture is an
    `aperture: {...}` flow mapping on one line)."""
    flag = "true" if diffraction else "false"
    text, count = re.subn(r"(?m)^name: .*$", f"name: {name}", text)
    if count != 1:
        sys.exit("the scene needs a top-level `name:` line")
    new, count = re.subn(r"aperture: \{\}", "aperture: {diffraction: %s}" % flag, text)
    if count != 1:
        new, count = re.subn(r"aperture: \{", "aperture: {diffraction: %s, " % flag, text)
    if count != 1:
        sys.exit("the scene needs one `aperture: {...}` line")
    return new


def render(camsim, scene, out, spp, seed):
    """Renders; returns (Y, CPU seconds of the process)."""
    log = out / (scene.stem + ".log")
    with open(log, "w") as f:
        proc = subprocess.Popen([camsim, "render", str(scene), "-o", str(out), "--threads", "1",
                                 "--spp", str(spp), "--seed", str(seed)], stdout=f, stderr=f)
        _, status, usage = os.wait4(proc.pid, 0)
    proc.returncode = os.waitstatus_to_exitcode(status)
    if proc.returncode != 0:
        sys.exit(f"camsim render {scene} failed ({proc.returncode}): see {log}")
    rgb = cv2.imread(str(out / (scene.stem + ".exr")), cv2.IMREAD_UNCHANGED).astype(np.float64)
    y = 0.2126 * rgb[..., 2] + 0.7152 * rgb[..., 1] + 0.0722 * rgb[..., 0]
    return y, usage.ru_utime + usage.ru_stime


def rmse(x, r):
    eps = 0.01 * abs(r.mean())
    e = x - r
    return float((e * e / (r * r + eps * eps)).mean())


def mrae(x, r):
    eps = 0.01 * abs(r.mean())
    return float((np.abs(x - r) / (np.abs(r) + eps)).mean())


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("camsim")
    ap.add_argument("--scene", default=str(ROOT / "scenes" / "diffraction_f8.yaml"))
    ap.add_argument("--spp", type=int, default=32)
    ap.add_argument("--ref-spp", type=int, default=512)
    ap.add_argument("--pairs", type=int, default=3)
    ap.add_argument("--out", default="out/diffraction_render_cost")
    args = ap.parse_args()
    if args.spp < 1 or args.ref_spp < 2 or args.pairs < 1:
        print("diffraction_render_cost: --spp, --pairs >= 1 and --ref-spp >= 2", file=sys.stderr)
        return 2
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    text = pathlib.Path(args.scene).read_text()
    stem = pathlib.Path(args.scene).stem
    configs = {"off": False, "on": True}
    scenes = {}
    for name, on in configs.items():
        # In OUT (a scene that names files relative to its folder would need them there).
        scenes[name] = out / f"{stem}_diffraction_{name}.yaml"
        scenes[name].write_text(variant(text, scenes[name].stem, on))
    refs, floors, mrae_floors = {}, {}, {}
    for name in configs:
        cache = out / f"{stem}_{name}_ref{args.ref_spp}.npz"
        if cache.exists():
            z = np.load(cache)
            a, b = z["a"], z["b"]
        else:
            a, _ = render(args.camsim, scenes[name], out, args.ref_spp // 2, 1001)
            b, _ = render(args.camsim, scenes[name], out, args.ref_spp // 2, 1002)
            np.savez(cache, a=a, b=b)
        refs[name] = 0.5 * (a + b)
        floors[name] = rmse(refs[name] + 0.5 * (a - b), refs[name])
        mrae_floors[name] = mrae(refs[name] + 0.5 * (a - b), refs[name])
    times = {name: [] for name in configs}
    errors = {name: [] for name in configs}
    maes = {name: [] for name in configs}
    for pair in range(args.pairs):
        order = list(configs) if pair % 2 == 0 else list(reversed(list(configs)))
        for name in order:
            y, cpu = render(args.camsim, scenes[name], out, args.spp, pair + 1)
            times[name].append(cpu)
            errors[name].append(rmse(y, refs[name]))
            maes[name].append(mrae(y, refs[name]))
    h, w = next(iter(refs.values())).shape
    samples = float(w * h * args.spp)
    med = {n: float(np.median(times[n])) for n in configs}
    err = {n: float(np.mean(errors[n])) - floors[n] for n in configs}
    print(f"{stem}: {w} x {h} px, {args.spp} spp ({samples / 1e6:.2f} M samples), 1 thread, "
          f"{args.pairs} alternated pairs; references {args.ref_spp} spp")
    print(f"{'diffraction':12s} {'CPU s per render':24s} {'median':>7s} {'rMSE per render':30s} "
          f"{'ref floor':>9s} {'rMSE-floor':>10s} {'MRAE (mean)':>11s} {'ref floor':>9s}")
    for n in configs:
        print(f"{n:12s} {', '.join(f'{t:.2f}' for t in times[n]):24s} {med[n]:7.2f} "
              f"{', '.join(f'{e:.2e}' for e in errors[n]):30s} {floors[n]:9.2e} {err[n]:10.3e} "
              f"{np.mean(maes[n]):11.4f} {mrae_floors[n]:9.4f}")
    ratio = med["on"] / med["off"]
    extra = (med["on"] - med["off"]) / samples * 1e6
    print(f"on / off CPU at equal spp: {ratio:.2f}x (extra {extra:.3f} us per sample); "
          f"rMSE on / off: {err['on'] / err['off']:.2f}; "
          f"time to equal error (t x rMSE) on / off: {ratio * err['on'] / err['off']:.2f}x; "
          f"MRAE on / off: {np.mean(maes['on']) / np.mean(maes['off']):.2f}")
    # The slope of log rMSE against log spp between the renders and the references (whose
    # error the floor estimates), and with it the CPU time diffraction on needs to reach the
    # off render's rMSE: t_on * (rMSE_on / rMSE_off)^(1 / |slope_on|).
    slope = {n: np.log(err[n] / floors[n]) / np.log(args.spp / args.ref_spp) for n in configs}
    reach = med["on"] * (err["on"] / err["off"]) ** (1.0 / abs(slope["on"]))
    print(f"rMSE slope against spp ({args.spp} -> {args.ref_spp}): off {slope['off']:.2f}, on "
          f"{slope['on']:.2f}; on reaches off's rMSE in {reach:.1f} CPU s, "
          f"{reach / med['off']:.1f}x off's time")
    return 0


if __name__ == "__main__":
    sys.exit(main())
