#!/usr/bin/python3
"""An independent reader of camsim's KITTI export (`exports: [kitti]`), written from the KITTI
object devkit's readme (not from camsim's code): it renders two small scenes through the
camsim binary and checks, for a level camera and one looking down:

  - kitti/image_2/000000.png is NAME.png; calib/000000.txt holds P0..P3 (12 numbers each),
    R0_rect (9), Tr_velo_to_cam and Tr_imu_to_velo (12); P0 = P1 = P2 = P3;
  - the level camera's P2 is K [I | 0] with K from the scene (f / pitch, pixel centres at
    integers); both cameras' P2 is the K of the capture's sidecar (derived.opencv_fx_fy_cx_cy)
    times [R | 0], R a rotation;
  - label_2/000000.txt: 15 fields per line; the turned box's type, dimensions (h, w, l),
    bottom-centre location and rotation_y against the closed forms (1e-4), alpha =
    rotation_y - atan2(x, z);
  - the label's 3-D box, built as the devkit builds it (corners from h, w, l, location,
    rotation_y) and projected through P2, spans its 2-D box within 1 px (the issue's test);
  - with the camera looking down 23 degrees: the box's true corners (from the scene's placement)
    through the true camera (from position and look_at) span the label's 2-D box within
    1 px: P2 and the rect frame describe the real camera;
  - occluded: the box in front 0, the ball behind it partly hidden (1 or 2).
Exit 0 on success, 1 on a failed check."""
import argparse
import json
import math
import pathlib
import subprocess
import sys
import tempfile

import numpy as np

W, H = 64, 48
FX = 50.0 / (36.0 / W)  # px: focal length 50 mm over a pitch of 0.5625 mm
CX, CY = W / 2 - 0.5, H / 2 - 0.5
TURN = 30.0  # degrees about +y
SIZE = (0.6, 0.4, 0.3)  # the box along x (l), y (h), z (w), m
AT = (0.2, 0.0, 0.0)  # its bottom centre, m
FAILURES = []

CUBE = """    vertices: [[-0.5, 0, -0.5], [0.5, 0, -0.5], [0.5, 1, -0.5], [-0.5, 1, -0.5],
               [-0.5, 0, 0.5], [0.5, 0, 0.5], [0.5, 1, 0.5], [-0.5, 1, 0.5]]
    faces: [[0, 2, 1], [0, 3, 2], [4, 5, 6], [4, 6, 7], [0, 1, 5], [0, 5, 4],
            [3, 6, 2], [3, 7, 6], [0, 4, 7], [0, 7, 3], [1, 2, 6], [1, 6, 5]]
"""


def scene(position, look_at):
    return ("exports: [kitti]\n"
            "camera: {position: %s, look_at: %s, resolution: [%d, %d],\n"
            "         focal_length_mm: 50, sensor_width_mm: 36, sensor_height_mm: 27}\n"
            % (list(position), list(look_at), W, H)
            + "render: {spp: 16, max_depth: 1}\n"
            "materials: {m: {type: diffuse, reflectance: 0.6}}\n"
            "shapes:\n"
            "  - {name: ground, type: rectangle, corner: [-5, 0, 5], edge_u: [10, 0, 0],\n"
            "     edge_v: [0, 0, -10], material: m}\n"
            "  - name: box\n    type: mesh\n    class: Car\n    material: m\n" + CUBE
            + "    instances: [{translate: %s, rotate: {axis: [0, 1, 0], angle_deg: %g},\n"
              "                 scale: %s}]\n" % (list(AT), TURN, list(SIZE))
            + "  - {name: ball, type: sphere, centre: [0.1, 0.2, 0.8], radius: 0.2, class: 2,\n"
            "     material: m}\n"
            "lights: [{type: point, position: [0, 3, -3], intensity: 50}]\n")


def check(ok, what):
    if not ok:
        FAILURES.append(what)
        print("FAIL: " + what)


