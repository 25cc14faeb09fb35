"""The real-renderer suite's Blender Cycles scenes (docs/evaluation-notes.md, "The Cycles
suite"), built from nothing and saved as .blend files for blender/statmc_cycles_passes.py:

    blender -b --factory-startup -P bench/evaluation/cycles_scenes.py -- \
        --scene NAME --resolution WxH --save OUT.blend

- glints:   rough gold, copper and smooth silver spheres on a checker floor, lit by one small,
            strong spherical light under a dim sky: small highlights and their glints.
- caustic:  a glass sphere and a glass block on a white floor before a wall, a small strong
            light beside them and a dim panel: caustics reached only by BSDF sampling.
- dof:      textured objects at several depths through a f/1.4 lens focused on the middle
            one, small bright lamps far behind (defocused discs), a sun and a blue sky.
- interior: kept aside from every choice of the default (docs/evaluation-notes.md): a room
            lit by six small coloured lamps of different strengths, a glossy tiled floor
            that mirrors them, a rough metal bowl, textured walls, and a ceiling reached
            only by bounces.

Each scene is built to break a denoiser in one way nobody here tuned for; none is shaped
after the figures it gives.
"""

import argparse
import math
import sys

import bpy


def arguments():
    parser = argparse.ArgumentParser()
    parser.add_argument("--scene", required=True,
                        choices=("glints", "caustic", "dof", "interior"))
    parser.add_argument("--resolution", default="320x180")
    parser.add_argument("--save", required=True)
    return parser.parse_args(sys.argv[sys.argv.index("--") + 1:])


def principled(name, colour, roughness=0.5, metallic=0.0, transmission=0.0, emission=0.0,
               texture=None, glow=(1.0, 0.9, 0.75)):
    m = bpy.data.materials.new(name)
    m.use_nodes = True
    nodes, links = m.node_tree.nodes, m.node_tree.links
    bsdf = nodes["Principled BSDF"]
    bsdf.inputs["Base Color"].default_value = (*colour, 1.0)
    bsdf.inputs["Roughness"].default_value = roughness
    bsdf.inputs["Metallic"].default_value = metallic
    bsdf.inputs["Transmission"].default_value = transmission
    if transmission:
        bsdf.inputs["IOR"].default_value = 1.5
    if emission:
        bsdf.inputs["Emission"].default_value = (*glow, 1.0)
        bsdf.inputs["Emission Strength"].default_value = emission
    if texture:
        kind, scale, second = texture
        tex = nodes.new(kind)
        tex.inputs["Scale"].default_value = scale
        if kind == "ShaderNodeTexChecker":
            tex.inputs["Color1"].default_value = (*colour, 1.0)
            tex.inputs["Color2"].default_value = (*second, 1.0)
            links.new(tex.outputs["Color"], bsdf.inputs["Base Color"])
        else:  # a grey-scale pattern between the colour and `second`
            ramp = nodes.new("ShaderNodeValToRGB")
            ramp.color_ramp.elements[0].color = (*colour, 1.0)
            ramp.color_ramp.elements[1].color = (*second, 1.0)
            links.new(tex.outputs["Fac"], ramp.inputs["Fac"])
            links.new(ramp.outputs["Color"], bsdf.inputs["Base Color"])
    return m


def add(obj, mat):
    obj.data.materials.append(mat)
    return obj


def sphere(location, radius, mat):
    bpy.ops.mesh.primitive_uv_sphere_add(radius=radius, location=location, segments=64,
                                         ring_count=32)
    bpy.ops.object.shade_smooth()
    return add(bpy.context.active_object, mat)


def plane(location, rotation, size, mat):
    bpy.ops.mesh.primitive_plane_add(size=size, location=location, rotation=rotation)
    return add(bpy.context.active_object, mat)


def cube(location, size, rotation, mat, scale=(1, 1, 1)):
    bpy.ops.mesh.primitive_cube_add(size=size, location=location, rotation=rotation)
    obj = bpy.context.active_object
    obj.scale = scale
    return add(obj, mat)


