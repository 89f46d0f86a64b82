#!/usr/bin/env python3
"""Renders the depth-of-field oracle's references with Mitsuba 3 (scalar_rgb):
tests/oracle/refs/pinhole.exr (the `perspective` sensor: field of view and handedness)
and tests/oracle/refs/depth_of_field.exr (the `thinlens` sensor), the scene of
tools/oracle/depth_of_field.lua. A4's diffuse material under a point light of
attenuation {0, 0, 1} and intensity I is Mitsuba's `diffuse` BSDF under a `point`
emitter of intensity pi * I; one bounce, so the `direct` integrator; a `box` pixel
filter, as glint's uniform AA averages its pixel's strata. Written as half-float EXR
(96 x 72: 40 KiB). Run from the repository root:

    python3 tools/oracle/depth_of_field.py [spp]
"""
import math
import sys

import mitsuba as mi

mi.set_variant("scalar_rgb")

WIDTH, HEIGHT = 96, 72
EYE = [0.0, 2.0, 4.0]
VIEW = [0.0, -0.2, -1.0]
FOV = 40.0
APERTURE = 0.6
FOCUS = 6.2
LIGHT = ([3.0, 7.0, 4.0], 40.0)
SPHERES = [
    ([-1.2, 0.5, 1.0], 0.5, [0.8, 0.2, 0.15]),
    ([0.3, 1.0, -3.0], 1.0, [0.2, 0.7, 0.3]),
    ([2.2, 1.5, -9.0], 1.5, [0.15, 0.3, 0.8]),
]


def diffuse(rgb):
    return {"type": "diffuse", "reflectance": {"type": "rgb", "value": rgb}}


def scene(sensor_type, spp):
    target = [e + v for e, v in zip(EYE, VIEW)]
    sensor = {
        "type": sensor_type,
        "fov": FOV,
        "fov_axis": "y",
        "to_world": mi.ScalarTransform4f().look_at(origin=EYE, target=target, up=[0, 1, 0]),
        "sampler": {"type": "multijitter", "sample_count": spp},
        "film": {
            "type": "hdrfilm",
            "width": WIDTH,
            "height": HEIGHT,
            "pixel_format": "rgb",
            "rfilter": {"type": "box"},
        },
    }
    if sensor_type == "thinlens":
        sensor["aperture_radius"] = APERTURE
        sensor["focus_distance"] = FOCUS
    d = {
        "type": "scene",
        "integrator": {"type": "direct"},
        "sensor": sensor,
        # glint's floor: the unit cube scaled (40, 1, 40), moved by (-20, -1, -30).
        "floor": {
            "type": "cube",
            "to_world": mi.ScalarTransform4f().translate([0, -0.5, -10]).scale([20, 0.5, 20]),
            "bsdf": diffuse([0.8, 0.8, 0.8]),
        },
        "light": {
            "type": "point",
            "position": LIGHT[0],
            "intensity": {"type": "rgb", "value": [math.pi * LIGHT[1]] * 3},
        },
    }
    for i, (centre, radius, rgb) in enumerate(SPHERES):
        d[f"sphere{i}"] = {
            "type": "sphere",
            "center": centre,
            "radius": radius,
            "bsdf": diffuse(rgb),
        }
    return mi.load_dict(d)


def main():
    spp = int(sys.argv[1]) if len(sys.argv) > 1 else 4096
    for sensor_type, name in [("perspective", "pinhole"), ("thinlens", "depth_of_field")]:
        image = mi.render(scene(sensor_type, spp), spp=spp)
        bitmap = mi.Bitmap(image).convert(component_format=mi.Struct.Type.Float16)
        path = f"tests/oracle/refs/{name}.exr"
        bitmap.write(path)
        print(f"wrote {path} ({spp} spp)")


if __name__ == "__main__":
    main()
