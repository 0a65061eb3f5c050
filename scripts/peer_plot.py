#!/usr/bin/env python3
# Plot of `camsim bench --peer cycles` (embedded in the binary and run with /usr/bin/python3 -c).
#   peer_plot.py CSV EQUAL_CSV PNG [NOTE]
# CSV: bench_peer.csv as written by integrator/measure/peer_compare.cpp (columns scene,
# renderer, width, height, max_depth, spp, seconds, rmse_rgb, floor_rmse_rgb, mrae_rgb, rmse_y,
# floor_rmse_y, mrae_y); EQUAL_CSV: bench_peer_equal.csv (scene, channel, target, cycles_spp,
# cycles_seconds, camsim_seconds, extrapolated, ratio), the report's equal-error lines. Per
# scene two panels, linear Rec.709 RGB and luminance Y: each renderer's error* (rMSE beyond its
# own reference's floor) against its render time, log-log, each point labelled with its spp,
# and the target — Cycles' error* at its top spp — as a dashed line, with camsim's time for it
# and the ratio to Cycles' in the legend, as the report computed them (the equal-error figures
# are read, not recomputed; a point's error* is rMSE − floor, points at or below 0 left out of
# the log axes). Also usable by hand on saved CSVs.
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

COLOURS = {"camsim": "tab:blue", "cycles": "tab:orange"}
NAMES = {"camsim": "camsim", "cycles": "Cycles"}


def panel(ax, rows, equal, key, floor_key, title):
    series = {}
    for r in rows:
        err = float(r[key]) - float(r[floor_key])
        if err > 0:
            series.setdefault(r["renderer"], []).append((float(r["seconds"]), err, int(r["spp"])))
    for renderer, pts in series.items():
        pts.sort()
        colour = COLOURS.get(renderer)
        ax.plot([p[0] for p in pts], [p[1] for p in pts], "o-", ms=4, lw=1, color=colour,
                label=NAMES.get(renderer, renderer))
        for t, e, spp in pts:
            ax.annotate(str(spp), (t, e), textcoords="offset points", xytext=(3, 3), fontsize=6,
                        color=colour)
    if equal and float(equal["target"]) > 0:
        label = (f"target: Cycles at {equal['cycles_spp']} spp, "
                 f"{float(equal['cycles_seconds']):.3g} s")
        if equal["camsim_seconds"]:
            label += (f"; camsim {float(equal['camsim_seconds']):.3g} s = "
                      f"{float(equal['ratio']):.2f}×")
            if equal["extrapolated"] == "1":
                label += " (extrapolated)"
        ax.axhline(float(equal["target"]), color="grey", ls="--", lw=1, label=label)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_title(title, fontsize=10)
    ax.set_xlabel("render time [s]")
    ax.set_ylabel("rMSE − reference floor")
    ax.grid(True, which="both", lw=0.3, alpha=0.5)
    ax.legend(fontsize=7, loc="lower left")


def main(argv):
    csv_path, equal_path, png_path = argv[1], argv[2], argv[3]
    note = argv[4] if len(argv) > 4 else ""
    with open(csv_path, newline="") as f:
        rows = list(csv.DictReader(f))
    with open(equal_path, newline="") as f:
        equal = {(r["scene"], r["channel"]): r for r in csv.DictReader(f)}
    scenes = list(dict.fromkeys(r["scene"] for r in rows))
    fig, axes = plt.subplots(max(1, len(scenes)), 2, figsize=(9.6, 3.9 * max(1, len(scenes))),
                             dpi=100, squeeze=False)
    for (ax_rgb, ax_y), scene in zip(axes, scenes):
        mine = [r for r in rows if r["scene"] == scene]
        size = f"{mine[0]['width']}×{mine[0]['height']} px, {mine[0]['max_depth']} events"
        panel(ax_rgb, mine, equal.get((scene, "rgb")), "rmse_rgb", "floor_rmse_rgb",
              f"{scene} ({size}): linear RGB")
        panel(ax_y, mine, equal.get((scene, "y")), "rmse_y", "floor_rmse_y",
              f"{scene}: luminance Y")
    fig.suptitle("camsim and Cycles: error against time" + (f" ({note})" if note else ""),
                 fontsize=11)
    fig.tight_layout()
    fig.savefig(png_path, format="png")


if __name__ == "__main__":
    main(sys.argv)
