"""Would sampling the Cornell box's lamp by solid angle (Urena et al. 2013) instead of by area
pay? The relative variance of one light sample's estimate of direct irradiance (visibility
ignored: cos at the point x cos at the lamp / r^2 over the lamp's area) at random points on
the floor and the three walls, under area and under solid-angle sampling, pooled over a
face as sum(variance) / sum(mean^2). The geometry is approximately scenes/cornell_box.yaml's
(the lamp exactly; the walls as axis-aligned planes, points below the lamp's plane). docs/performance.md, "The Cornell box's luminance gap: where the
error is, and what did not pay".

Usage: /usr/bin/python3 bench/light_solid_angle_variance.py [POINTS [LAMP_SAMPLES]]
"""
import sys

import numpy as np

CORNER = np.array([0.343, 0.5487, 0.227])  # m, the lamp (scenes/cornell_box.yaml)
EDGE_U = np.array([0.0, 0.0, 0.105])
EDGE_V = np.array([-0.130, 0.0, 0.0])
LAMP_NORMAL = np.array([0.0, -1.0, 0.0])
AREA = 0.105 * 0.130


def moments(p, n, rng, count):
    """Mean and variance of the area-sampled and the solid-angle-sampled estimate at p."""
    u = rng.random((count, 2))
    q = CORNER + u[:, :1] * EDGE_U + u[:, 1:] * EDGE_V
    d = q - p
    r2 = (d * d).sum(1)
    w = d / np.sqrt(r2)[:, None]
    cos_here = np.clip(w @ n, 0.0, None)
    cos_lamp = np.clip(-(w @ LAMP_NORMAL), 0.0, None)
    area = cos_here * cos_lamp / r2 * AREA  # f / p_area
    g = cos_lamp / r2  # solid angle per area: p_sa / p_area up to the lamp's solid angle
    if not g.any():  # the lamp is not seen from p
        return 0.0, 0.0, 0.0
    solid_angle = g.mean() * AREA  # the lamp's solid angle from p (sr)
    m1 = (cos_here * g).mean() / g.mean()  # E_sa[cos_here]
    m2 = (cos_here ** 2 * g).mean() / g.mean()
    sa_var = (m2 - m1 * m1) * solid_angle ** 2  # estimate = cos_here x solid angle
    return area.mean(), area.var(), sa_var


def main():
    try:
        points = int(sys.argv[1]) if len(sys.argv) > 1 else 200
        lamp = int(sys.argv[2]) if len(sys.argv) > 2 else 4000
    except ValueError:
        sys.exit(__doc__)
    if len(sys.argv) > 3 or points < 1 or lamp < 2:
        sys.exit(__doc__)
    top = 0.5487  # the lamp's plane (m): wall points below it see the lamp's front
    rng = np.random.default_rng(1)
    faces = [
        ("floor", [0, 1, 0], lambda: [rng.random() * 0.55, 0.0, rng.random() * 0.559]),
        ("green wall", [1, 0, 0], lambda: [0.0, rng.random() * top, rng.random() * 0.559]),
        ("red wall", [-1, 0, 0], lambda: [0.55, rng.random() * top, rng.random() * 0.559]),
        ("back wall", [0, 0, -1], lambda: [rng.random() * 0.55, rng.random() * top, 0.559]),
    ]
    for name, normal, point in faces:
        n = np.array(normal, dtype=np.float64)
        rows = [moments(np.array(point()), n, rng, lamp) for _ in range(points)]
        mean2 = sum(m * m for m, _, _ in rows)
        area_var = sum(v for _, v, _ in rows)
        sa_var = sum(s for _, _, s in rows)
        if mean2 == 0.0 or sa_var == 0.0:
            print(f"{name:>10}: the lamp lights none of the points")
            continue
        print(f"{name:>10}: relative variance per light sample: area {area_var / mean2:.4f}, "
              f"solid angle {sa_var / mean2:.4f} ({area_var / sa_var:.1f}x less)")


if __name__ == "__main__":
    main()
