#!/usr/bin/python3
"""An independent reader of camsim's BOP export (issue 40), written from bop_toolkit's
docs/bop_datasets_format.md and docs/output.md's "BOP layout" with json, numpy and cv2 only:
no camsim code reads the files.

usage: bop_layout_check.py CAMSIM [--keep DIR]

camsim renders two small scenes with `exports: [bop]` (pinhole 64 x 48 px, fx = fy =
88.889 px; a wall 3 m ahead, a box (class 5, the unit cube placed at scale 0.3) whose front
face is 1.85 m ahead and a ball (class 7, r 0.15 m) partly behind it):
  single    one capture: bop/train_pbr/000000 with image 0
  sequence  two frames at 10 Hz, the box moving along +x at 0.5 m/s: two images
and this script checks, against the scenes' own numbers:
  - every file and field the format names: models/obj_NNNNNN.ply and models_info.json
    (diameter, min_*, size_* in mm), scene_camera.json (cam_K, cam_R_w2c, cam_t_w2c in mm,
    depth_scale), scene_gt.json (obj_id, cam_R_m2c row-major, cam_t_m2c in mm),
    rgb/ (the capture's PNG), depth/ (16-bit);
  - the poses: R orthonormal with det +1, the box's and the ball's t_m2c where the scene puts
    them (mm, OpenCV axes); in the sequence at each frame's shutter centre;
  - the model's vertices through cam_R_m2c, cam_t_m2c and cam_K inside the image, their box
    against bbox_obj (1.5 px: the turned box's corner pixels); cam_R_m2c row-major;
  - depth PNG x depth_scale = the analytic depth (wall 3000 mm, box face 1850 mm) within half
    a step;
  - masks (when the render has the amodal AOV): mask/ and mask_visib/ 0/255 PNGs whose counts
    and bop_toolkit boxes are scene_gt_info.json's, visible within amodal, visib_fract their
    ratio, px_count_valid the amodal pixels with depth; the unoccluded box fully visible, the
    ball partly. Without the amodal AOV (a camsim that does not know `aovs: [amodal]`) the
    mask part is skipped, and camsim must have said so; a camsim that knows it must write it.
Exit 0 on success, 1 on a failed check."""
import argparse
import json
import math
import pathlib
import subprocess
import sys
import tempfile

import cv2
import numpy as np

FX = 50.0 / (36.0 / 64)  # px: focal length 50 mm over a pitch of 0.5625 mm
CX, CY = 31.5, 23.5  # px, pixel centres at integers
FAILURES = []
# The box turns about the optical axis (its front face stays at 1.85 m): cam_R_m2c is then
# not symmetric, so a transposed (column-major) matrix fails.
BOX_TURN_DEG = 30.0

CUBE = """    vertices: [[-0.5, -0.5, -0.5], [0.5, -0.5, -0.5], [0.5, 0.5, -0.5], [-0.5, 0.5, -0.5],
               [-0.5, -0.5, 0.5], [0.5, -0.5, 0.5], [0.5, 0.5, 0.5], [-0.5, 0.5, 0.5]]
    faces: [[0, 2, 1], [0, 3, 2], [4, 5, 6], [4, 6, 7], [0, 1, 5], [0, 5, 4],
            [3, 6, 2], [3, 7, 6], [0, 4, 7], [0, 7, 3], [1, 2, 6], [1, 6, 5]]
"""


