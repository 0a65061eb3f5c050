#!/usr/bin/python3
"""Draws a KITTI object export's boxes over its images, as a KITTI reader sees them.

Reads only the export (the devkit readme's layout, none of camsim's code):
kitti/image_2/IIIIII.png, kitti/calib/IIIIII.txt (P2) and kitti/label_2/IIIIII.txt. For each
label it builds the 3-D box from h, w, l, x, y, z, rotation_y as the devkit does, projects its
corners through P2 and draws its edges (the front face, +x of the object, thicker), and the
2-D box (left, top, right, bottom) dashed, with the type and the occlusion state. Several
images go side by side.

Usage: scripts/kitti_boxes_plot.py OUT/kitti [--ids 0 3] -o boxes.png
"""
import argparse
import math
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

OCCLUDED = {0: "visible", 1: "partly occluded", 2: "largely occluded", 3: "unknown"}
EDGES = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4),
         (0, 4), (1, 5), (2, 6), (3, 7)]
FRONT = {(0, 1), (4, 5), (0, 4), (1, 5)}  # the face at +l/2 (the object's heading)


def read_p2(path):
    for line in path.read_text().splitlines():
        key, _, values = line.partition(":")
        if key == "P2":
            return np.array([float(v) for v in values.split()]).reshape(3, 4)
    sys.exit(f"{path}: no P2 line")


def corners(h, w, l, x, y, z, ry):
    """The devkit's box corners in rect coordinates (3 x 8)."""
    xs = [l / 2, l / 2, -l / 2, -l / 2, l / 2, l / 2, -l / 2, -l / 2]
    ys = [0, 0, 0, 0, -h, -h, -h, -h]
    zs = [w / 2, -w / 2, -w / 2, w / 2, w / 2, -w / 2, -w / 2, w / 2]
    r = np.array([[math.cos(ry), 0, math.sin(ry)], [0, 1, 0], [-math.sin(ry), 0, math.cos(ry)]])
    return r @ np.array([xs, ys, zs]) + np.array([[x], [y], [z]])


def draw(ax, root, image_id):
    name = f"{image_id:06d}"
    ax.imshow(mpimg.imread(root / "image_2" / (name + ".png")))
    p2 = read_p2(root / "calib" / (name + ".txt"))
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    lines = (root / "label_2" / (name + ".txt")).read_text().splitlines()
    for i, line in enumerate(lines):
        f = line.split()
        kind, occluded = f[0], int(f[2])
        left, top, right, bottom, h, w, l, x, y, z, ry = map(float, f[4:15])
        c = colours[i % len(colours)]
        uvw = p2 @ np.vstack([corners(h, w, l, x, y, z, ry), np.ones((1, 8))])
        uv = uvw[:2] / uvw[2]
        for a, b in EDGES:
            ax.plot(uv[0, [a, b]], uv[1, [a, b]], color=c,
                    linewidth=2.2 if (a, b) in FRONT else 1.0)
        ax.add_patch(plt.Rectangle((left, top), right - left, bottom - top, fill=False,
                                   edgecolor=c, linestyle="--", linewidth=0.8))
        ax.text(left, top - 3, f"{kind}, {OCCLUDED.get(occluded, occluded)}", color=c,
                fontsize=7, va="bottom")
    ax.set_title(f"kitti/image_2/{name}.png", fontsize=8)
    ax.axis("off")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("kitti", type=pathlib.Path, help="the export's kitti/ folder")
    parser.add_argument("--ids", type=int, nargs="+", default=[0], help="image ids (default 0)")
    parser.add_argument("-o", "--output", required=True, type=pathlib.Path)
    args = parser.parse_args()
    for image_id in args.ids:
        if not (args.kitti / "label_2" / f"{image_id:06d}.txt").is_file():
            print(f"{args.kitti}: no label_2/{image_id:06d}.txt", file=sys.stderr)
            return 2
    fig, axes = plt.subplots(1, len(args.ids), figsize=(4.8 * len(args.ids), 3.9), squeeze=False)
    for ax, image_id in zip(axes[0], args.ids):
        draw(ax, args.kitti, image_id)
    fig.tight_layout()
    fig.savefig(args.output, dpi=110)
    print(f"{args.output}: {len(args.ids)} image(s)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
