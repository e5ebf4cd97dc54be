#!/usr/bin/env python3
"""Instructions a cold `glint render` spends, counted by valgrind: repeatable
where wall time on a shared VM is not.

    apt-get install valgrind
    python3 tools/callgrind/instructions.py spd:tetra                         # the shaded render
    python3 tools/callgrind/instructions.py spd:tetra --view depth --glint A B  # two builds side by side

Each binary renders the scene once under `valgrind --tool=callgrind` with
Mesa's shader cache disabled, and the instructions are split by where they
ran:
  * kernel: the JIT-compiled kernels themselves (code outside every mapped
    file), the per-pixel work the warm frames repeat;
  * compile: LLVM and Mesa (libLLVM, libgallium, lavapipe), the driver
    translating and compiling each pipeline, what a cold start pays;
  * other: everything else (the process, the scene, the BVH, the PNG).
The counts of one binary on one scene do not change from run to run or with
the machine's load, so a change of a fraction of a percent is a real one; on
an idle machine the wall time of a warm frame follows the kernel count
roughly, not exactly (spills and branch misses cost more than they count).
Valgrind runs the CPU instructions it supports, so a driver may compile
slightly different code under it than outside; compare builds under it only.
"""

import argparse
import os
import re
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
DRIVER = re.compile(r"libLLVM|libgallium|libvulkan_lvp")


def count(glint, scene, view, size):
    """(kernel, compile, other) instructions of one cold render."""
    with tempfile.TemporaryDirectory() as work:
        out = os.path.join(work, "callgrind.out")
        env = dict(os.environ, MESA_SHADER_CACHE_DISABLE="true")
        command = ["valgrind", "--tool=callgrind", "--smc-check=all", f"--callgrind-out-file={out}",
                   glint, "render", scene, "--view", view, "--width", str(size), "--height", str(size),
                   "-o", os.path.join(work, "image.png")]
        run = subprocess.run(command, env=env, capture_output=True, text=True)
        if run.returncode != 0:
            sys.exit(f"{glint} failed under valgrind:\n{run.stderr[-2000:]}")
        totals = per_object(out)
    kernel = sum(n for obj, n in totals.items() if obj == "???")
    compile_ = sum(n for obj, n in totals.items() if DRIVER.search(obj))
    return kernel, compile_, sum(totals.values()) - kernel - compile_


def per_object(path):
    """Instructions per object file (shared library, executable, or ??? for JIT code)."""
    listing = subprocess.run(["callgrind_annotate", "--threshold=100", path],
                             check=True, capture_output=True, text=True).stdout
    totals = {}
    for line in listing.splitlines():
        m = re.match(r"\s*([\d,]+) \([\s\d.]+%\)\s+\S.*\[(.*)\]\s*$", line)
        if m:
            obj = m.group(2)
            totals[obj] = totals.get(obj, 0) + int(m.group(1).replace(",", ""))
    return totals


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("scene", help="scene file or spd:NAME")
    parser.add_argument("--view", default="shaded")
    parser.add_argument("--size", type=int, default=512)
    parser.add_argument("--glint", nargs="+", default=[os.path.join(REPO, "target", "release", "glint")])
    args = parser.parse_args()
    print(f"{args.scene}, {args.view} view, {args.size}x{args.size}; millions of instructions, "
          "and each count against the first build's")
    print("| glint | kernel | vs first | compile | vs first | other |\n|---|---:|---:|---:|---:|---:|")
    first = None
    for glint in args.glint:
        kernel, compile_, other = count(glint, args.scene, args.view, args.size)
        first = first or (kernel, compile_)
        print(f"| {glint} | {kernel / 1e6:.1f} | {kernel / first[0]:.3f}x "
              f"| {compile_ / 1e6:.1f} | {compile_ / first[1]:.3f}x | {other / 1e6:.1f} |")


if __name__ == "__main__":
    main()