def scene(sequence):
    turn = "rotate: {axis: [0, 0, 1], angle_deg: %g}" % BOX_TURN_DEG
    box_place = ("    motion: [{time: 0, translate: [0.1, 0.05, 0], %s, scale: 0.3},\n"
                 "             {time: 1, translate: [0.6, 0.05, 0], %s, scale: 0.3}]\n"
                 % (turn, turn) if sequence else
                 "    instances: [{translate: [0.1, 0.05, 0], %s, scale: 0.3}]\n" % turn)
    return ("exports: [bop]\n"
            + ("frames: {count: 2, rate_hz: 10}\n" if sequence else "")
            + "camera: {position: [0, 0, -2], look_at: [0, 0, 0], resolution: [64, 48],\n"
            "         focal_length_mm: 50, sensor_width_mm: 36, sensor_height_mm: 27}\n"
            "render: {spp: 16, max_depth: 1}\n"
            "materials: {m: {type: diffuse, reflectance: 0.6}}\n"
            "shapes:\n"
            "  - {name: wall, type: rectangle, corner: [-2, -2, 1], edge_u: [4, 0, 0],\n"
            "     edge_v: [0, 4, 0], material: m}\n"
            "  - name: box\n    type: mesh\n    class: 5\n    material: m\n" + CUBE + box_place
            + "  - {name: ball, type: sphere, centre: [-0.05, -0.1, 0.3], radius: 0.15, class: 7,\n"
            "     material: m}\n"
            "lights: [{type: point, position: [0, 1, -2], intensity: 20}]\n")


def check(ok, what):
    if not ok:
        FAILURES.append(what)
        print("FAIL:", what)
    return ok


def near(a, b, tol, what):
    return check(abs(a - b) <= tol, f"{what}: {a} vs {b} (tolerance {tol})")


def read_ply(path):
    """ASCII PLY: vertices (x y z nx ny nz) and triangles, as the format document shows."""
    lines = path.read_text().splitlines()
    check(lines[0] == "ply" and lines[1] == "format ascii 1.0", f"{path.name}: an ASCII PLY")
    end = lines.index("end_header")
    header = lines[:end]
    nv = int(next(l for l in header if l.startswith("element vertex")).split()[2])
    nf = int(next(l for l in header if l.startswith("element face")).split()[2])
    props = [l.split()[2] for l in header if l.startswith("property float")]
    check(props[:6] == ["x", "y", "z", "nx", "ny", "nz"], f"{path.name}: x y z nx ny nz")
    v = np.array([[float(x) for x in l.split()] for l in lines[end + 1:end + 1 + nv]])
    f = [l.split() for l in lines[end + 1 + nv:end + 1 + nv + nf]]
    check(all(t[0] == "3" for t in f), f"{path.name}: triangles")
    return v[:, :3], v[:, 3:6]


def bop_box(mask):
    ys, xs = np.nonzero(mask)
    if len(xs) == 0:
        return [-1, -1, -1, -1]
    return [int(xs.min()), int(ys.min()), int(xs.max() - xs.min()), int(ys.max() - ys.min())]


def rotation_ok(r, what):
    r = np.array(r, dtype=float).reshape(3, 3)
    check(np.abs(r @ r.T - np.eye(3)).max() < 1e-6, f"{what}: orthonormal")
    near(np.linalg.det(r), 1.0, 1e-6, f"{what}: det")
    return r


def render(camsim, text, name, work):
    path = work / (name + ".yaml")
    path.write_text(text)
    out = work / name
    run = subprocess.run([camsim, "render", str(path), "-o", str(out), "--reproducible"],
                         capture_output=True, text=True)
    if run.returncode != 0:
        print(run.stdout, run.stderr)
        sys.exit(f"camsim render {name} failed ({run.returncode})")
    return out, run.stdout + run.stderr


