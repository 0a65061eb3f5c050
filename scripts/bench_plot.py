#!/usr/bin/env python3
# Plot of `camsim bench` (embedded in the binary and run with /usr/bin/python3 -c).
#   bench_plot.py CSV PNG [NOTE]
# CSV: bench.csv as written by integrator/measure/bench_metrics.cpp (columns scene, sampler, spp, width,
# height, seconds, cpu_seconds, samples_per_s, rays_per_s, rmse_rel, mrae, ref_rmse_rel,
# ref_mrae, in_fit). One panel per scene: rMSE of luminance Y against render time (log-log) for each
# sampler, filled markers for the budgets in the slope fit, the fitted line with its slope in
# the legend, and the reference's noise floor (dotted). Also usable by hand on a saved CSV.
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

COLOURS = {"independent": "tab:orange", "sobol": "tab:blue"}


def fit(points):
    """Least squares of log10 y on log10 x: (slope, intercept) or None."""
    if len(points) < 2:
        return None
    lx = [math.log10(x) for x, _ in points]
    ly = [math.log10(y) for _, y in points]
    n = len(points)
    mx, my = sum(lx) / n, sum(ly) / n
    sxx = sum((a - mx) ** 2 for a in lx)
    if sxx <= 0:
        return None
    slope = sum((a - mx) * (b - my) for a, b in zip(lx, ly)) / sxx
    return slope, my - slope * mx


def main(argv):
    csv_path, png_path = argv[1], argv[2]
    note = argv[3] if len(argv) > 3 else ""
    with open(csv_path, newline="") as f:
        rows = list(csv.DictReader(f))
    scenes = list(dict.fromkeys(r["scene"] for r in rows))
    cols = min(3, len(scenes))
    nrows = math.ceil(len(scenes) / cols)
    fig, axes = plt.subplots(nrows, cols, figsize=(4.6 * cols, 3.8 * nrows), dpi=100, squeeze=False)
    for ax in axes.flat[len(scenes):]:
        ax.set_visible(False)
    for ax, scene in zip(axes.flat, scenes):
        mine = [r for r in rows if r["scene"] == scene]
        for sampler in dict.fromkeys(r["sampler"] for r in mine):
            pts = [r for r in mine if r["sampler"] == sampler]
            t = [float(r["seconds"]) for r in pts]
            e = [float(r["rmse_rel"]) for r in pts]
            used = [int(r["in_fit"]) > 0 for r in pts]
            colour = COLOURS.get(sampler, None)
            ax.plot(t, e, "-", color=colour, lw=0.8, alpha=0.6)
            ax.plot([a for a, u in zip(t, used) if u], [b for b, u in zip(e, used) if u], "o", ms=4,
                    color=colour)
            ax.plot([a for a, u in zip(t, used) if not u], [b for b, u in zip(e, used) if not u], "o",
                    ms=4, mfc="none", color=colour)
            line = fit([(a, b) for a, b, u in zip(t, e, used) if u])
            label = sampler
            if line:
                slope, icept = line
                xs = [a for a, u in zip(t, used) if u]
                x0, x1 = min(xs), max(xs)
                ax.plot([x0, x1], [10 ** (icept + slope * math.log10(x0)), 10 ** (icept + slope * math.log10(x1))],
                        "--", color=colour, lw=1.2)
                label += f" (slope {slope:.2f})"
            ax.plot([], [], "o-", color=colour, label=label)
        floor = float(mine[0]["ref_rmse_rel"])
        if floor > 0:
            ax.axhline(floor, color="grey", ls=":", lw=1, label="reference noise floor")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(f"{scene} ({mine[0]['width']}×{mine[0]['height']} px)", fontsize=10)
        ax.set_xlabel("render time [s]")
        ax.set_ylabel("rMSE of luminance Y")
        ax.grid(True, which="both", lw=0.3, alpha=0.5)
        ax.legend(fontsize=7, loc="lower left")
    fig.suptitle("camsim bench: error against time" + (f" ({note})" if note else ""), fontsize=11)
    fig.tight_layout()
    fig.savefig(png_path, format="png")


if __name__ == "__main__":
    main(sys.argv)
