#!/usr/bin/python3
"""Time per capture with and without reusing the built scene (Embree BVH, materials, lights)
between captures of one camsim.Scene, and whether the bytes are the same.

The captures of bench/python_capture_rate.py (default 200 of the smartphone Cornell box at
128 x 128 px, 4 spp, each with its own camera position and exposure time, auto-exposure
off), in this one process, on two Scenes: scene.render(reuse=True), where each capture
renders on the scene its previous capture built (meta["scene_reused"]), and reuse=False,
where each builds its own as before — capture by capture, alternating which goes first, so
that another process's load falls on both alike; each capture timed from its overrides to
its arrays. The error column: captures whose arrays (xyz, sensor_film, raw of every
bracket, acescg, display8, AOVs) differ in any byte between the two (expected: 0).

  PYTHONPATH=build-py/python /usr/bin/python3 bench/python_scene_reuse.py [--grid N]
--grid N adds a floor of 2 N^2 triangles (a BVH that costs something to build).
"""
import argparse
import hashlib
import time

import numpy as np

import camsim
from python_capture_rate import CENTRE, SCENE, draws, scene_dict


def digest(r):
    """SHA-256 over every array of a capture (meta excluded: it has the wall time)."""
    h = hashlib.sha256()

    def add(v):
        if isinstance(v, dict):
            for k in sorted(v):
                if k != "meta":
                    add(v[k])
        elif isinstance(v, list):
            for x in v:
                add(x)
        elif isinstance(v, np.ndarray):
            h.update(v.tobytes())
    add(r)
    return h.hexdigest()


def add_grid(d, n):
    """A bumpy n x n-quad height field (2 n^2 triangles) as the box's floor: geometry whose
    BVH build costs something."""
    u = np.linspace(0.0, 0.55, n + 1)
    x, z = np.meshgrid(u, u)
    y = 0.002 * np.sin(60.0 * x) * np.cos(60.0 * z)
    vertices = np.stack([x, y, z], axis=-1).reshape(-1, 3)
    i = np.arange(n)[:, None] * (n + 1) + np.arange(n)[None, :]
    faces = np.stack([i, i + 1, i + n + 2, i + n + 1], axis=-1).reshape(-1, 4)
    material = next(iter(d["materials"]))
    d["shapes"].append({"name": "grid", "type": "mesh", "material": material,
                        "vertices": vertices, "faces": faces})


def run(d, items, threads):
    """Both modes capture by capture on two Scenes (which goes first alternates), so that a
    drift in the machine's load falls on both alike; per mode: seconds of each capture,
    digests, captures reused."""
    scenes = {m: camsim.Scene.from_dict(d, base_dir=SCENE.parent) for m in (True, False)}
    out = {m: ([], [], 0) for m in (True, False)}
    for i, it in enumerate(items):
        for reuse in ((True, False) if i % 2 == 0 else (False, True)):
            scene = scenes[reuse]
            start = time.perf_counter()
            scene.set_pose(position=it["position"], look_at=CENTRE)
            scene.set_exposure(exposure_time_s=it["exposure_time_s"])
            scene.set_seed(it["seed"])
            r = scene.render(threads=threads, reuse=reuse)
            seconds = time.perf_counter() - start
            times, digests, reused = out[reuse]
            times.append(seconds)
            digests.append(digest(r))
            out[reuse] = (times, digests, reused + bool(r["meta"]["scene_reused"]))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--count", type=int, default=200)
    ap.add_argument("--size", type=int, default=128)
    ap.add_argument("--spp", type=int, default=4)
    ap.add_argument("--threads", type=int, default=0)
    ap.add_argument("--grid", type=int, default=0, help="add a floor of 2 N^2 triangles")
    args = ap.parse_args()
    d = scene_dict(args.size, args.spp)
    if args.grid:
        add_grid(d, args.grid)
    items = draws(args.count)
    out = run(d, items, args.threads)
    differ = sum(a != b for a, b in zip(out[True][1], out[False][1]))
    n = args.count
    grid = f", + {2 * args.grid ** 2} triangles" if args.grid else ""
    print(f"{n} captures, {args.size}x{args.size} px, {args.spp} spp, threads {args.threads}"
          f"{grid}")
    print(f"{'mode':<18}{'total s':>9}{'mean ms':>9}{'median ms':>11}{'reused':>8}")
    for reuse, name in ((True, "reuse (default)"), (False, "reuse=False")):
        t = np.array(out[reuse][0]) * 1e3
        print(f"{name:<18}{t.sum() / 1e3:>9.2f}{t.mean():>9.2f}{np.median(t):>11.2f}"
              f"{out[reuse][2]:>8}")
    saved = np.array(out[False][0]) - np.array(out[True][0])
    print(f"saved per capture: mean {1e3 * saved.mean():.2f} ms, median "
          f"{1e3 * np.median(saved):.2f} ms; captures whose bytes differ: {differ} of {n}")
    return 0 if differ == 0 and out[True][2] == n - 1 else 1


if __name__ == "__main__":
    raise SystemExit(main())
