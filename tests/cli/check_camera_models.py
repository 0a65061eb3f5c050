#!/usr/bin/python3
"""Projects rendered points with the camera model and intrinsics camsim exported in
cameras.json, through the real library where one implements the model and through the
model's published closed form otherwise, and compares them with the pixels they were
rendered at.

usage: check_camera_models.py CAMERAS_JSON POINTS_CSV TOLERANCE_PX
POINTS_CSV rows: frame index, pixel x, pixel y (OpenCV: pixel centres at integers),
world X, Y, Z. Prints the model, the point count and the largest error; exits 1 if it
exceeds the tolerance.

  opencv          cv2.projectPoints, the 14 coefficients k1 k2 p1 p2 k3 k4 k5 k6 s1..s4
                  tau_x tau_y (rational, thin prism, tilt)
  kannala_brandt  cv2.fisheye.projectPoints (D = k1..k4) for points in front (Z > 0);
                  cv2.fisheye works on X/Z and so mirrors a point behind the camera
                  (θ → 180° − θ): those are checked with the closed form
                  ρ = θ(1 + k1θ² + k2θ⁴ + k3θ⁶ + k4θ⁸) (Kannala & Brandt 2006), and the
                  mirror error cv2 would make is printed
  unified         cv2.omnidir.projectPoints (xi, D = k1 k2 p1 p2; Mei & Rives 2007)
  equidistant ρ = θ, equisolid ρ = 2 sin(θ/2), stereographic ρ = 2 tan(θ/2),
  orthographic ρ = sin θ, ftheta ρ = θ + k1θ² + k2θ³ + k3θ⁴ + k4θ⁵: m = ρ (X, Y)/√(X² + Y²)
  double_sphere   Usenko, Demmel, Cremers 2018 (eq. 40-43): d1 = |X|,
                  d2 = √(X² + Y² + (ξ d1 + Z)²), m = (X, Y)/(α d2 + (1 − α)(ξ d1 + Z))
  equirectangular λ = atan2(X, Z), φ = atan2(Y, √(X² + Z²)): u = cx + fx λ, v = cy + fy φ
                  (the error in u taken modulo the 2π·fx of a full turn)
and u = fx mx + cx, v = fy my + cy."""
import csv
import json
import math
import sys

import cv2
import numpy as np

RADIAL = {
    "equidistant": lambda t, c: t,
    "equisolid": lambda t, c: 2 * np.sin(t / 2),
    "stereographic": lambda t, c: 2 * np.tan(t / 2),
    "orthographic": lambda t, c: np.sin(t),
    "ftheta": lambda t, c: t + c["k1"] * t**2 + c["k2"] * t**3 + c["k3"] * t**4 + c["k4"] * t**5,
    "kannala_brandt": lambda t, c: t * (1 + c["k1"] * t**2 + c["k2"] * t**4 + c["k3"] * t**6
                                        + c["k4"] * t**8),
}


def radial(X, c):
    theta = np.arctan2(np.hypot(X[:, 0], X[:, 1]), X[:, 2])
    rho = RADIAL[c["model"]](theta, c)
    s = np.hypot(X[:, 0], X[:, 1])
    return np.stack([rho * X[:, 0] / s, rho * X[:, 1] / s], 1)


def double_sphere(X, c):
    xi, alpha = c["xi"], c["alpha"]
    d1 = np.linalg.norm(X, axis=1)
    d2 = np.sqrt(X[:, 0]**2 + X[:, 1]**2 + (xi * d1 + X[:, 2])**2)
    den = alpha * d2 + (1 - alpha) * (xi * d1 + X[:, 2])
    return np.stack([X[:, 0] / den, X[:, 1] / den], 1)


def pixels(m, c):
    return np.stack([c["fx"] * m[:, 0] + c["cx"], c["fy"] * m[:, 1] + c["cy"]], 1)


def project(X, c):
    """Pixels of camera-space points X (N×3, OpenCV axes); the method's name."""
    K = np.array([[c["fx"], 0, c["cx"]], [0, c["fy"], c["cy"]], [0, 0, 1]], dtype=np.float64)
    zero = np.zeros(3)
    model = c["model"]
    if model == "opencv":
        dist = np.array([c[k] for k in ("k1", "k2", "p1", "p2", "k3", "k4", "k5", "k6", "s1",
                                        "s2", "s3", "s4", "tau_x", "tau_y")])
        uv, _ = cv2.projectPoints(X, zero, zero, K, dist)
        return uv.reshape(-1, 2), "cv2.projectPoints (14 coefficients)"
    if model == "kannala_brandt":
        D = np.array([c["k1"], c["k2"], c["k3"], c["k4"]])
        uv, _ = cv2.fisheye.projectPoints(X.reshape(-1, 1, 3), zero, zero, K, D)
        uv = uv.reshape(-1, 2)
        behind = X[:, 2] <= 0
        closed = pixels(radial(X, c), c)
        if behind.any():
            mirror = np.hypot(*(uv[behind] - closed[behind]).T).max()
            print(f"  kannala_brandt: {behind.sum()} points behind the camera; cv2.fisheye "
                  f"puts them up to {mirror:.1f} px away (it mirrors θ > 90°), closed form used")
        uv[behind] = closed[behind]
        return uv, "cv2.fisheye.projectPoints (Z > 0) + closed form (Z <= 0)"
    if model == "unified":
        D = np.array([[c["k1"], c["k2"], c["p1"], c["p2"]]])
        uv, _ = cv2.omnidir.projectPoints(X.reshape(-1, 1, 3), zero.reshape(1, 3),
                                          zero.reshape(1, 3), K, c["xi"], D)
        return uv.reshape(-1, 2), "cv2.omnidir.projectPoints"
    if model == "double_sphere":
        return pixels(double_sphere(X, c), c), "closed form (Usenko et al. 2018)"
    if model == "equirectangular":
        lon = np.arctan2(X[:, 0], X[:, 2])
        lat = np.arctan2(X[:, 1], np.hypot(X[:, 0], X[:, 2]))
        return pixels(np.stack([lon, lat], 1), c), "closed form (longitude, latitude)"
    return pixels(radial(X, c), c), "closed form"


cameras = json.load(open(sys.argv[1]))["frames"]
rows = [[float(v) for v in r] for r in csv.reader(open(sys.argv[2]))]
worst, count, method = 0.0, 0, ""
for k, c in enumerate(cameras):
    sel = np.array([r for r in rows if int(r[0]) == k])
    if len(sel) == 0:
        continue
    cam_from_world = np.linalg.inv(np.array(c["world_from_camera_opencv"], dtype=np.float64))
    W = sel[:, 3:6]
    X = (cam_from_world[:3, :3] @ W.T).T + cam_from_world[:3, 3]
    uv, method = project(np.ascontiguousarray(X), c)
    d = uv - sel[:, 1:3]
    if c["model"] == "equirectangular":
        turn = 2 * math.pi * c["fx"]
        d[:, 0] = (d[:, 0] + turn / 2) % turn - turn / 2
    err = np.hypot(d[:, 0], d[:, 1])
    worst = max(worst, float(err.max()))
    count += len(sel)
print(f"{cameras[0]['model']}: {count} points, largest error {worst:.5f} px, {method} "
      f"(OpenCV {cv2.__version__})")
sys.exit(0 if count > 0 and worst <= float(sys.argv[3]) else 1)
