#!/usr/bin/python3
"""Makes docs/images/fisheye_sequence.png (frame 2 of the 200° fisheye sequence and its
ground-truth quick looks) and docs/images/panorama_room.png (the equirectangular panorama
and its layers) from
  build/camsim render scenes/fisheye_sequence.yaml -o OUT --aov-previews
  build/camsim render scenes/panorama_room.yaml -o OUT --aov-previews
usage: make_model_figures.py OUT   (both into the same OUT; needs python3-matplotlib)"""
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg
import matplotlib.pyplot as plt

out = pathlib.Path(sys.argv[1])
docs = pathlib.Path(__file__).resolve().parent.parent / "docs" / "images"


def grid(name, layers, shape, size, target):
    fig, axes = plt.subplots(*shape, figsize=size)
    for ax in axes.flat:
        ax.axis("off")
    for ax, (suffix, title) in zip(axes.flat, layers):
        ax.imshow(mpimg.imread(out / f"{name}{suffix}.png"))
        ax.set_title(title, fontsize=9)
    fig.tight_layout()
    fig.savefig(docs / target, dpi=80, metadata={"Software": None})
    print(docs / target)


grid("fisheye_room_0002",
     [("", "picture (200° Kannala–Brandt)"), ("_depth", "depth.Z (log; z ≤ 0 black)"),
      ("_normal", "N (world)"), ("_instance", "instance.id"), ("_class", "class.id"),
      ("_motion", "motion_fw (hue: direction)"), ("_valid", "valid.A")],
     (2, 4), (12.8, 6.6), "fisheye_sequence.png")
grid("panorama_room",
     [("", "picture (equirectangular 360° × 180°)"), ("_depth", "depth.Z (log; z ≤ 0 black)"),
      ("_normal", "N (world)"), ("_instance", "instance.id")],
     (2, 2), (12.8, 6.8), "panorama_room.png")
