#!/usr/bin/env python3
# Plots of `camsim ptc` (embedded in the binary and run with /usr/bin/python3 -c).
#   ptc_plot.py CSV PTC_PNG SNR_PNG NAME K ETA SIGMA_D MU_P_SAT MU_P_MIN
# CSV: the per-level table written by cli/ptc_command.cpp. Plots, EMVA 1288 Release 4.0:
#   PTC_PNG: photon transfer, var_y - var_y.dark against mu_y - mu_y.dark, with the fitted
#            line of slope K (solid over the 0-70 % fit range) and the saturation point;
#   SNR_PNG: SNR against mu_p (log-log) with the ideal sqrt(mu_p) and the linear model
#            eta*mu_p / sqrt(sigma_d^2 + sigma_q^2/K^2 + eta*mu_p), up to saturation.
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(argv):
    csv_path, ptc_png, snr_png, name = argv[1:5]
    k, eta, sigma_d, mu_p_sat, mu_p_min = (float(v) for v in argv[5:10])
    with open(csv_path, newline="") as f:
        rows = [{key: float(val) for key, val in row.items()} for row in csv.DictReader(f)]
    x = [r["mu_y_minus_dark"] for r in rows]
    y = [r["var_y_minus_dark"] for r in rows]
    fit = [r["in_gain_fit"] > 0 for r in rows]
    sat = next(i for i, r in enumerate(rows) if r["saturation"] > 0)

    fig, ax = plt.subplots(figsize=(7, 4.8), dpi=110)
    ax.plot([v for v, f in zip(x, fit) if f], [v for v, f in zip(y, fit) if f], "o",
            ms=4, color="tab:blue", label="measured, fit range (0–70 % of saturation)")
    ax.plot([v for v, f in zip(x, fit) if not f], [v for v, f in zip(y, fit) if not f], "o",
            ms=4, mfc="none", color="tab:blue", label="measured, outside the fit")
    x_fit = max(v for v, f in zip(x, fit) if f)
    ax.plot([0, x_fit], [0, k * x_fit], "-", color="tab:red", lw=1.5,
            label=f"fit: K = {k:.4g} DN/e⁻")
    ax.plot([x_fit, x[sat]], [k * x_fit, k * x[sat]], "--", color="tab:red", lw=1)
    ax.plot([x[sat]], [y[sat]], "s", ms=8, mfc="none", color="black",
            label=f"saturation (variance maximum), μ_p.sat = {mu_p_sat:.4g}")
    ax.set_xlabel("μ_y − μ_y.dark  [DN]")
    ax.set_ylabel("σ²_y − σ²_y.dark  [DN²]")
    ax.set_title(f"Photon transfer: {name} (EMVA 1288 Release 4.0)")
    ax.set_xlim(left=0)
    ax.set_ylim(bottom=0)
    ax.grid(alpha=0.3)
    ax.legend(loc="upper left", fontsize=8)
    fig.tight_layout()
    fig.savefig(ptc_png, format="png")
    plt.close(fig)

    # Up to saturation (beyond it the temporal variance collapses and the SNR is meaningless).
    mu_p = [r["mu_p"] for r in rows[:sat + 1] if r["snr"] > 0]
    snr = [r["snr"] for r in rows[:sat + 1] if r["snr"] > 0]
    lo = min(mu_p_min, min(mu_p)) / 2
    grid = [lo * (mu_p_sat / lo) ** (i / 300) for i in range(301)]
    model = [eta * p / math.sqrt(sigma_d ** 2 + 1 / 12 / k ** 2 + eta * p) for p in grid]
    fig, ax = plt.subplots(figsize=(7, 4.8), dpi=110)
    ax.loglog(grid, [math.sqrt(p) for p in grid], ":", color="gray", label="ideal: √μ_p")
    ax.loglog(grid, model, "-", color="tab:red", lw=1.2,
              label=f"model: η = {eta:.3g}, σ_d = {sigma_d:.3g} e⁻, K = {k:.3g} DN/e⁻")
    ax.loglog(mu_p, snr, "o", ms=4, color="tab:blue", label="measured (temporal), to saturation")
    ax.axvline(mu_p_min, color="tab:green", lw=1, ls="--",
               label=f"μ_p.min = {mu_p_min:.3g} (SNR = 1)")
    ax.axvline(mu_p_sat, color="black", lw=1, ls="--", label=f"μ_p.sat = {mu_p_sat:.4g}")
    ax.set_xlabel("μ_p  [photons per pixel]")
    ax.set_ylabel("SNR")
    ax.set_title(f"Signal-to-noise ratio: {name}")
    ax.grid(alpha=0.3, which="both")
    ax.legend(loc="upper left", fontsize=8)
    fig.tight_layout()
    fig.savefig(snr_png, format="png")
    plt.close(fig)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
