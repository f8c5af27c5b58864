# Renders a glTF file as Blender 3.4's importer opens it, with Cycles, to compare with lamina render
# (README, "Light units in other viewers"). Usage:
#   blender -b --factory-startup -P tools/blender_render.py -- IN.glb OUT.png|OUT.exr
#       [--exposure STOPS] [--lighting-mode SPEC|COMPAT|RAW] [--width W] [--spp N]
# The import keeps the importer's defaults (lighting mode SPEC: lux / 683 for suns, candela * 4 pi /
# 683 watts for point and spot lights) unless --lighting-mode says otherwise. The view transform is
# Standard (the sRGB curve, as lamina's `clip` tone map), and the exposure Blender's own (stops).
# An .exr output holds scene-linear radiance without the exposure, as Blender writes it.
import argparse
import json
import struct
import sys

import bpy
import numpy

# Debian 12 pairs Blender 3.4 with NumPy 1.24, which removed the alias `numpy.bool` that the 3.4
# glTF importer still uses for meshes; the alias meant the built-in bool.
if not hasattr(numpy, "bool"):
    numpy.bool = bool

argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
parser = argparse.ArgumentParser(prog="blender_render.py")
parser.add_argument("input")
parser.add_argument("output")
parser.add_argument("--exposure", type=float, default=0.0)
parser.add_argument("--lighting-mode", default="SPEC", choices=["SPEC", "COMPAT", "RAW"])
parser.add_argument("--width", type=int, default=480)
parser.add_argument("--spp", type=int, default=64)
args = parser.parse_args(argv)



def first_camera(path):
    """The glTF file's first camera (name, aspect ratio): Blender 3.4's importer leaves the aspect out."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:4] == b"glTF":  # a .glb: the JSON chunk follows the 12-byte header
        length = struct.unpack_from("<I", data, 12)[0]
        data = data[20:20 + length]
    cameras = json.loads(data).get("cameras", [])
    if not cameras:
        sys.exit("blender_render.py: " + path + " has no camera")
    return cameras[0].get("name", ""), cameras[0].get("perspective", {}).get("aspectRatio", 1.5)


camera_name, aspect = first_camera(args.input)
bpy.ops.wm.read_factory_settings(use_empty=True)
bpy.ops.import_scene.gltf(filepath=args.input, convert_lighting_mode=args.lighting_mode)
scene = bpy.context.scene
cameras = sorted((o for o in scene.objects if o.type == "CAMERA"), key=lambda o: o.data.name != camera_name)
scene.camera = cameras[0]
scene.render.engine = "CYCLES"
scene.cycles.device = "CPU"
scene.cycles.samples = args.spp
scene.cycles.use_denoising = False
scene.render.resolution_x = args.width
scene.render.resolution_y = max(1, round(args.width / aspect))
scene.render.resolution_percentage = 100
scene.view_settings.view_transform = "Standard"
scene.view_settings.look = "None"
scene.view_settings.exposure = args.exposure
if args.output.lower().endswith(".exr"):
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
else:
    scene.render.image_settings.file_format = "PNG"
scene.render.filepath = args.output
bpy.ops.render.render(write_still=True)
