#!/usr/bin/env python3
"""A newcomer's game, as CI checks it: a fresh cargo project with the README's `[dependencies]` (Bevy's
default features) and this crate as a path dependency, whose `main.rs` is the README's quick
start, built, run under Xvfb and Mesa's lavapipe, and photographed.

The game has no screenshot code of its own (it is the README's code and nothing else), so the
picture is taken from Xvfb's framebuffer (`-fbdir`, an XWD file), converted to PNG once the
flag, the physical cloth and the leaves are on screen. `tests/screenshots.rs` then checks it.

Usage: newcomer.py OUT.png
"""
import os
import re
import struct
import subprocess
import sys
import time
import zlib

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
PROJECT = os.path.join(ROOT, "target", "newcomer")


def quick_start():
    """The README's quick start: the first rust block after '## Quick start'."""
    text = open(os.path.join(ROOT, "README.md")).read()
    section = text[text.index("## Quick start"):]
    return re.search(r"```rust[^\n]*\n(.*?)```", section, re.S).group(1)


def install_lines():
    """The README's `[dependencies]` block under '## Install': Bevy's line as written, and this
    crate's with the clone's own path (the README's is the folder next to a game)."""
    text = open(os.path.join(ROOT, "README.md")).read()
    section = text[text.index("## Install"):]
    block = re.search(r"```toml\n(.*?)```", section, re.S).group(1)
    bevy = re.search(r"^bevy = .*$", block, re.M).group(0)
    ours = re.search(r"^bevy_windfall = \{ path = \"[^\"]+\" \}$", block, re.M)
    assert ours, "the README's install block depends on bevy_windfall by path"
    return bevy, f'bevy_windfall = {{ path = "{ROOT}" }}'


def write_project():
    os.makedirs(os.path.join(PROJECT, "src"), exist_ok=True)
    # The same dev profile as this crate's, so that the shared target directory reuses what it
    # can (a newcomer's project would build with cargo's defaults; only the build time differs).
    bevy, ours = install_lines()
    manifest = f"""[package]
name = "newcomer"
version = "0.1.0"
edition = "2024"

[dependencies]
{bevy}
{ours}

[profile.dev.package."*"]
debug = false
"""
    open(os.path.join(PROJECT, "Cargo.toml"), "w").write(manifest)
    open(os.path.join(PROJECT, "src", "main.rs"), "w").write(quick_start())
    code = open(os.path.join(PROJECT, "src", "main.rs")).read()
    uses = set(re.findall(r"^use ([^;]+);", code, re.M))
    assert uses <= {"bevy::prelude::*", "bevy_windfall::prelude::*"}, uses


def read_xwd(path):
    """(width, height, rgb bytes) of an XWD file of a 24/32-bit TrueColor screen."""
    data = open(path, "rb").read()
    for order in (">", "<"):
        header = struct.unpack(order + "25I", data[:100])
        if header[0] < 4096:
            break
    size, width, height = header[0], header[4], header[5]
    byte_order, bpp, line, ncolors = header[7], header[11], header[12], header[19]
    red_mask, green_mask, blue_mask = header[14], header[15], header[16]
    assert bpp == 32, f"{bpp} bits per pixel"
    start = size + 12 * ncolors
    fmt = "<" if byte_order == 0 else ">"
    rgb = bytearray(width * height * 3)
    shift = lambda m: (m & -m).bit_length() - 1
    rs, gs, bs = shift(red_mask), shift(green_mask), shift(blue_mask)
    for y in range(height):
        row = struct.unpack_from(f"{fmt}{width}I", data, start + y * line)
        out = rgb[y * width * 3:(y + 1) * width * 3]
        out[0::3] = bytes((p >> rs) & 255 for p in row)
        out[1::3] = bytes((p >> gs) & 255 for p in row)
        out[2::3] = bytes((p >> bs) & 255 for p in row)
        rgb[y * width * 3:(y + 1) * width * 3] = out
    return width, height, bytes(rgb)


def write_png(path, width, height, rgb):
    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))
    raw = b"".join(b"\0" + rgb[y * width * 3:(y + 1) * width * 3] for y in range(height))
    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(raw, 6)) + chunk(b"IEND", b"")
    open(path, "wb").write(png)


def shares(rgb, width):
    """Shares of pixels that are flag red and cloth blue (every 7th pixel), and leaf specks: runs
    of autumn colours (red above green above blue, as `tests/screenshots.rs` counts them) per
    1000 pixels of every 4th row."""
    red = blue = n = 0
    for i in range(0, len(rgb) - 2, 21):
        r, g, b = rgb[i], rgb[i + 1], rgb[i + 2]
        n += 1
        red += r > 90 and r > 2 * g and r > 2 * b
        blue += b > 80 and b > 1.5 * r and b > 1.2 * g
    runs = pixels = 0
    for row in range(0, len(rgb) // (3 * width), 4):
        line = rgb[row * width * 3:(row + 1) * width * 3]
        previous = False
        for x in range(width):
            r, g, b = line[3 * x], line[3 * x + 1], line[3 * x + 2]
            autumn = r > g + 10 and r > b + 40
            runs += autumn and not previous
            previous = autumn
        pixels += width
    return red / n, blue / n, 1000 * runs / max(pixels, 1)


def main():
    out = sys.argv[1]
    write_project()
    subprocess.run(["cargo", "build", "--ignore-rust-version", "--manifest-path", os.path.join(PROJECT, "Cargo.toml")],
                   check=True, env={**os.environ, "CARGO_TARGET_DIR": os.path.join(ROOT, "target")})
    fb = os.path.join(PROJECT, "fb")
    os.makedirs(fb, exist_ok=True)
    display = ":97"
    xvfb = subprocess.Popen(["Xvfb", display, "-screen", "0", "1280x720x24", "-fbdir", fb, "-nolisten", "tcp"])
    time.sleep(2)
    log = open(os.path.join(PROJECT, "log.txt"), "w")
    game = subprocess.Popen([os.path.join(ROOT, "target", "debug", "newcomer")], stdout=log, stderr=log,
                            env={**os.environ, "DISPLAY": display, "WGPU_BACKEND": "vulkan"})
    try:
        start, seen = time.time(), None
        while time.time() - start < 900:
            time.sleep(5)
            if game.poll() is not None:
                raise SystemExit(f"the game exited ({game.returncode}); see {log.name}")
            width, height, rgb = read_xwd(os.path.join(fb, "Xvfb_screen0"))
            red, blue, specks = shares(rgb, width)
            print(f"{time.time() - start:5.0f} s: red {red:.4f}, blue {blue:.4f}, leaf specks {specks:.2f}")
            if red > 0.002 and blue > 0.002 and specks > 0.3:
                seen = seen or time.time()
                # Ten seconds more: every pipeline in, the leaves falling.
                if time.time() - seen > 10:
                    break
        write_png(out, width, height, rgb)
        print(f"saved {out} after {time.time() - start:.0f} s")
    finally:
        game.kill()
        xvfb.kill()


if __name__ == "__main__":
    main()
