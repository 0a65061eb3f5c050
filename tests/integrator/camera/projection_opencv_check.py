#!/usr/bin/python3
"""Projects camera-space points through the real OpenCV and compares the pixels with the
ones camsim's projection models (integrator/camera/projection.h) computed.

usage: projection_opencv_check.py CSV TOLERANCE_PX
CSV rows: case name, fx, fy, cx, cy, k1..k6, p1, p2, s1..s4, tau_x, tau_y, xi, X, Y, Z,
u, v.
The case name picks OpenCV's function: "opencv*" -> cv2.projectPoints with the 14
coefficients (k1 k2 p1 p2 k3 k4 k5 k6 s1 s2 s3 s4 tau_x tau_y), "kannala_brandt" and "equidistant" ->
cv2.fisheye.projectPoints with (k1 k2 k3 k4), "unified*" -> cv2.omnidir.projectPoints with
xi and (k1 k2 p1 p2). Prints the largest difference per case; exits 1 if any exceeds the
tolerance or a case has no rows."""
import collections
import csv
import sys

import cv2
import numpy as np

groups = collections.defaultdict(list)
for row in csv.reader(open(sys.argv[1])):
    groups[(row[0], tuple(map(float, row[1:20])))].append(list(map(float, row[20:25])))

tolerance = float(sys.argv[2])
zero = np.zeros(3, dtype=np.float64)
worst_all = 0.0
for (name, c), rows in sorted(groups.items()):
    fx, fy, cx, cy, k1, k2, k3, k4, k5, k6, p1, p2, s1, s2, s3, s4, tx, ty, xi = c
    data = np.array(rows, dtype=np.float64)
    points = data[:, 0:3].reshape(1, -1, 3)
    K = np.array([[fx, 0, cx], [0, fy, cy], [0, 0, 1]], dtype=np.float64)
    if name.startswith("opencv"):
        dist = np.array([k1, k2, p1, p2, k3, k4, k5, k6, s1, s2, s3, s4, tx, ty], dtype=np.float64)
        uv, _ = cv2.projectPoints(points, zero, zero, K, dist)
    elif name in ("kannala_brandt", "equidistant"):
        D = np.array([k1, k2, k3, k4], dtype=np.float64)
        uv, _ = cv2.fisheye.projectPoints(points, zero.reshape(1, 1, 3), zero.reshape(1, 1, 3),
                                          K, D)
    elif name.startswith("unified"):
        D = np.array([[k1, k2, p1, p2]], dtype=np.float64)
        uv, _ = cv2.omnidir.projectPoints(points, zero.reshape(3, 1), zero.reshape(3, 1), K,
                                          float(xi), D)
    else:
        print(f"unknown case {name}")
        sys.exit(1)
    uv = uv.reshape(-1, 2)
    err = np.hypot(uv[:, 0] - data[:, 3], uv[:, 1] - data[:, 4])
    theta = np.degrees(np.arctan2(np.hypot(data[:, 0], data[:, 1]), data[:, 2]))
    worst = float(err.max())
    worst_all = max(worst_all, worst)
    print(f"{name:16s} {len(rows):5d} points up to {theta.max():6.2f} deg: largest difference "
          f"from OpenCV {worst:.3g} px")
print(f"OpenCV {cv2.__version__}: largest difference {worst_all:.3g} px "
      f"(tolerance {tolerance:g} px)")
sys.exit(0 if groups and worst_all <= tolerance else 1)
