"""Render K passes of a .blend with Blender's Cycles for statmc's --passes.

    blender -b scene.blend -P blender/statmc_cycles_passes.py -- K OUT_DIR \\
        [--frames A-B] [--samples N] [--seed S] [--adaptive on|off|scene] [--use-cycles]

Each pass is a full render of the frame with its own seed: pass k (0 .. K-1) of frame f gets
seed S + K*(f - F) + k, F being the scene's start frame. Every (frame, pass) of a shot thus
has a seed of its own, however its frames are split between runs or machines, and a still at
the start frame gets S .. S+K-1. Pass k of frame f is written to OUT_DIR/pass{k:03d}-{f:04d}.exr:
multilayer OpenEXR, 32-bit float, with the Denoising Data passes (statmc's albedo and normal
guides). Blender's own denoiser, the compositor and the sequencer are off for these renders,
and nothing is saved into the .blend. At the end, the statmc command to run next is printed.
Blender 3.0 or later (tested with Debian 12's 3.4.1). docs/renderers.md has the details.
"""

import argparse
import os
import sys
import time

import bpy

PROG = "statmc_cycles_passes"


def fail(message):
    print(f"{PROG}: error: {message}", file=sys.stderr)
    sys.exit(1)


class Parser(argparse.ArgumentParser):
    def error(self, message):  # argparse exits with 2; the message format stays ours
        self.print_usage(sys.stderr)
        fail(message)


def frame_range(text):
    first, _, last = text.partition("-")
    try:
        return int(first), int(last or first)
    except ValueError:
        raise argparse.ArgumentTypeError(f"--frames wants A-B or A, got {text!r}")


def arguments():
    parser = Parser(prog=f"blender -b scene.blend -P {PROG}.py --",
                    description="Render K passes with distinct seeds for statmc --passes.")
    parser.add_argument("K", type=int, help="passes per frame (2 or more)")
    parser.add_argument("out_dir", metavar="OUT_DIR")
    parser.add_argument("--frames", type=frame_range, metavar="A-B",
                        help="frames to render (default: the current frame)")
    parser.add_argument("--samples", type=int, metavar="N",
                        help="samples per pass (default: the scene's Render > Max Samples)")
    parser.add_argument("--seed", type=int, default=0, metavar="S", help="first seed (0)")
    parser.add_argument("--adaptive", choices=("on", "off", "scene"), default="scene",
                        help="Cycles' adaptive sampling (default: as the scene has it)")
    # Not "--cycles": Cycles reads the arguments after "--" too, and would take it for an
    # abbreviation of its own --cycles-device.
    parser.add_argument("--use-cycles", action="store_true",
                        help="switch the render engine to Cycles if the scene uses another")
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    args = parser.parse_args(argv)
    if not 2 <= args.K <= 999:  # 999: the file names have 3 digits for the pass
        fail(f"K must be 2 to 999 (got {args.K}): statmc estimates each pixel's variance "
             "from the spread of the passes")
    if args.samples is not None and args.samples < 1:
        fail(f"--samples must be 1 or more (got {args.samples})")
    if args.seed < 0:
        fail(f"--seed must be 0 or more (got {args.seed})")
    if args.frames and args.frames[0] > args.frames[1]:
        fail(f"--frames {args.frames[0]}-{args.frames[1]}: the first frame is after the last")
    return args


def writable_directory(path):
    try:
        os.makedirs(path, exist_ok=True)
        probe = os.path.join(path, f".{PROG}-{os.getpid()}")
        open(probe, "w").close()
        os.remove(probe)
    except OSError as e:
        fail(f"cannot write into OUT_DIR {path!r}: {e.strerror}")


