#!/usr/bin/env python3
# Plot of `camsim mtf` (embedded in the binary and run with /usr/bin/python3 -c).
#   mtf_plot.py CSV JSON PNG
#   mtf_plot.py --fields PNG CSV1 JSON1 [CSV2 JSON2 ...]   (several ROIs: mtf_fields.png)
# CSV: frequency_cy_px[, frequency_cy_mm], mtf_<channel>... (cli/mtf_command.cpp,
# sensor/measure/mtf_measurement.h); JSON: the report (MTF50 per channel, edge, ROI).
# One curve per channel (R, G, B in their colours, Y black) from 0 to 1 cycle/pixel, the
# Nyquist frequency (0.5) marked, each MTF50 as a dot; a top axis in cycles/mm when the
# pixel pitch is known.
import csv
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

COLOURS = {"R": "tab:red", "G": "tab:green", "B": "tab:blue", "Y": "black"}


def axes(ax, top_mtf, pitch):
    """Nyquist and MTF 0.5 marked, 0 … 1 cycle/px, cycles/mm on top when the pitch is known."""
    ax.axvline(0.5, color="0.5", ls="--", lw=1)
    ax.text(0.505, 1.02, "Nyquist", color="0.4", fontsize=8, va="bottom")
    ax.axhline(0.5, color="0.8", lw=0.8)
    ax.set_xlim(0, 1)
    ax.set_ylim(0, top_mtf)
    ax.set_xlabel("spatial frequency (cycles/pixel, along the edge normal)")
    ax.set_ylabel("MTF (e-SFR)")
    if pitch:
        top = ax.secondary_xaxis("top", functions=(lambda f: f / (pitch * 1e-3),
                                                   lambda n: n * pitch * 1e-3))
        top.set_xlabel("cycles/mm")


def main(argv):
    csv_path, json_path, png_path = argv[1:4]
    with open(csv_path, newline="") as f:
        rows = list(csv.DictReader(f))
    with open(json_path) as f:
        report = json.load(f)
    freq = [float(r["frequency_cy_px"]) for r in rows]
    fig, ax = plt.subplots(figsize=(7, 4.6), dpi=110)
    others = iter(["tab:purple", "tab:orange", "tab:brown", "tab:gray", "tab:olive"])
    for channel in report["channels"]:
        name = channel["name"]
        colour = COLOURS.get(name) or next(others, "tab:cyan")
        mtf = [float(r["mtf_" + name]) for r in rows]
        mtf50 = channel["mtf50_cy_px"]
        label = f"{name}: MTF50 {mtf50:.3f} cy/px" if mtf50 is not None else f"{name}: MTF50 > 1"
        ax.plot(freq, mtf, color=colour, lw=1.6 if name == "Y" else 1.2, label=label)
        if mtf50 is not None:
            ax.plot([mtf50], [0.5], "o", color=colour, ms=4)
    axes(ax, max(1.1, max(float(r["mtf_" + c["name"]]) for r in rows
                          for c in report["channels"]) * 1.05), report.get("pixel_pitch_um"))
    roi = report["roi"]
    field = report.get("field", {})
    where = f"  field {field['relative_height']:.2f}" if "relative_height" in field else ""
    if "height_mm" in field:
        where += f" ({field['height_mm']:.1f} mm)"
    ax.set_title(f"{report['source'].split('/')[-1]}  ROI {roi['x']},{roi['y']},"
                 f"{roi['width']},{roi['height']}{where}  {report['edge_orientation']} edge "
                 f"{report['edge_angle_deg']:.2f}°", fontsize=9)
    ax.legend(fontsize=8, loc="upper right")
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(png_path, format="png")


def fields(argv):
    """One curve per region: the Y channel (else the first), labelled with its field height."""
    png_path, pairs = argv[2], argv[3:]
    fig, ax = plt.subplots(figsize=(7, 4.6), dpi=110)
    colours = iter(["tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple",
                    "tab:brown", "tab:pink", "tab:gray", "tab:olive", "tab:cyan"])
    pitch = None
    for csv_path, json_path in zip(pairs[0::2], pairs[1::2]):
        with open(csv_path, newline="") as f:
            rows = list(csv.DictReader(f))
        with open(json_path) as f:
            report = json.load(f)
        names = [c["name"] for c in report["channels"]]
        name = "Y" if "Y" in names else names[0]
        channel = report["channels"][names.index(name)]
        field = report.get("field", {})
        pitch = report.get("pixel_pitch_um") or pitch
        label = f"field {field.get('relative_height', 0):.2f}"
        if "height_mm" in field:
            label += f" ({field['height_mm']:.1f} mm)"
        mtf50 = channel["mtf50_cy_px"]
        label += f", {name} MTF50 " + (f"{mtf50:.3f} cy/px" if mtf50 is not None else "> 1")
        c = next(colours, "black")
        ax.plot([float(r["frequency_cy_px"]) for r in rows],
                [float(r["mtf_" + name]) for r in rows], color=c, lw=1.4, label=label)
        if mtf50 is not None:
            ax.plot([mtf50], [0.5], "o", color=c, ms=4)
    axes(ax, 1.1, pitch)
    ax.legend(fontsize=8, loc="upper right", title="field height (over the half diagonal)",
              title_fontsize=8)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(png_path, format="png")


if __name__ == "__main__":
    if len(sys.argv) > 1 and sys.argv[1] == "--fields":
        fields(sys.argv)
    else:
        main(sys.argv)
