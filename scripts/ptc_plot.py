#!/usr/bin/env python3
# Plots of `camsim ptc` (embedded in the binary and run with /usr/bin/python3 -c).
#   ptc_plot.py CSV JSON NAME PTC_PNG SNR_PNG [GAIN_PNG NOISE_PNG]
# CSV: the per-level table written by cli/ptc_command.cpp (an `iso` column); JSON: the report
# (cli/ptc_report.cpp). Plots, EMVA 1288 Release 4.0:
#   PTC_PNG: photon transfer, var_y - var_y.dark against mu_y - mu_y.dark, with the fitted
#            line of slope K (solid over the 0-70 % fit range) and the saturation point;
#            several ISOs: one series per ISO on log-log axes;
#   SNR_PNG: SNR against mu_p (log-log) with the ideal sqrt(mu_p) and the linear model
#            eta*mu_p / sqrt(sigma_d^2 + sigma_q^2/K^2 + eta*mu_p), up to saturation;
#   GAIN_PNG (several ISOs): K against ISO, measured with error bars, the fitted K = g*ISO
#            per conversion-gain segment, and the configured K;
#   NOISE_PNG (several ISOs): sigma_d (e-) against ISO, measured, from the sigma_pre /
#            sigma_post split and configured; and sigma_row, sigma_read (DN).
import csv
import json
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def q(iso, name):
    return iso["quantities"][name]


def main(argv):
    csv_path, json_path, name, ptc_png, snr_png = argv[1:6]
    extra = argv[6:8]
    with open(csv_path, newline="") as f:
        rows = [{key: float(val) for key, val in row.items()} for row in csv.DictReader(f)]
    with open(json_path) as f:
        report = json.load(f)
    isos = report["isos"]
    many = len(isos) > 1
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]

    fig, ax = plt.subplots(figsize=(7, 4.8), dpi=110)
    fig2, ax2 = plt.subplots(figsize=(7, 4.8), dpi=110)
    for n, iso in enumerate(isos):
        c = colours[n % len(colours)]
        own = [r for r in rows if r["iso"] == iso["iso"]]
        k = q(iso, "system_gain_k")["value"]
        eta = q(iso, "quantum_efficiency")["value"]
        sigma_d = q(iso, "dark_noise_e")["value"]
        mu_p_sat = q(iso, "mu_p_sat")["value"]
        mu_p_min = q(iso, "mu_p_min")["value"]
        tag = f"ISO {iso['iso']:g}: " if many else ""
        x = [r["mu_y_minus_dark"] for r in own]
        y = [r["var_y_minus_dark"] for r in own]
        fit = [r["in_gain_fit"] > 0 for r in own]
        sat = next(i for i, r in enumerate(own) if r["saturation"] > 0)
        keep = [i for i in range(len(own)) if not many or (x[i] > 0 and y[i] > 0)]
        ax.plot([x[i] for i in keep if fit[i]], [y[i] for i in keep if fit[i]], "o", ms=4,
                color=c, label=f"{tag}measured, fit range (0–70 % of saturation)")
        ax.plot([x[i] for i in keep if not fit[i]], [y[i] for i in keep if not fit[i]], "o",
                ms=4, mfc="none", color=c, label=None if many else "measured, outside the fit")
        x_fit = max(v for v, f in zip(x, fit) if f)
        x_lo = min(v for v in x if v > 0) if many else 0
        ax.plot([x_lo, x_fit], [k * x_lo, k * x_fit], "-", color=c if many else "tab:red",
                lw=1.5, label=f"{tag}fit: K = {k:.4g} DN/e⁻")
        ax.plot([x[sat]], [y[sat]], "s", ms=8, mfc="none", color="black",
                label=None if many and n else f"saturation (variance maximum)"
                + ("" if many else f", μ_p.sat = {mu_p_sat:.4g}"))

        # SNR up to saturation (beyond it the temporal variance collapses).
        mu_p = [r["mu_p"] for r in own[:sat + 1] if r["snr"] > 0]
        snr = [r["snr"] for r in own[:sat + 1] if r["snr"] > 0]
        lo = min(mu_p_min, min(mu_p)) / 2
        grid = [lo * (mu_p_sat / lo) ** (i / 300) for i in range(301)]
        model = [eta * p / math.sqrt(sigma_d ** 2 + 1 / 12 / k ** 2 + eta * p) for p in grid]
        if n == 0:
            ax2.loglog(grid, [math.sqrt(p) for p in grid], ":", color="gray", label="ideal: √μ_p")
        ax2.loglog(grid, model, "-", color=c if many else "tab:red", lw=1.2,
                   label=f"{tag}model: η = {eta:.3g}, σ_d = {sigma_d:.3g} e⁻, K = {k:.3g} DN/e⁻")
        ax2.loglog(mu_p, snr, "o", ms=3 if many else 4, color=c if many else "tab:blue",
                   label=None if many else "measured (temporal), to saturation")
        ax2.axvline(mu_p_min, color=c if many else "tab:green", lw=1, ls="--",
                    label=None if many else f"μ_p.min = {mu_p_min:.3g} (SNR = 1)")
        if not many:
            ax2.axvline(mu_p_sat, color="black", lw=1, ls="--", label=f"μ_p.sat = {mu_p_sat:.4g}")

    ax.set_xlabel("μ_y − μ_y.dark  [DN]")
    ax.set_ylabel("σ²_y − σ²_y.dark  [DN²]")
    ax.set_title(f"Photon transfer: {name} (EMVA 1288 Release 4.0)")
    if many:
        ax.set_xscale("log")
        ax.set_yscale("log")
    else:
        ax.set_xlim(left=0)
        ax.set_ylim(bottom=0)
    ax.grid(alpha=0.3, which="both")
    ax.legend(loc="upper left", fontsize=7 if many else 8)
    fig.tight_layout()
    fig.savefig(ptc_png, format="png")
    plt.close(fig)
    ax2.set_xlabel("μ_p  [photons per pixel]")
    ax2.set_ylabel("SNR")
    ax2.set_title(f"Signal-to-noise ratio: {name}")
    ax2.grid(alpha=0.3, which="both")
    ax2.legend(loc="upper left", fontsize=7 if many else 8)
    fig2.tight_layout()
    fig2.savefig(snr_png, format="png")
    plt.close(fig2)
    if len(extra) == 2:
        plot_isos(report, name, *extra)
    return 0


