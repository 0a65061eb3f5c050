#!/usr/bin/python3
"""Triangulates a camsim sequence with COLMAP, given the exported poses.

usage: colmap_triangulate.py SEQUENCE_DIR WORK_DIR

SEQUENCE_DIR holds a sequence camsim wrote (NAME_NNNN.png and colmap/, the text model of
the exported intrinsics and poses). Runs Debian's COLMAP (3.8) headless on the CPU:
feature_extractor (SIFT, the exported camera model, one camera per image) on the PNGs, then
exhaustive_matcher, then point_triangulator with the exported model — the poses are kept,
not estimated. COLMAP numbers the database's images as its reader threads finish, so the
model's image and camera ids are first renumbered to the database's (by image name).
Writes WORK_DIR/database.db, WORK_DIR/model_in (the renumbered model), WORK_DIR/sparse
(binary) and WORK_DIR/sparse_txt (text: cameras.txt, images.txt, points3D.txt); prints the
number of points. Exits non-zero, saying which step failed, if one does.
"""
import os
import pathlib
import sqlite3
import subprocess
import sys


def run(step, args, work):
    env = dict(os.environ, QT_QPA_PLATFORM="offscreen")
    log = work / f"{step}.log"
    with open(log, "w") as out:
        r = subprocess.run(["colmap", step] + args, stdout=out, stderr=subprocess.STDOUT, env=env)
    if r.returncode != 0:
        sys.exit(f"colmap_triangulate: colmap {step} failed (exit {r.returncode}); see {log}")


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    seq, work = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])
    work.mkdir(parents=True, exist_ok=True)
    model = seq / "colmap"
    images = [l for l in (model / "images.txt").read_text().splitlines() if l and not l.startswith("#")]
    cameras = {l.split()[0]: l.split(None, 1)[1] for l in (model / "cameras.txt").read_text().splitlines()
               if l and not l.startswith("#")}
    names = [l.split()[9] for l in images]
    # The database's cameras of the exported model (OPENCV, FULL_OPENCV, OPENCV_FISHEYE):
    # point_triangulator then refines nothing and keeps the exported parameters.
    camera_model = next(iter(cameras.values())).split()[0]
    (work / "images.list").write_text("\n".join(names) + "\n")
    db = work / "database.db"
    if db.exists():
        db.unlink()
    run("feature_extractor", ["--database_path", str(db), "--image_path", str(seq),
                              "--image_list_path", str(work / "images.list"),
                              "--ImageReader.camera_model", camera_model,
                              "--SiftExtraction.use_gpu", "0"], work)
    ids = {name: (image_id, camera_id) for image_id, name, camera_id in
           sqlite3.connect(db).execute("select image_id, name, camera_id from images")}
    model_in = work / "model_in"
    model_in.mkdir(exist_ok=True)
    cams, imgs = [], []
    for line in images:
        f = line.split()
        image_id, camera_id = ids[f[9]]
        cams.append(f"{camera_id} {cameras[f[8]]}")
        imgs.append(" ".join([str(image_id)] + f[1:8] + [str(camera_id), f[9]]) + "\n")
    (model_in / "cameras.txt").write_text("\n".join(cams) + "\n")
    (model_in / "images.txt").write_text("\n".join(imgs) + "\n")
    (model_in / "points3D.txt").write_text("")
    run("exhaustive_matcher", ["--database_path", str(db), "--SiftMatching.use_gpu", "0"], work)
    sparse, text = work / "sparse", work / "sparse_txt"
    sparse.mkdir(exist_ok=True)
    text.mkdir(exist_ok=True)
    run("point_triangulator", ["--database_path", str(db), "--image_path", str(seq),
                               "--input_path", str(model_in), "--output_path", str(sparse)], work)
    run("model_converter", ["--input_path", str(sparse), "--output_path", str(text),
                            "--output_type", "TXT"], work)
    points = [l for l in (text / "points3D.txt").read_text().splitlines() if l and not l.startswith("#")]
    print(f"colmap_triangulate: {len(images)} images, {len(points)} points triangulated "
          f"with the exported poses ({text})")


if __name__ == "__main__":
    main()
