#!/usr/bin/python3
"""Writes the example scenes' environment maps (lat-long, linear Rec.709, half float,
ZIP-compressed OpenEXR) from closed-form descriptions, so the data in scenes/env/ can be
regenerated and checked:

  sky.exr     a clear-sky-like dome without the sun (the sun is a `distant` light):
              zenith blue brightening to a white horizon, Rayleigh-like colour, a soft
              glow around the sun's direction, and a dark neutral ground.
  studio.exr  a photo studio for metals and glass: dark grey walls, a large overhead
              softbox, two vertical strip lights, a warm key and a grey floor.

Conventions (docs/scene-format.md, `environment`): row 0 is the zenith (+y), columns run
eastwards from u = 0 (south) through u = 1/2 (north, +z) ... u = 3/4 is east (−x).
Values are relative: scenes set the absolute level with `illuminance`.

Usage: /usr/bin/python3 scripts/make_envmaps.py [OUTPUT_DIR]   (default scenes/env)
"""
import os
import struct
import sys
import zlib

import numpy as np


def exr_bytes(rgb):
    """Scanline OpenEXR, channels B, G, R as HALF, ZIP compression (16 lines per chunk)."""
    h, w, _ = rgb.shape
    def attr(name, type_, value):
        return name.encode() + b"\0" + type_.encode() + b"\0" + struct.pack("<i", len(value)) + value
    chlist = b"".join(c.encode() + b"\0" + struct.pack("<iB3xii", 1, 0, 1, 1) for c in "BGR") + b"\0"
    box = struct.pack("<iiii", 0, 0, w - 1, h - 1)
    header = (b"\x76\x2f\x31\x01" + struct.pack("<i", 2) +
              attr("channels", "chlist", chlist) + attr("compression", "compression", b"\x03") +
              attr("dataWindow", "box2i", box) + attr("displayWindow", "box2i", box) +
              attr("lineOrder", "lineOrder", b"\x00") + attr("pixelAspectRatio", "float", struct.pack("<f", 1.0)) +
              attr("screenWindowCenter", "v2f", struct.pack("<ff", 0.0, 0.0)) +
              attr("screenWindowWidth", "float", struct.pack("<f", 1.0)) + b"\0")
    half = rgb.astype("<f2")
    chunks = []
    for y0 in range(0, h, 16):
        raw = b"".join(half[y, :, c].tobytes() for y in range(y0, min(y0 + 16, h)) for c in (2, 1, 0))
        b = np.frombuffer(raw, dtype=np.uint8)
        t = np.concatenate([b[0::2], b[1::2]])  # interleave: even bytes, then odd bytes
        d = t.astype(np.int16)
        d[1:] = (t[1:].astype(np.int16) - t[:-1].astype(np.int16) + 128) % 256  # predictor
        packed = zlib.compress(d.astype(np.uint8).tobytes(), 9)
        data = packed if len(packed) < len(raw) else raw
        chunks.append(struct.pack("<ii", y0, len(data)) + data)
    offsets, pos = [], len(header) + 8 * len(chunks)
    for c in chunks:
        offsets.append(pos)
        pos += len(c)
    return header + struct.pack("<%dQ" % len(chunks), *offsets) + b"".join(chunks)


def directions(w, h):
    """Unit world directions of the texel centres (x east is −x, y up, z north)."""
    u = (np.arange(w) + 0.5) / w
    v = (np.arange(h) + 0.5) / h
    phi = 2.0 * np.pi * u[None, :]  # azimuth from south (u = 0), eastwards
    theta = np.pi * v[:, None]      # from the zenith
    # u = 1/2 faces north (+z), u = 3/4 east (−x): azimuth measured from north = phi − π.
    az = phi - np.pi
    x = -np.sin(theta) * np.sin(az)
    y = np.cos(theta) * np.ones_like(az)
    z = np.sin(theta) * np.cos(az)
    return x, y, z


def sky(w=512, h=256, sun_elevation=35.0, sun_azimuth=135.0):
    x, y, z = directions(w, h)
    el, az = np.radians(sun_elevation), np.radians(sun_azimuth)
    sun = np.array([-np.cos(el) * np.sin(az), np.sin(el), np.cos(el) * np.cos(az)])
    cos_sun = np.clip(x * sun[0] + y * sun[1] + z * sun[2], -1.0, 1.0)
    up = np.clip(y, 0.0, 1.0)
    # Rayleigh-like: deep blue at the zenith, whitening towards the horizon.
    zenith = np.array([0.16, 0.30, 0.75])
    horizon = np.array([0.85, 0.90, 1.00])
    t = np.exp(-4.0 * up)[..., None]
    rgb = zenith * (1.0 - t) + horizon * t
    rgb = rgb * (0.6 + 0.4 * (1.0 + cos_sun ** 2)[..., None] / 2.0)  # Rayleigh phase
    rgb = rgb + (np.array([1.0, 0.9, 0.75]) * 2.5 * np.exp((cos_sun - 1.0) * 40.0)[..., None])  # glow
    ground = np.array([0.09, 0.085, 0.08]) * (0.5 + 0.5 * np.clip(-y, 0.0, 1.0))[..., None]
    return np.where((y >= 0.0)[..., None], rgb, ground)


def studio(w=512, h=256):
    x, y, z = directions(w, h)
    rgb = np.ones(x.shape + (3,)) * 0.03  # dark grey walls
    rgb[y < 0.0] = 0.06  # a grey floor
    softbox = y > np.cos(np.radians(22.0))
    rgb[softbox] = 6.0
    elev = np.degrees(np.arcsin(np.clip(y, -1.0, 1.0)))
    az = (np.degrees(np.arctan2(-x, z)) + 360.0) % 360.0  # 0 north (+z), 90 east (−x)
    for centre in (70.0, 290.0):  # two vertical strips, east-north-east and west-north-west
        strip = (np.abs(((az - centre + 180.0) % 360.0) - 180.0) < 6.0) & (elev > 0.0) & (elev < 50.0)
        rgb[strip] = 4.0
    key = (np.abs(((az - 180.0 + 180.0) % 360.0) - 180.0) < 18.0) & (elev > 15.0) & (elev < 45.0)
    rgb[key] = np.array([9.0, 7.5, 5.5])  # a warm key light behind the camera (south)
    return rgb


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "scenes", "env")
    os.makedirs(out, exist_ok=True)
    for name, img in (("sky.exr", sky()), ("studio.exr", studio())):
        path = os.path.join(out, name)
        with open(path, "wb") as f:
            f.write(exr_bytes(img.astype(np.float32)))
        print(path, img.shape[1], "x", img.shape[0])


if __name__ == "__main__":
    main()