def camera(scene, location, target, lens=35, fstop=0.0, focus=None):
    data = bpy.data.cameras.new("camera")
    data.lens = lens
    if fstop:
        data.dof.use_dof = True
        data.dof.aperture_fstop = fstop
        data.dof.focus_distance = focus
    cam = bpy.data.objects.new("camera", data)
    cam.location = location
    direction = [t - l for t, l in zip(target, location)]
    # Blender's camera looks down its -Z: aim it with a track quaternion.
    from mathutils import Vector
    cam.rotation_euler = Vector(direction).to_track_quat("-Z", "Y").to_euler()
    scene.collection.objects.link(cam)
    scene.camera = cam


def world(scene, colour, strength):
    w = bpy.data.worlds.new("world")
    w.use_nodes = True
    background = w.node_tree.nodes["Background"]
    background.inputs["Color"].default_value = (*colour, 1.0)
    background.inputs["Strength"].default_value = strength
    scene.world = w


def glints(scene):
    floor = principled("floor", (0.5, 0.5, 0.5), roughness=0.7,
                       texture=("ShaderNodeTexChecker", 8.0, (0.08, 0.08, 0.08)))
    plane((0, 0, 0), (0, 0, 0), 12, floor)
    sphere((-0.9, 0.3, 0.4), 0.4, principled("gold", (1.0, 0.77, 0.34), roughness=0.15,
                                             metallic=1.0))
    sphere((0.05, 0.0, 0.35), 0.35, principled("copper", (0.95, 0.64, 0.54), roughness=0.3,
                                               metallic=1.0))
    sphere((0.85, 0.4, 0.3), 0.3, principled("silver", (0.97, 0.96, 0.91), roughness=0.04,
                                             metallic=1.0))
    sphere((1.6, 2.2, 2.6), 0.06, principled("lamp", (0, 0, 0), emission=2500.0))
    world(scene, (0.4, 0.5, 0.7), 0.04)
    camera(scene, (0.0, -4.0, 1.3), (0.0, 0.3, 0.35), lens=45)


def caustic(scene):
    white = principled("white", (0.8, 0.8, 0.8), roughness=0.9)
    plane((0, 0, 0), (0, 0, 0), 8, white)
    plane((0, 1.5, 1.5), (math.pi / 2, 0, 0), 8, principled("wall", (0.6, 0.55, 0.5),
                                                             roughness=0.9))
    glass = principled("glass", (1, 1, 1), roughness=0.0, transmission=1.0)
    sphere((-0.45, 0.2, 0.45), 0.45, glass)
    cube((0.6, 0.4, 0.3), 0.6, (0, 0, 0.5), glass)
    sphere((-1.6, -0.4, 1.5), 0.12, principled("lamp", (0, 0, 0), emission=800.0))
    plane((1.8, 1.49, 1.6), (math.pi / 2, 0, 0), 0.5, principled("panel", (0, 0, 0),
                                                                emission=20.0))
    world(scene, (1, 1, 1), 0.02)
    camera(scene, (0.3, -3.6, 1.6), (0.0, 0.3, 0.35), lens=40)


def dof(scene):
    plane((0, 2, 0), (0, 0, 0), 20, principled(
        "ground", (0.35, 0.3, 0.22), roughness=0.8,
        texture=("ShaderNodeTexNoise", 6.0, (0.12, 0.1, 0.08))))
    cube((-0.9, -1.2, 0.3), 0.6, (0, 0, 0.4), principled(
        "near", (0.7, 0.2, 0.1), roughness=0.5,
        texture=("ShaderNodeTexChecker", 12.0, (0.9, 0.85, 0.7))))
    sphere((0.1, 0.2, 0.45), 0.45, principled(
        "focus", (0.15, 0.3, 0.6), roughness=0.35,
        texture=("ShaderNodeTexWave", 5.0, (0.85, 0.85, 0.8))))
    cube((1.0, 2.5, 0.6), 1.2, (0, 0, -0.3), principled(
        "far", (0.3, 0.5, 0.2), roughness=0.6,
        texture=("ShaderNodeTexNoise", 3.0, (0.7, 0.75, 0.4))))
    lamp = principled("lamp", (0, 0, 0), emission=300.0)
    for i in range(5):
        sphere((-2.2 + 1.1 * i, 6.0 + 0.3 * (i % 2), 0.5 + 0.35 * (i % 3)), 0.04, lamp)
    sun = bpy.data.lights.new("sun", "SUN")
    sun.energy = 3.0
    sun.angle = math.radians(2.0)
    sun_obj = bpy.data.objects.new("sun", sun)
    sun_obj.rotation_euler = (math.radians(50), 0, math.radians(-40))
    scene.collection.objects.link(sun_obj)
    world(scene, (0.45, 0.6, 0.9), 0.6)
    camera(scene, (0.3, -4.2, 0.9), (0.1, 0.2, 0.45), lens=50, fstop=1.4, focus=4.45)


