"""A small Cornell-style scene rendered by Blender's Cycles into multilayer EXRs with the
denoising passes: K passes with different seeds, and optionally a reference.

blender -b --factory-startup --python scripts/cycles_scene.py -- \
    --out DIR --passes K --samples S --resolution WxH [--reference SAMPLES]

Writes DIR/pass000.exr ... (view layer "ViewLayer": Combined, Denoising Albedo/Normal/Depth,
and the light groups Combined_key and Combined_fill) and DIR/reference.exr. Adaptive sampling and Blender's own denoiser are off, so each pass
is S independent samples per pixel.
"""

import argparse
import os
import sys

import bpy


def arguments():
    parser = argparse.ArgumentParser()
    parser.add_argument("--out", required=True)
    parser.add_argument("--passes", type=int, default=8)
    parser.add_argument("--samples", type=int, default=4)
    parser.add_argument("--resolution", default="320x240")
    parser.add_argument("--reference", type=int, default=0)
    return parser.parse_args(sys.argv[sys.argv.index("--") + 1:])


def material(name, colour, emission=0.0, roughness=0.8, metallic=0.0):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    bsdf = m.node_tree.nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (*colour, 1.0)
    bsdf.inputs["Roughness"].default_value = roughness
    bsdf.inputs["Metallic"].default_value = metallic
    if emission:
        bsdf.inputs["Emission"].default_value = (1.0, 0.85, 0.6, 1.0)
        bsdf.inputs["Emission Strength"].default_value = emission
    return m


def plane(name, location, rotation, size, mat):
    bpy.ops.mesh.primitive_plane_add(size=size, location=location, rotation=rotation)
    obj = bpy.context.active_object
    obj.name = name
    obj.data.materials.append(mat)
    return obj


def build_scene(width, height):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.use_adaptive_sampling = False
    scene.cycles.use_denoising = False
    scene.cycles.max_bounces = 8
    scene.render.resolution_x, scene.render.resolution_y = width, height
    scene.render.resolution_percentage = 100
    scene.render.film_transparent = False
    settings = scene.render.image_settings
    settings.file_format = "OPEN_EXR_MULTILAYER"
    settings.color_depth = "32"
    settings.exr_codec = "ZIP"
    scene.view_layers[0].cycles.denoising_store_passes = True

    half_pi = 1.5707963
    white = material("white", (0.73, 0.73, 0.73))
    plane("floor", (0, 0, 0), (0, 0, 0), 2, white)
    plane("ceiling", (0, 0, 2), (0, 0, 0), 2, white)
    plane("back", (0, 1, 1), (half_pi, 0, 0), 2, white)
    plane("left", (-1, 0, 1), (0, half_pi, 0), 2, material("red", (0.63, 0.06, 0.05)))
    plane("right", (1, 0, 1), (0, half_pi, 0), 2, material("green", (0.14, 0.45, 0.09)))
    # Two light groups that add up to Combined (the world is black): the ceiling light and
    # a dim panel low on the back wall.
    layer = scene.view_layers[0]
    for group in ("key", "fill"):
        layer.lightgroups.add(name=group)
    plane("light", (0, 0, 1.99), (0, 0, 0), 0.5,
          material("light", (0, 0, 0), emission=12.0)).lightgroup = "key"
    plane("fill", (0.55, 0.99, 0.25), (half_pi, 0, 0), 0.3,
          material("fill", (0, 0, 0), emission=4.0)).lightgroup = "fill"
    bpy.ops.mesh.primitive_cube_add(size=0.6, location=(-0.35, 0.3, 0.6))
    tall = bpy.context.active_object
    tall.scale = (1, 1, 2)
    tall.rotation_euler = (0, 0, 0.3)
    tall.data.materials.append(white)
    bpy.ops.mesh.primitive_uv_sphere_add(radius=0.3, location=(0.4, -0.2, 0.3), segments=64,
                                         ring_count=32)
    sphere = bpy.context.active_object
    bpy.ops.object.shade_smooth()
    sphere.data.materials.append(material("metal", (0.9, 0.9, 0.9), roughness=0.15,
                                          metallic=1.0))

    camera_data = bpy.data.cameras.new("camera")
    camera_data.lens = 35
    camera = bpy.data.objects.new("camera", camera_data)
    camera.location = (0, -3.4, 1)
    camera.rotation_euler = (half_pi, 0, 0)
    scene.collection.objects.link(camera)
    scene.camera = camera
    world = bpy.data.worlds.new("world")
    world.color = (0, 0, 0)
    scene.world = world
    return scene


def render(scene, samples, seed, path):
    scene.cycles.samples = samples
    scene.cycles.seed = seed
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)


def main():
    args = arguments()
    width, height = (int(v) for v in args.resolution.split("x"))
    os.makedirs(args.out, exist_ok=True)
    scene = build_scene(width, height)
    for k in range(args.passes):
        render(scene, args.samples, k + 1, os.path.join(args.out, f"pass{k:03d}.exr"))
    if args.reference:
        render(scene, args.reference, 100000, os.path.join(args.out, "reference.exr"))


main()