def near(a, b, tol, what):
    check(abs(a - b) <= tol, f"{what}: {a} vs {b} (tolerance {tol})")


def render(camsim, text, name, work):
    path = work / (name + ".yaml")
    path.write_text("name: %s\n" % name + text)
    out = work / name
    run = subprocess.run([camsim, "render", str(path), "-o", str(out), "--spp", "16"],
                         capture_output=True, text=True)
    if run.returncode != 0:
        print(run.stdout, run.stderr)
        sys.exit(f"camsim render {name} failed ({run.returncode})")
    return out


def read_calib(path):
    calib = {}
    for line in path.read_text().splitlines():
        key, values = line.split(":", 1)
        calib[key] = np.array([float(v) for v in values.split()])
    return calib


def devkit_corners(h, w, l, x, y, z, ry):
    """The devkit's 3-D box: corners in rect coordinates (3 x 8)."""
    xs = [l / 2, l / 2, -l / 2, -l / 2, l / 2, l / 2, -l / 2, -l / 2]
    ys = [0, 0, 0, 0, -h, -h, -h, -h]
    zs = [w / 2, -w / 2, -w / 2, w / 2, w / 2, -w / 2, -w / 2, w / 2]
    r = np.array([[math.cos(ry), 0, math.sin(ry)], [0, 1, 0], [-math.sin(ry), 0, math.cos(ry)]])
    return r @ np.array([xs, ys, zs]) + np.array([[x], [y], [z]])


def bounds(p, corners):
    uvw = p @ np.vstack([corners, np.ones((1, corners.shape[1]))])
    uv = uvw[:2] / uvw[2]
    return uv[0].min(), uv[1].min(), uv[0].max(), uv[1].max()


def camera_cv(position, look_at):
    """World -> camera (OpenCV axes) of a look_at camera with up +y (camsim's: right =
    forward x up)."""
    pos = np.array(position, dtype=float)
    z = np.array(look_at, dtype=float) - pos
    z /= np.linalg.norm(z)
    x = np.cross(z, [0.0, 1.0, 0.0])
    x /= np.linalg.norm(x)
    y = np.cross(z, x)
    r = np.array([x, y, z])
    return r, -r @ pos


def true_box_corners():
    c, s = math.cos(math.radians(TURN)), math.sin(math.radians(TURN))
    turn = np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])  # about +y, right-handed
    pts = []
    for i in range(8):
        v = np.array([(i & 1) - 0.5, (i >> 1) & 1, ((i >> 2) & 1) - 0.5]) * np.array(SIZE)
        pts.append(turn @ v + np.array(AT))
    return np.array(pts).T