def prepare(scene, args):
    """Set the scene up for statmc. Changes live only in this Blender process."""
    if scene.render.engine != "CYCLES":
        if not args.use_cycles:
            fail(f"the scene renders with {scene.render.engine}, not Cycles: choose Cycles in "
                 "Render Properties > Render Engine, or pass --use-cycles to switch for this run")
        print(f"{PROG}: switching the render engine from {scene.render.engine} to Cycles")
        scene.render.engine = "CYCLES"
    cycles = scene.cycles
    # statmc is the denoiser: Blender's would smooth each pass, so the passes would no longer
    # be independent samples (and Debian's Blender, built without OpenImageDenoise, fails
    # with "Build without OpenImageDenoiser" when it is on).
    cycles.use_denoising = False  # (the viewport's denoiser plays no part in -b renders)
    # The seed must be exactly what we set: the animated seed would hash in the frame.
    cycles.use_animated_seed = False
    if args.samples is not None:
        cycles.samples = args.samples
    # Either setting is sound for statmc, which counts each pass as one sample of the pixel
    # whatever number of samples Cycles spent there; the spread of the passes stays honest.
    if args.adaptive != "scene":
        cycles.use_adaptive_sampling = args.adaptive == "on"
    # Every pass must take the same number of samples: a time limit would stop them unevenly.
    cycles.time_limit = 0.0
    # Raw render passes only: the compositor and sequencer would rewrite Combined (a Denoise
    # node would also fail without OpenImageDenoise).
    scene.render.use_compositing = False
    scene.render.use_sequencer = False
    layers = ([bpy.context.view_layer] if scene.render.use_single_layer
              else [layer for layer in scene.view_layers if layer.use])
    for layer in layers:
        # Denoising Albedo/Normal/Depth: the guides statmc's test uses.
        layer.cycles.denoising_store_passes = True
    settings = scene.render.image_settings
    settings.file_format = "OPEN_EXR_MULTILAYER"  # every pass of every layer in one file
    settings.color_depth = "32"  # half floats would round the noise statmc measures
    settings.exr_codec = "ZIP"  # lossless
    return layers


def main():
    args = arguments()
    out_dir = os.path.abspath(args.out_dir)
    writable_directory(out_dir)
    scene = bpy.context.scene
    layers = prepare(scene, args)
    first, last = args.frames or (scene.frame_current,) * 2

    def seed(frame, k):  # distinct for every (frame, pass), fixed by the scene's start frame
        return args.seed + args.K * (frame - scene.frame_start) + k

    if seed(first, 0) < 0:
        fail(f"frame {first}, before the start frame {scene.frame_start}, would get a "
             f"negative seed: pass --seed {-seed(first, 0) + args.seed} or more")
    if seed(last, args.K - 1) > 2**31 - 1:
        fail("the seeds would pass Cycles' largest, 2147483647: lower --seed")
    adaptive = "on" if scene.cycles.use_adaptive_sampling else "off"
    frames = f"frame {first}" if first == last else f"frames {first}-{last}"
    print(f"{PROG}: {args.K} passes of {frames}, {scene.cycles.samples} samples "
          f"each, adaptive sampling {adaptive}, view layers: "
          + ", ".join(layer.name for layer in layers))
    started = time.time()
    for frame in range(first, last + 1):
        scene.frame_set(frame)
        for k in range(args.K):
            scene.cycles.seed = seed(frame, k)
            scene.render.filepath = os.path.join(out_dir, f"pass{k:03d}-{frame:04d}.exr")
            bpy.ops.render.render(write_still=True)
            print(f"{PROG}: frame {frame} pass {k} seed {scene.cycles.seed} -> "
                  f"{scene.render.filepath}", flush=True)
    print(f"{PROG}: rendered {args.K * (last - first + 1)} passes in "
          f"{time.time() - started:.1f} s; seeds {seed(first, 0)}-{seed(last, args.K - 1)}")

    if first == last and os.path.exists(os.path.join(out_dir, f"pass{args.K:03d}-{first:04d}.exr")):
        print(f"{PROG}: warning: {out_dir} holds pass{args.K:03d}-{first:04d}.exr from an "
              "earlier run with more passes: remove it, or the glob below takes it too")
    if len(layers) > 1:
        print(f"{PROG}: note: statmc's --passes takes one view layer per file: keep one with "
              "--ch (docs/renderers.md)")
    print("Next, denoise with statmc:")
    if first == last:
        print(f"  statmc {out_dir}/pass???-{first:04d}.exr --passes --denoise "
              f"-o {out_dir}/denoised-{first:04d}.exr")
    else:  # statmc runs the line once per frame, '#' standing for the frame as %04d
        names = " ".join(f"{out_dir}/pass{k:03d}-#.exr" for k in range(args.K))
        print(f"  statmc {names} --frames {first}-{last} --passes --denoise "
              f"-o {out_dir}/denoised-#.exr")


main()
