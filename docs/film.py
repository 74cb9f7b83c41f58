#!/usr/bin/env python3
"""The README's moving picture, docs/showcase.gif, from the showcase tour's film frames.

    xvfb-run -a -s "-screen 0 1280x720x24" env WGPU_BACKEND=vulkan \\
        target/debug/examples/showcase --tour target/film --film --window 640x360 --msaa 1
    python3 docs/film.py target/film docs/showcase.gif

The tour saves the last 32 frames before its leaves and flag screenshots (`film_<scene>_<nn>.png`,
16 frames a second on the recording clock, so every run shows the same moment); this joins them
into one looping GIF with Pillow (Debian's python3-pil), each frame reduced to its own palette.
Usage: film.py FRAMES_DIR OUT.gif [WIDTH]
"""
import glob
import os
import sys

from PIL import Image

# The recording clock's frame: 62.5 ms of game time.
FRAME_MS = 62.5


def frames(folder, scene):
    paths = sorted(glob.glob(os.path.join(folder, f"film_{scene}_*.png")))
    if not paths:
        raise SystemExit(f"no film_{scene}_*.png in {folder}: run the tour with --film")
    return paths


def main():
    folder, out = sys.argv[1], sys.argv[2]
    width = int(sys.argv[3]) if len(sys.argv) > 3 else 480
    images = []
    for scene in ("leaves", "flag"):
        for path in frames(folder, scene):
            image = Image.open(path).convert("RGB")
            height = round(image.height * width / image.width)
            image = image.resize((width, height), Image.LANCZOS)
            images.append(image.quantize(colors=128, method=Image.Quantize.MEDIANCUT, dither=Image.Dither.NONE))
    images[0].save(
        out,
        save_all=True,
        append_images=images[1:],
        duration=round(FRAME_MS),
        loop=0,
        optimize=True,
        disposal=1,
    )
    print(f"{out}: {len(images)} frames, {width} px wide, {os.path.getsize(out)} bytes")


if __name__ == "__main__":
    main()