def interior(scene):
    plane((0, 0, 0), (0, 0, 0), 8, principled(
        "tiles", (0.3, 0.27, 0.24), roughness=0.12,
        texture=("ShaderNodeTexChecker", 10.0, (0.06, 0.055, 0.05))))
    plane((0, 2.0, 1.5), (math.pi / 2, 0, 0), 8, principled(
        "plaster", (0.62, 0.58, 0.5), roughness=0.9,
        texture=("ShaderNodeTexNoise", 8.0, (0.4, 0.36, 0.3))))
    plane((-2.2, 0, 1.5), (0, math.pi / 2, 0), 8, principled("red", (0.5, 0.12, 0.08),
                                                            roughness=0.8))
    plane((0, 0, 2.6), (0, 0, 0), 8, principled("ceiling", (0.75, 0.75, 0.75), roughness=0.9))
    shelf = principled("shelf", (0.25, 0.15, 0.08), roughness=0.5)
    cube((0.0, 1.6, 0.8), 1.0, (0, 0, 0), shelf, scale=(1.9, 0.35, 0.04))
    sphere((0.6, 0.2, 0.28), 0.28, principled("bowl", (0.9, 0.9, 0.88), roughness=0.2,
                                              metallic=1.0))
    lamps = [((-1.5, 1.6, 0.87), 0.035, 1500.0, (1.0, 0.55, 0.2)),
             ((-0.8, 1.55, 0.88), 0.045, 700.0, (0.2, 0.5, 1.0)),
             ((-0.1, 1.65, 0.86), 0.025, 3000.0, (1.0, 0.95, 0.85)),
             ((0.7, 1.5, 0.89), 0.05, 500.0, (0.35, 1.0, 0.3)),
             ((1.4, 1.6, 0.87), 0.03, 1200.0, (0.9, 0.2, 0.8)),
             ((-1.2, 0.3, 2.2), 0.04, 900.0, (1.0, 0.85, 0.6))]
    for i, (where, radius, strength, glow) in enumerate(lamps):
        sphere(where, radius, principled(f"lamp{i}", (0, 0, 0), emission=strength, glow=glow))
    world(scene, (0.3, 0.35, 0.45), 0.01)
    camera(scene, (0.4, -3.4, 1.35), (0.0, 0.9, 0.75), lens=32)


def main():
    args = arguments()
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.max_bounces = 12
    scene.cycles.transmission_bounces = 12
    scene.cycles.use_adaptive_sampling = False
    scene.cycles.use_denoising = False
    # Clamping off: statmc's promise is about the renderer's own light, caustics included.
    scene.cycles.sample_clamp_direct = 0.0
    scene.cycles.sample_clamp_indirect = 0.0
    scene.cycles.caustics_reflective = True
    scene.cycles.caustics_refractive = True
    scene.cycles.blur_glossy = 0.0
    width, height = (int(v) for v in args.resolution.split("x"))
    scene.render.resolution_x, scene.render.resolution_y = width, height
    scene.render.resolution_percentage = 100
    {"glints": glints, "caustic": caustic, "dof": dof, "interior": interior}[args.scene](scene)
    bpy.ops.wm.save_as_mainfile(filepath=args.save)


main()
