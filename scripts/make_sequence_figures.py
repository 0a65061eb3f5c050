#!/usr/bin/python3
"""Makes docs/images/rolling_balls_sequence.png (the 6 frames) and
docs/images/rolling_balls_aovs.png (frame 2's picture and ground-truth quick looks) from
  build/camsim render scenes/rolling_balls_sequence.yaml -o OUT --aov-previews
usage: make_sequence_figures.py OUT   (needs python3-matplotlib)"""
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg
import matplotlib.pyplot as plt

out = pathlib.Path(sys.argv[1])
docs = pathlib.Path(__file__).resolve().parent.parent / "docs" / "images"

frames = sorted(out.glob("rolling_balls_[0-9][0-9][0-9][0-9].png"))
fig, axes = plt.subplots(2, 3, figsize=(10.8, 4.9))
for ax, f in zip(axes.flat, frames):
    ax.imshow(mpimg.imread(f))
    ax.set_title(f.name, fontsize=9)
    ax.axis("off")
fig.tight_layout()
fig.savefig(docs / "rolling_balls_sequence.png", dpi=80, metadata={"Software": None})

layers = [("", "picture"), ("_depth", "depth.Z (log, near bright)"), ("_normal", "N (world)"),
          ("_albedo", "albedo"), ("_instance", "instance.id"), ("_class", "class.id"),
          ("_material", "material.id"), ("_motion", "motion_fw (hue: direction)")]
fig, axes = plt.subplots(2, 4, figsize=(12.8, 4.6))
for ax, (suffix, title) in zip(axes.flat, layers):
    ax.imshow(mpimg.imread(out / f"rolling_balls_0002{suffix}.png"))
    ax.set_title(title, fontsize=9)
    ax.axis("off")
fig.tight_layout()
fig.savefig(docs / "rolling_balls_aovs.png", dpi=80, metadata={"Software": None})
print(docs / "rolling_balls_sequence.png", docs / "rolling_balls_aovs.png")
