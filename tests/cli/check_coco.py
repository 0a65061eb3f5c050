#!/usr/bin/python3
"""Checks camsim's COCO annotations.json against the dominant instance ids of its frames.

usage: check_coco.py annotations.json ids.txt
ids.txt: one line per pixel row, "frame y id id id ..." (the EXR's instance.id channel).
Decodes each RLE mask as COCO defines uncompressed RLE (pycocotools' frPyObjects: runs of
0 then 1 alternating, column-major over [height, width]) and requires: the mask equals the
pixels whose dominant id is the instance's; area is its pixel count; bbox is its tight box
(corner convention); bbox_3d, the projected 3-D bounds, contains bbox within 1 px (a pixel
the instance only partly covers, as its dominant id, reaches up to 1 px past the bounds; the
scene keeps motion blur below that); categories name every category_id. Prints a summary; exits 1 on the first mismatch.
"""
import json
import sys

import numpy as np


def main():
    coco = json.load(open(sys.argv[1]))
    rows = {}
    for line in open(sys.argv[2]):
        f, y, *ids = line.split()
        rows.setdefault(int(f), {})[int(y)] = [int(float(v)) for v in ids]
    frames = {f: np.array([r[y] for y in sorted(r)]) for f, r in rows.items()}
    cats = {c["id"]: c["name"] for c in coco["categories"]}
    images = {im["id"]: im for im in coco["images"]}
    checked = 0
    for a in coco["annotations"]:
        im = images[a["image_id"]]
        ids = frames[a["image_id"] - 1]
        h, w = a["segmentation"]["size"]
        assert (h, w) == ids.shape == (im["height"], im["width"]), (h, w, ids.shape)
        counts = a["segmentation"]["counts"]
        assert sum(counts) == h * w, "RLE counts do not cover the image"
        flat = np.zeros(h * w, dtype=bool)
        pos, value = 0, False
        for c in counts:
            flat[pos:pos + c] = value
            pos += c
            value = not value
        mask = flat.reshape((w, h)).T  # column-major
        truth = ids == a["instance_id"]
        assert (mask == truth).all(), f"annotation {a['id']}: mask differs from the ids"
        assert a["area"] == truth.sum()
        ys, xs = np.nonzero(truth)
        tight = [xs.min(), ys.min(), xs.max() - xs.min() + 1, ys.max() - ys.min() + 1]
        assert a["bbox"] == tight, (a["bbox"], tight)
        assert a["category_id"] in cats
        if "bbox_3d" in a:
            bx, by, bw, bh = a["bbox_3d"]
            eps = 1.0
            assert bx <= tight[0] + eps and by <= tight[1] + eps, (a["bbox_3d"], tight)
            assert bx + bw >= tight[0] + tight[2] - eps and by + bh >= tight[1] + tight[3] - eps
        checked += 1
    print(f"COCO: {len(coco['images'])} images, {len(cats)} categories, "
          f"{checked} annotations: masks, areas and boxes match the ids")
    return 0 if checked > 0 else 1


if __name__ == "__main__":
    sys.exit(main())