def check_case(out, name, position, look_at, level):
    kitti = out / "kitti"
    check((kitti / "image_2" / "000000.png").read_bytes() == (out / (name + ".png")).read_bytes(),
          f"{name}: image_2/000000.png is {name}.png")
    calib = read_calib(kitti / "calib" / "000000.txt")
    for key, n in (("P0", 12), ("P1", 12), ("P2", 12), ("P3", 12), ("R0_rect", 9),
                   ("Tr_velo_to_cam", 12), ("Tr_imu_to_velo", 12)):
        check(key in calib and calib[key].size == n, f"{name}: calib {key} ({n} numbers)")
    for key in ("P0", "P1", "P3"):
        check(np.allclose(calib[key], calib["P2"]), f"{name}: {key} = P2")
    p2 = calib["P2"].reshape(3, 4)
    k = np.array([[FX, 0, CX], [0, FX, CY], [0, 0, 1]])
    if level:
        check(np.allclose(p2, np.hstack([k, np.zeros((3, 1))]), atol=1e-6),
              f"{name}: P2 {p2} is K [I | 0]")
    # calib matches the intrinsics the capture exports (its sidecar's opencv fx, fy, cx, cy):
    # P2 = K' [R | 0] with R a rotation, so P2[:, :3] P2[:, :3]^T = K' K'^T.
    fx, fy, cx, cy = json.loads((out / (name + ".json")).read_text())[
        "camera"]["derived"]["opencv_fx_fy_cx_cy"]
    exported = np.array([[fx, 0, cx], [0, fy, cy], [0, 0, 1]])
    check(np.allclose(p2[:, :3] @ p2[:, :3].T, exported @ exported.T, rtol=1e-9, atol=1e-9)
          and np.allclose(p2[:, 3], 0), f"{name}: P2 {p2} is the exported K {exported} [R | 0]")
    labels = [line.split() for line in (kitti / "label_2" / "000000.txt").read_text().splitlines()]
    check(all(len(fields) == 15 for fields in labels), f"{name}: 15 fields per label")
    by_type = {fields[0]: [float(v) for v in fields[1:]] for fields in labels}
    check(sorted(by_type) == ["Car", "Class2"], f"{name}: types {sorted(by_type)}")
    for kind, v in by_type.items():
        trunc, occl, alpha, left, top, right, bottom, h, w, l, x, y, z, ry = v
        near(alpha, math.atan2(math.sin(ry - math.atan2(x, z)), math.cos(ry - math.atan2(x, z))),
             1e-6, f"{name} {kind}: alpha")
        lo_u, lo_v, hi_u, hi_v = bounds(p2, devkit_corners(h, w, l, x, y, z, ry))
        check(max(abs(lo_u - left), abs(lo_v - top), abs(hi_u - right), abs(hi_v - bottom)) <= 1,
              f"{name} {kind}: 3-D box through P2 [{lo_u}, {lo_v}, {hi_u}, {hi_v}] vs its 2-D box "
              f"[{left}, {top}, {right}, {bottom}]")
        near(trunc, 0.0, 1e-9, f"{name} {kind}: truncated")
    box = by_type["Car"]
    near(box[7], SIZE[1], 1e-4, f"{name}: box h")
    near(box[8], SIZE[2], 1e-4, f"{name}: box w")
    near(box[9], SIZE[0], 1e-4, f"{name}: box l")
    check(box[1] == 0, f"{name}: the box in front is not occluded ({box[1]})")
    check(by_type["Class2"][1] in (1.0, 2.0), f"{name}: the ball behind it is partly occluded")
    r, t = camera_cv(position, look_at)
    cam = r @ true_box_corners() + t[:, None]
    uv = (k @ cam)[:2] / (k @ cam)[2]
    true_bounds = uv[0].min(), uv[1].min(), uv[0].max(), uv[1].max()
    check(max(abs(a - b) for a, b in zip(true_bounds, box[3:7])) <= 1,
          f"{name}: the true box through the true camera {true_bounds} vs the label {box[3:7]}")
    if level:
        near(box[10], -AT[0], 1e-4, f"{name}: box x")  # the camera's x is world -x
        near(box[11], position[1] - AT[1], 1e-4, f"{name}: box y (down)")
        near(box[12], AT[2] - position[2], 1e-4, f"{name}: box z")
        want_ry = math.atan2(math.sin(math.radians(TURN)), -math.cos(math.radians(TURN)))
        near(box[13], want_ry, 1e-4, f"{name}: box rotation_y")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("camsim")
    parser.add_argument("--keep")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        work = pathlib.Path(args.keep or tmp)
        work.mkdir(parents=True, exist_ok=True)
        cases = (("level", (0.0, 0.3, -3.0), (0.0, 0.3, 0.0), True),
                 ("down", (0.0, 1.5, -3.0), (0.0, 0.2, 0.0), False))
        for name, position, look_at, level in cases:
            out = render(args.camsim, scene(position, look_at), name, work)
            check_case(out, name, position, look_at, level)
    if FAILURES:
        print(f"{len(FAILURES)} checks failed")
        return 1
    print("kitti layout: calib, labels and boxes as the devkit reads them (level and tilted "
          "camera)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