def check_scene(out, log, images, box_x_m, masks_expected):
    bop = out / "bop"
    # models/
    info = json.loads((bop / "models" / "models_info.json").read_text())
    check(sorted(info) == ["5", "7"], f"models_info ids {sorted(info)}")
    models = {}
    for oid, size, diameter in (("5", 300.0, 300.0 * math.sqrt(3)), ("7", 300.0, 300.0)):
        m = info[oid]
        for key in ("diameter", "min_x", "min_y", "min_z", "size_x", "size_y", "size_z"):
            check(key in m, f"models_info[{oid}].{key}")
        near(m["diameter"], diameter, 1e-3, f"obj {oid} diameter (mm)")
        for axis in "xyz":
            near(m["size_" + axis], size, 1e-3, f"obj {oid} size_{axis} (mm)")
            near(m["min_" + axis], -size / 2, 1e-3, f"obj {oid} min_{axis} (mm)")
        verts, normals = read_ply(bop / "models" / f"obj_{int(oid):06d}.ply")
        near(verts[:, 0].max() - verts[:, 0].min(), m["size_x"], 1e-3, f"obj {oid} PLY width")
        check(np.abs(np.linalg.norm(normals, axis=1) - 1).max() < 1e-5, f"obj {oid} unit normals")
        models[int(oid)] = verts
    sc = bop / "train_pbr" / "000000"
    cams = json.loads((sc / "scene_camera.json").read_text())
    gts = json.loads((sc / "scene_gt.json").read_text())
    check(sorted(cams) == [str(i) for i in images], f"scene_camera images {sorted(cams)}")
    check(sorted(gts) == [str(i) for i in images], f"scene_gt images {sorted(gts)}")
    info_file = sc / "scene_gt_info.json"
    if masks_expected:
        check(info_file.is_file(), "scene_gt_info.json written (the render has the amodal AOV)")
    else:
        check("mask/, mask_visib/ and scene_gt_info.json not written" in log,
              "camsim says why the masks are left out")
        print("masks: skipped (this camsim has no amodal AOV)")
    ginfo = json.loads(info_file.read_text()) if info_file.is_file() else None
    for im in images:
        key, name = str(im), f"{im:06d}"
        cam = cams[key]
        k = np.array(cam["cam_K"], dtype=float).reshape(3, 3)
        check(np.allclose(k, [[FX, 0, CX], [0, FX, CY], [0, 0, 1]], atol=1e-6), f"cam_K {k}")
        r_w2c = rotation_ok(cam["cam_R_w2c"], "cam_R_w2c")
        check(np.allclose(r_w2c, np.diag([-1.0, -1.0, 1.0]), atol=1e-9), f"cam_R_w2c {r_w2c}")
        check(np.allclose(cam["cam_t_w2c"], [0, 0, 2000], atol=1e-6),
              f"cam_t_w2c {cam['cam_t_w2c']} (mm)")
        scale = cam["depth_scale"]
        near(scale, 0.1, 1e-12, "depth_scale (mm)")
        gt = gts[key]
        check([g["obj_id"] for g in gt] == [5, 7], f"obj_ids {[g['obj_id'] for g in gt]}")
        c, s = math.cos(math.radians(BOX_TURN_DEG)), math.sin(math.radians(BOX_TURN_DEG))
        want_r = np.diag([-1.0, -1.0, 1.0]) @ np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])
        got_r = np.array(gt[0]["cam_R_m2c"], dtype=float).reshape(3, 3)  # row-major
        check(np.allclose(got_r, want_r, atol=1e-9), f"image {im}: box cam_R_m2c {got_r}")
        t_box = np.array(gt[0]["cam_t_m2c"])
        check(np.allclose(t_box, [-1000 * box_x_m[im], -50, 2000], atol=1e-3),
              f"image {im}: box cam_t_m2c {t_box} (mm)")
        check(np.allclose(gt[1]["cam_t_m2c"], [50, 100, 2300], atol=1e-3),
              f"image {im}: ball cam_t_m2c {gt[1]['cam_t_m2c']} (mm)")
        rgb = cv2.imread(str(sc / "rgb" / (name + ".png")), cv2.IMREAD_UNCHANGED)
        check(rgb is not None and rgb.shape[:2] == (48, 64), f"rgb/{name}.png 64 x 48")
        depth = cv2.imread(str(sc / "depth" / (name + ".png")), cv2.IMREAD_UNCHANGED)
        check(depth is not None and depth.dtype == np.uint16, f"depth/{name}.png 16-bit")
        near(depth[2, 2] * scale, 3000.0, scale / 2, f"image {im}: wall depth (mm)")
        u = FX * (-box_x_m[im] / 1.85) + CX  # the box face's centre
        v = FX * (-0.05 / 1.85) + CY
        near(depth[int(round(v)), int(round(u))] * scale, 1850.0, scale / 2,
             f"image {im}: box face depth (mm)")
        poses = []
        for g in gt:
            r = rotation_ok(g["cam_R_m2c"], f"image {im} obj {g['obj_id']} cam_R_m2c")
            p = (r @ models[g["obj_id"]].T).T + np.array(g["cam_t_m2c"])
            uv = (k @ p.T).T
            uv = uv[:, :2] / uv[:, 2:3]
            check(p[:, 2].min() > 0 and uv.min() > -0.5 and uv[:, 0].max() < 63.5
                  and uv[:, 1].max() < 47.5, f"image {im} obj {g['obj_id']}: model in view")
            poses.append(uv)
        if ginfo is None:
            continue
        entries = ginfo[key]
        check(len(entries) == len(gt), "scene_gt_info entries")
        fractions = []
        for gid, (e, uv) in enumerate(zip(entries, poses)):
            for field in ("bbox_obj", "bbox_visib", "px_count_all", "px_count_valid",
                          "px_count_visib", "visib_fract"):
                check(field in e, f"scene_gt_info.{field}")
            mask = cv2.imread(str(sc / "mask" / f"{name}_{gid:06d}.png"), cv2.IMREAD_UNCHANGED)
            visib = cv2.imread(str(sc / "mask_visib" / f"{name}_{gid:06d}.png"),
                               cv2.IMREAD_UNCHANGED)
            check(set(np.unique(mask)) <= {0, 255} and set(np.unique(visib)) <= {0, 255},
                  "masks 0/255")
            a, b = mask == 255, visib == 255
            check(e["px_count_all"] == int(a.sum()), f"px_count_all {e['px_count_all']}")
            check(e["px_count_visib"] == int(b.sum()), f"px_count_visib {e['px_count_visib']}")
            check(e["px_count_valid"] == int((a & (depth > 0)).sum()), "px_count_valid")
            check(not (b & ~a).any(), "visible within amodal")
            check(e["bbox_obj"] == bop_box(a), f"bbox_obj {e['bbox_obj']} vs {bop_box(a)}")
            check(e["bbox_visib"] == bop_box(b), f"bbox_visib {e['bbox_visib']}")
            near(e["visib_fract"], b.sum() / max(a.sum(), 1), 1e-9, "visib_fract")
            lo, hi = uv.min(axis=0), uv.max(axis=0)  # the projected model's extent (px)
            box = e["bbox_obj"]
            # 1.5 px: the turned box's corners are tips whose pixels are less than half
            # covered, so the mask (coverage >= 0.5) stops up to a pixel and a half inside.
            check(abs(box[0] - lo[0]) <= 1.5 and abs(box[1] - lo[1]) <= 1.5
                  and abs(box[0] + box[2] - hi[0]) <= 1.5 and abs(box[1] + box[3] - hi[1]) <= 1.5,
                  f"bbox_obj {box} vs the projected model {lo}, {hi}")
            fractions.append(e["visib_fract"])
        near(fractions[0], 1.0, 1e-12, "the box is unoccluded")
        check(0.05 < fractions[1] < 0.95, f"the ball is partly behind the box ({fractions[1]})")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("camsim")
    parser.add_argument("--keep")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        work = pathlib.Path(args.keep or tmp)
        work.mkdir(parents=True, exist_ok=True)
        masks = True  # exports: [bop] adds the amodal aov: the masks must be there
        out, log = render(args.camsim, scene(False), "single", work)
        check((out / "bop" / "train_pbr" / "000000" / "rgb" / "000000.png").read_bytes()
              == (out / "single.png").read_bytes(), "rgb/000000.png is single.png")
        check_scene(out, log, [0], {0: 0.1}, masks)
        out, log = render(args.camsim, scene(True), "sequence", work)
        # Frame k's reference time: the centre of its window [k/10, k/10 + 1/60] s.
        x = {k: 0.1 + 0.5 * (k / 10 + 1 / 120) for k in (0, 1)}
        check_scene(out, log, [0, 1], x, masks)
    if FAILURES:
        print(f"{len(FAILURES)} checks failed")
        return 1
    print("bop layout: every file and field as documented (single capture, 2-frame sequence)"
          + ("" if masks else "; masks skipped"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