def plot_isos(report, name, gain_png, noise_png):
    isos = report["isos"]
    iso = [i["iso"] for i in isos]
    fig, ax = plt.subplots(figsize=(7, 4.8), dpi=110)
    k = [q(i, "system_gain_k") for i in isos]
    ax.errorbar(iso, [v["value"] for v in k], yerr=[v["uncertainty"] for v in k], fmt="o",
                color="tab:blue", label="measured K (± u)")
    ax.plot(iso, [v["configured"] for v in k], "x", ms=9, color="black", label="configured K")
    for s in report["fits"]["gain_segments"]:
        g = s["gain_per_iso"]["value"]
        xs = [s["iso_min"], s["iso_max"]]
        ax.plot(xs, [g * v for v in xs], "-", color="tab:red", lw=1.2)
    ax.plot([], [], "-", color="tab:red", label="fit K = g·ISO per conversion-gain segment")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("ISO")
    ax.set_ylabel("system gain K  [DN/e⁻]")
    ax.set_title(f"System gain against ISO: {name}")
    ax.grid(alpha=0.3, which="both")
    ax.legend(loc="upper left", fontsize=8)
    fig.tight_layout()
    fig.savefig(gain_png, format="png")
    plt.close(fig)

    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 4.6), dpi=110)
    d = [q(i, "dark_noise_e") for i in isos]
    a1.errorbar(iso, [v["value"] for v in d], yerr=[v["uncertainty"] for v in d], fmt="o",
                color="tab:blue", label="measured σ_d (± u)")
    a1.plot(iso, [v["configured"] for v in d], "x", ms=9, color="black", label="configured σ_d")
    fitted = [p["fitted_e"] for p in report["fits"]["dark_noise_e"]]
    if all(v is not None for v in fitted):
        split = report["fits"]["dark_noise_split"]["sigma_post_dn"]["value"]
        a1.plot(iso, fitted, "-", color="tab:red",
                label=f"split fit: σ_pre per segment, σ_post = {split:.3g} DN")
    a1.set_xscale("log")
    a1.set_yscale("log")
    a1.set_xlabel("ISO")
    a1.set_ylabel("temporal dark noise σ_d  [e⁻]")
    a1.grid(alpha=0.3, which="both")
    a1.legend(fontsize=7)
    for key, label, c in (("sigma_y_dark", "σ_y.dark", "tab:blue"),
                          ("read_noise_gaussian_dn", "σ_read (normal plot)", "tab:green"),
                          ("row_noise_dn", "σ_row (temporal)", "tab:orange")):
        v = [q(i, key) for i in isos]
        a2.errorbar(iso, [x["value"] for x in v], yerr=[x["uncertainty"] for x in v], fmt="o-",
                    color=c, ms=4, label=label)
    a2.set_xscale("log")
    a2.set_yscale("symlog", linthresh=0.1)
    a2.set_xlabel("ISO")
    a2.set_ylabel("noise  [DN]")
    a2.grid(alpha=0.3, which="both")
    a2.legend(fontsize=7)
    fig.suptitle(f"Noise against ISO: {name}")
    fig.tight_layout()
    fig.savefig(noise_png, format="png")
    plt.close(fig)


if __name__ == "__main__":
    sys.exit(main(sys.argv))
