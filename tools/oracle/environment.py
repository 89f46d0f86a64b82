#!/usr/bin/env python3
"""Mitsuba 3 references for glint's HDR environment maps (tests/oracle/environment.rs).

Writes, under tests/oracle/refs/environment/:
  sky.exr     the 64x32 procedural HDR sky both renderers read (float32 RGB): a blue
              gradient above, a brown ground below, coloured bands around the horizon
              (each 1/8 of the turn its own colour, so an orientation error shows) and a
              bright sun (HDR, up to 8) north-east above the horizon;
  mirror.exr  a mirror sphere (conductor, material 'none': a perfect mirror) in it;
  glass.exr   a glass sphere (dielectric, ior 1.5, exact Fresnel) in it.
`python3 tools/oracle/environment.py sky-hdr` writes instead the same sky at 256x128 as
textures/sky.hdr (Radiance RGBE), the map of scenes/environment.lua.

Each scene is 48x48, fov 40 (square), eye (0, 0.6, 4) looking at the origin, unit sphere at
the origin, the map turned 30 degrees about +y (glint's environment_rotation = 30), box
filter, the path integrator (only specular surfaces and the envmap: Whitted's light
transport), scalar_rgb. Run from the repository root: python3 tools/oracle/environment.py
"""
import math
import os
import sys

import mitsuba as mi

mi.set_variant("scalar_rgb")

OUT = os.path.join("tests", "oracle", "refs", "environment")
SIZE = 48
SPP = {"mirror": 16384, "glass": 16384}
BANDS = [
    (1.0, 0.25, 0.2), (1.0, 0.8, 0.2), (0.3, 1.0, 0.3), (0.2, 0.9, 1.0),
    (0.3, 0.3, 1.0), (0.9, 0.3, 1.0), (1.0, 1.0, 1.0), (0.1, 0.1, 0.1),
]


def sky(width=64, height=32):
    """The sky's texels as a flat list of r, g, b, row 0 straight up (Mitsuba's envmap:
    row j at v = j/(h-1), column i centred at u = (i + 1/2)/w)."""
    texels = []
    sun = (math.sin(0.8) * math.cos(0.5), math.sin(0.5), -math.cos(0.8) * math.cos(0.5))
    for j in range(height):
        theta = math.pi * j / (height - 1)
        for i in range(width):
            u = (i + 0.5) / width
            phi = 2 * math.pi * u
            d = (math.sin(phi) * math.sin(theta), math.cos(theta),
                 -math.cos(phi) * math.sin(theta))
            if d[1] > 0.25:
                c = [x * (0.6 + 1.4 * d[1]) for x in (0.25, 0.45, 1.0)]
            elif d[1] > -0.25:
                c = [x * 1.5 for x in BANDS[int(u * 8) % 8]]
            else:
                c = [x * (1.0 - d[1]) for x in (0.35, 0.22, 0.1)]
            glow = max(0.0, sum(a * b for a, b in zip(d, sun)))
            texels.extend(x + 8.0 * glow ** 64 for x in c)
    return mi.Bitmap(mi.TensorXf(texels, shape=(height, width, 3)))


def render(kind, env_path, rotation=30.0):
    bsdf = ({"type": "conductor", "material": "none"} if kind == "mirror"
            else {"type": "dielectric", "int_ior": 1.5, "ext_ior": 1.0})
    scene = mi.load_dict({
        "type": "scene",
        "integrator": {"type": "path", "max_depth": 17, "rr_depth": 100},
        "sensor": {
            "type": "perspective",
            "fov": 40,
            "fov_axis": "y",
            "to_world": mi.ScalarTransform4f().look_at(
                origin=[0, 0.6, 4], target=[0, 0, 0], up=[0, 1, 0]),
            "film": {"type": "hdrfilm", "width": SIZE, "height": SIZE,
                     "rfilter": {"type": "box"}, "pixel_format": "rgb"},
            "sampler": {"type": "independent", "sample_count": SPP[kind]},
        },
        "sphere": {"type": "sphere", "center": [0, 0, 0], "radius": 1.0, "bsdf": bsdf},
        "env": {"type": "envmap", "filename": env_path,
                "to_world": mi.ScalarTransform4f().rotate([0, 1, 0], rotation)},
    })
    return mi.render(scene, seed=7)


def main():
    if sys.argv[1:] == ["sky-hdr"]:
        sky(256, 128).write(os.path.join("textures", "sky.hdr"))
        return
    os.makedirs(OUT, exist_ok=True)
    env_path = os.path.join(OUT, "sky.exr")
    sky().write(env_path)
    for kind in sys.argv[1:] or ["mirror", "glass"]:
        image = render(kind, env_path)
        mi.Bitmap(image).write(os.path.join(OUT, f"{kind}.exr"))
        print(kind, "written")


if __name__ == "__main__":
    main()
