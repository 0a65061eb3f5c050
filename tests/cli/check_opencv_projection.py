#!/usr/bin/python3
"""Projects points with the intrinsics, distortion and poses camsim exported in
cameras.json through OpenCV's own cv2.projectPoints, and compares them with the pixels
they were rendered at.

usage: check_opencv_projection.py CAMERAS_JSON POINTS_CSV TOLERANCE_PX
POINTS_CSV rows: frame index, pixel x, pixel y (OpenCV: pixel centres at integers),
world X, Y, Z. Prints the largest error; exits 1 if it exceeds the tolerance."""
import csv
import json
import sys

import cv2
import numpy as np

cameras = json.load(open(sys.argv[1]))["frames"]
worst = 0.0
count = 0
for row in csv.reader(open(sys.argv[2])):
    k, px, py, X, Y, Z = int(row[0]), float(row[1]), float(row[2]), *map(float, row[3:6])
    c = cameras[k]
    world_from_cam = np.array(c["world_from_camera_opencv"], dtype=np.float64)
    cam_from_world = np.linalg.inv(world_from_cam)
    rvec, _ = cv2.Rodrigues(cam_from_world[:3, :3])
    tvec = cam_from_world[:3, 3]
    K = np.array([[c["fx"], 0, c["cx"]], [0, c["fy"], c["cy"]], [0, 0, 1]], dtype=np.float64)
    dist = np.array([c["k1"], c["k2"], c["p1"], c["p2"], c["k3"]], dtype=np.float64)
    uv, _ = cv2.projectPoints(np.array([[X, Y, Z]], dtype=np.float64), rvec, tvec, K, dist)
    err = float(np.hypot(uv[0, 0, 0] - px, uv[0, 0, 1] - py))
    worst = max(worst, err)
    count += 1
print(f"{count} points, largest reprojection error {worst:.4f} px (OpenCV {cv2.__version__})")
sys.exit(0 if count > 0 and worst <= float(sys.argv[3]) else 1)
