"""Where a render's luminance error lies: the share of its rMSE (camsim bench's weighting,
e^2/(r^2 + eps^2), eps = 1 % of the reference's mean) held by the darkest and brightest
pixels of the reference and by the bottom rows. docs/performance.md, "The Cornell box's
luminance gap: where the error is, and what did not pay".

RENDER: a `camsim render` EXR (its XYZ.Y channel). REFERENCE: an EXR with a Y channel, or the
peer bench's cached reference (build/bench-cache/peer-SCENE-camsim-KEY.exr: halves A.Y, B.Y,
averaged), of the same size.

Usage: PYTHONPATH=build/python /usr/bin/python3 bench/error_by_brightness.py RENDER REFERENCE
"""
import sys

import numpy as np

import camsim


def channel(path, names):
    channels = camsim.read_exr(path)["channels"]
    found = [n for n in names if n in channels]
    if not found:
        sys.exit(f"{path}: none of the channels {', '.join(names)}")
    return np.asarray(channels[found[0]], dtype=np.float64)


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    render = channel(sys.argv[1], ["XYZ.Y", "Y"])
    refs = camsim.read_exr(sys.argv[2])["channels"]
    if "A.Y" in refs and "B.Y" in refs:
        ref = 0.5 * (np.asarray(refs["A.Y"], np.float64) + np.asarray(refs["B.Y"], np.float64))
    else:
        ref = channel(sys.argv[2], ["Y", "XYZ.Y"])
    if ref.shape != render.shape:
        sys.exit(f"sizes differ: {render.shape} against {ref.shape}")
    eps = 0.01 * abs(ref.mean())
    e2 = (render - ref) ** 2 / (ref * ref + eps * eps)
    total = e2.sum()
    print(f"rMSE Y {e2.mean():.4g} (render mean / reference mean {render.mean() / ref.mean():.4f})")
    order = np.sort(ref.ravel())
    for label, lo, hi in [("darkest 10 %", 0.0, 0.1), ("darkest 25 %", 0.0, 0.25),
                          ("brightest 25 %", 0.75, 1.0)]:
        a = order[int(lo * (order.size - 1))]
        b = order[int(hi * (order.size - 1))]
        share = e2[(ref >= a) & (ref <= b)].sum() / total
        print(f"{label:>15}: {100 * share:5.1f} % of the rMSE")
    rows = ref.shape[0]
    print(f"{'bottom 30 % rows':>15}: {100 * e2[int(0.7 * rows):].sum() / total:5.1f} % of the rMSE")


if __name__ == "__main__":
    main()
