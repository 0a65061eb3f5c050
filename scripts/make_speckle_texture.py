#!/usr/bin/python3
"""Writes scenes/textures/speckle.png: a 256 x 256 grey speckle (value noise summed over five
octaves, seed 1), the feature-rich surface the example sequence's wall and floor carry
so that structure-from-motion tools (COLMAP's SIFT) find points to match. Deterministic:
the same bytes on every run. Needs python3-numpy and python3-matplotlib (Debian)."""
import pathlib

import matplotlib.image
import numpy as np

rng = np.random.default_rng(1)
size = 256
img = np.zeros((size, size))
for octave, cells in enumerate((8, 16, 32, 64, 128)):
    coarse = rng.random((cells, cells))
    # Nearest-cell upsampling then a separable box blur: soft blobs of this octave's size.
    up = np.kron(coarse, np.ones((size // cells, size // cells)))
    k = size // cells
    kernel = np.ones(k) / k
    for axis in (0, 1):
        up = np.apply_along_axis(lambda r: np.convolve(np.concatenate([r[-k:], r, r[:k]]), kernel, "same")[k:-k], axis, up)
    img += up / 1.6 ** octave
img = (img - img.min()) / (img.max() - img.min())
img = 0.1 + 0.75 * img  # reflectance 0.1 … 0.85 once decoded from sRGB
out = pathlib.Path(__file__).resolve().parent.parent / "scenes" / "textures" / "speckle.png"
matplotlib.image.imsave(out, np.stack([img] * 3, axis=-1), vmin=0.0, vmax=1.0, metadata={"Software": None})
print(out)
