#!/usr/bin/python3
"""What the amodal masks cost against how many labelled objects there are (issue 40's row
in docs/performance.md, "Amodal masks").

For N in --counts, a tabletop: an unlabelled floor and back wall, and N instances of Keenan
Crane's Spot (scenes/assets/spot.obj, 5,856 triangles, one shared BVH) in a square grid
seen from above at 45°, each instance labelled (`class: cow`), so that they occlude one
another. Each scene is rendered by bench/aov_cost_bench with `render.aovs: [amodal]`
against no aovs at all, alternating, --rounds rounds (it checks that the picture is the same
bytes both ways). Printed: N, the median ratio with / without, and the seconds of each side.

usage: bench/amodal_cost.py [--bench build/bench/aov_cost_bench] [--counts 1,4,16,64]
                            [--rounds 5] [--threads 2] [--resolution 480x320] [--spp 16]
"""
import argparse
import math
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def scene_text(n, width, height, spp):
    side = max(1, math.ceil(math.sqrt(n)))
    spacing = 0.22  # m between cows (each about 0.2 m long at scale 0.2): they overlap in view
    half = 0.5 * spacing * (side - 1)
    instances = []
    for k in range(n):
        x = -half + spacing * (k % side)
        z = -half + spacing * (k // side)
        instances.append(
            "      - {translate: [%.4f, 0.1474, %.4f], rotate: {axis: [0, 1, 0], angle_deg: %d}}"
            % (x, z, (37 * k) % 360))
    extent = half + 0.5
    return "\n".join([
        "format: camsim-scene/1",
        "name: amodal_cost_%d" % n,
        "render: {spp: %d, max_depth: 3}" % spp,
        "camera:",
        "  position: [0, %.3f, %.3f]" % (extent * 1.6, extent * 1.6),
        "  look_at: [0, 0, 0]",
        "  focal_length_mm: 24",
        "  resolution: [%d, %d]" % (width, height),
        "materials:",
        "  floor: {type: diffuse, reflectance: 0.4}",
        "  cow: {type: diffuse, reflectance: {rgb: [0.85, 0.6, 0.45]}}",
        "shapes:",
        "  - {name: floor, type: rectangle, corner: [-5, 0, 5], edge_u: [10, 0, 0], "
        "edge_v: [0, 0, -10], material: floor}",
        "  - {name: wall, type: rectangle, corner: [-5, 0, -3], edge_u: [10, 0, 0], "
        "edge_v: [0, 4, 0], material: floor}",
        "  - name: cow",
        "    type: mesh",
        "    file: %s" % os.path.join(ROOT, "scenes/assets/spot.obj"),
        "    scale: 0.2",
        "    material: cow",
        "    class: cow",
        "    instances:",
    ] + instances + [
        "lights:",
        "  - {type: distant, direction: [-0.3, -1, -0.4], illuminance: 20000}",
        "",
    ])


def with_aovs(text, aovs):
    return text.replace("max_depth: 3}", "max_depth: 3, aovs: [%s]}" % aovs)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--bench", default=os.path.join(ROOT, "build/bench/aov_cost_bench"))
    p.add_argument("--counts", default="1,4,16,64")
    p.add_argument("--rounds", type=int, default=5)
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--resolution", default="480x320")
    p.add_argument("--spp", type=int, default=16)
    a = p.parse_args()
    width, height = (int(v) for v in a.resolution.split("x"))
    print("| labelled objects | with amodal / without (median of rounds) | without (s) | with (s) |")
    print("|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        for n in (int(c) for c in a.counts.split(",")):
            path = os.path.join(tmp, "amodal_%d.yaml" % n)
            with open(path, "w") as f:
                f.write(with_aovs(scene_text(n, width, height, a.spp), "amodal"))
            out = subprocess.run([a.bench, path, "--rounds", str(a.rounds), "--threads",
                                  str(a.threads)], capture_output=True, text=True)
            if out.returncode != 0:
                sys.exit("aov_cost_bench failed on N = %d:\n%s%s" % (n, out.stdout, out.stderr))
            ratio = re.search(r"rounds: median ratio ([0-9.]+)", out.stdout)
            sums = re.findall(r"^\s*\d+\s+([0-9.]+)\s+([0-9.]+)\s+[0-9.]+$", out.stdout, re.M)
            if not ratio or not sums:
                sys.exit("cannot read aov_cost_bench's output:\n" + out.stdout)
            without = sorted(float(s[0]) for s in sums)[len(sums) // 2]
            with_ = sorted(float(s[1]) for s in sums)[len(sums) // 2]
            print("| %d | %s× | %.2f | %.2f |" % (n, ratio.group(1), without, with_))
            sys.stdout.flush()


if __name__ == "__main__":
    main()
