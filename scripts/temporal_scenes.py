#!/usr/bin/env python3
"""The temporal evaluation's sequences (scripts/evaluate_temporal.sh), made from one pbrt-v3
scene whose second line is its camera's Transform:

  temporal_scenes.py SCENE OUT          writes OUT/static.pbrt (the scene as it is) and
                                        OUT/pan.pbrt (the camera orbiting the scene's
                                        vertical axis by 16 degrees over one second)
  temporal_scenes.py --strip-motion IN OUT N
                                        copies IN/f.0001.exr .. f.N.exr to OUT without
                                        their motion layer
"""
import os
import sys


def write_scenes(scene, out):
    lines = open(scene).read().split("\n")
    if not lines[1].startswith("Transform"):
        sys.exit(f"{scene}: expected the camera's Transform on line 2")
    base = os.path.dirname(os.path.abspath(scene))
    # Relative Includes and meshes keep resolving against the original directory.
    lines = [l.replace('"models/', f'"{base}/models/') for l in lines]
    with open(os.path.join(out, "static.pbrt"), "w") as f:
        f.write("\n".join(lines))
    camera = lines[1]
    orbit = ["TransformTimes 0 1",
             "ActiveTransform StartTime", camera, "Rotate -8 0 1 0",
             "ActiveTransform EndTime", camera, "Rotate 8 0 1 0",
             "ActiveTransform All"]
    with open(os.path.join(out, "pan.pbrt"), "w") as f:
        f.write("\n".join([lines[0]] + orbit + lines[2:]))


def strip_motion(src, dst, frames):
    import OpenImageIO as oiio
    for k in range(1, frames + 1):
        name = f"f.{k:04d}.exr"
        buf = oiio.ImageBuf(os.path.join(src, name))
        names = list(buf.spec().channelnames)
        keep = tuple(c for c in names if not c.startswith("motion."))
        out = oiio.ImageBufAlgo.channels(buf, keep)
        if not out.write(os.path.join(dst, name)):
            sys.exit(out.geterror())


if __name__ == "__main__":
    if sys.argv[1] == "--strip-motion":
        strip_motion(sys.argv[2], sys.argv[3], int(sys.argv[4]))
    else:
        write_scenes(sys.argv[1], sys.argv[2])
