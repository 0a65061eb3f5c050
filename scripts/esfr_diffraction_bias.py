#!/usr/bin/env python3
# How far the e-SFR (sensor/measure/slanted_edge.h, docs/mtf.md) reads above the
# diffraction-limited MTF of a circular pupil because its ROI and Hamming window cut off the
# Airy line spread's tail (which falls only as 1/x²): the method's steps 5–7 applied to the
# analytic ESF of an in-focus edge, with no noise and no edge fit.
#   esfr_diffraction_bias.py PITCH_UM N_W LAMBDA_NM WIDTH_PX...
# e.g. `esfr_diffraction_bias.py 2 8.0483 550 96 128 160` (the test
# DiffractionRender.EdgeMtfAtF8And550NmIsTheDiffractionLimitedMtf's camera).
#
# Model: the edge's MTF is D(ν)·sinc(f)·sinc(f/4) (ν = f·λN_w/pitch; D the circular pupil's
# diffraction MTF; the photosite's box and ISO's ¼-px bins along the normal), so its ESF on
# the ¼-px bins u_b (px from the edge) is ½ + ∫₀^fc M(f) sin(2πf·u_b)/(πf) df. Then the
# central-difference LSF, the Hamming window over the N = 4·WIDTH bins, the DFT normalised
# at 0 and the central difference's correction, as the measurement does. Prints, per ROI
# width, the largest error (measured − M) from 0 to the cut-off fc and where it is.
import sys

import numpy as np


def pupil_mtf(nu):
    nu = np.clip(np.abs(nu), 0.0, 1.0)
    return 2.0 / np.pi * (np.arccos(nu) - nu * np.sqrt(1.0 - nu * nu))


def main():
    pitch = float(sys.argv[1]) * 1e-6
    nw = float(sys.argv[2])
    lam = float(sys.argv[3]) * 1e-9
    cutoff = pitch / (lam * nw)  # cycles/px
    fq = np.linspace(0.0, cutoff, 4001)
    dq = fq[1] - fq[0]
    trapezoid = np.ones_like(fq)
    trapezoid[[0, -1]] = 0.5
    optics = pupil_mtf(fq / cutoff) * np.sinc(fq) * np.sinc(fq / 4.0)
    print(f"cut-off {cutoff:.4f} cycles/px (pitch {pitch * 1e6:g} um, N_w {nw:g}, {lam * 1e9:g} nm)")
    for width in (int(a) for a in sys.argv[4:]):
        n = 4 * width
        u = (np.arange(n) - n / 2 + 0.5) / 4.0  # bin centres, px from the edge
        kernel = np.where(fq[None, :] > 0,
                          np.sin(2 * np.pi * fq[None, :] * u[:, None]) / (np.pi * np.maximum(fq, 1e-30)),
                          2.0 * u[:, None])
        esf = 0.5 + (optics * trapezoid * kernel).sum(axis=1) * dq
        lsf = np.zeros(n)
        lsf[1:-1] = 0.5 * (esf[2:] - esf[:-2])
        lsf[0], lsf[-1] = lsf[1], lsf[-2]
        window = 0.54 + 0.46 * np.cos(2 * np.pi * (np.arange(n) - (n - 1) / 2) / (n - 1))
        spectrum = np.abs(np.fft.fft(lsf * window))
        k = np.arange(n // 4 + 1)
        f = 4.0 * k / n
        correction = np.ones_like(f)
        correction[1:] = (2 * np.pi * k[1:] / n) / np.sin(2 * np.pi * k[1:] / n)
        measured = spectrum[: n // 4 + 1] / spectrum[0] * correction
        expected = pupil_mtf(f / cutoff) * np.sinc(f) * np.sinc(f / 4.0)
        inside = f <= cutoff
        err = (measured - expected)[inside]
        worst = int(np.argmax(np.abs(err)))
        print(f"ROI {width:4d} px ({width * pitch / (lam * nw):5.1f} lambda N_w): "
              f"max error {err[worst]:+.4f} at {f[inside][worst]:.3f} cycles/px")


if __name__ == "__main__":
    main()
