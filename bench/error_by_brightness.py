"""Where a render's luminance error lies: the share of its rMSE (camsim bench's weighting,
e^2/(r^2 + eps^2), eps = 1 % of the reference's mean) held by the darkest and brightest
pixels of the reference and by the bottom rows. Pixels whose reference is exactly 0 (a
frame around the scene that nothing lights) are left out of the ranking; they are counted
in the rMSE, which they do not change. docs/performance.md, "The Cornell box's
luminance gap: where the error is, and what did not pay".

RENDER: a `camsim render` EXR (its XYZ.Y channel). REFERENCE: an EXR with a Y channel, or the
peer bench's cached reference (build/bench-cache/peer-SCENE-camsim-KEY.exr: halves A.Y, B.Y,
averaged), of the same size and units (a camsim render at the reference's max_depth: the peer bench's
is --peer-max-depth, 9 for the Cornell box in docs/performance.md).

Usage: PYTHONPATH=build/python /usr/bin/python3 bench/error_by_brightness.py RENDER REFERENCE
"""
import sys

import numpy as np

import camsim


def read(path):
    try:
        return camsim.read_exr(path)["channels"]
    except camsim.InputError as e:
        sys.exit(str(e))


def channel(path, names):
    channels = read(path)
    found = [n for n in names if n in channels]
    if not found:
        sys.exit(f"{path}: none of the channels {', '.join(names)}")
    return np.asarray(channels[found[0]], dtype=np.float64)


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    render = channel(sys.argv[1], ["XYZ.Y", "Y"])
    refs = read(sys.argv[2])
    if "A.Y" in refs and "B.Y" in refs:
        ref = 0.5 * (np.asarray(refs["A.Y"], np.float64) + np.asarray(refs["B.Y"], np.float64))
    else:
        ref = channel(sys.argv[2], ["Y", "XYZ.Y"])
    if ref.shape != render.shape:
        sys.exit(f"sizes differ: {render.shape} against {ref.shape}")
    eps = 0.01 * abs(ref.mean())
    e2 = (render - ref) ** 2 / (ref * ref + eps * eps)
    total = e2.sum()
    ratio = render.mean() / ref.mean() if ref.mean() != 0 else float("nan")
    print(f"rMSE Y {e2.mean():.3e} (render mean / reference mean {ratio:.4f})")
    if not abs(ratio - 1.0) < 0.05:
        print("warning: the means differ by more than 5 %: not the same scene, depth or units?")
    lit = ref > 0
    print(f"pixels with reference 0 (left out below): {100 * (1 - lit.mean()):.1f} %")
    # Lit pixels ranked by the reference's Y (ties broken by position: exact fractions).
    order = np.argsort(ref[lit], kind="stable")
    e2_lit = e2[lit][order]
    n = e2_lit.size
    for label, lo, hi in [("darkest 10 %", 0.0, 0.1), ("darkest 25 %", 0.0, 0.25),
                          ("brightest 25 %", 0.75, 1.0)]:
        share = e2_lit[int(lo * n):int(hi * n)].sum() / total
        print(f"{label:>16}: {100 * share:5.1f} % of the rMSE")
    rows = ref.shape[0]
    print(f"{'bottom 30 % rows':>16}: {100 * e2[int(0.7 * rows):].sum() / total:5.1f} % of the rMSE")

if __name__ == "__main__":
    main()
