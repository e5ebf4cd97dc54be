#!/usr/bin/env python3
"""Glint against Mitsuba 3 on the same NFF files, side by side in one run.

    pip install mitsuba                  # its llvm variant needs libLLVM >= 16 (Debian 12: libllvm19)
    cargo build --release
    python3 tools/mitsuba/compare.py     # the seven classic SPD scenes and the Stanford bunny

For each scene, alternating the two renderers:
  * warm primary rays: `glint bench FILE --json` (median frame of the depth
    view, one eye ray per pixel) against Mitsuba's `aov` depth integrator,
    median of as many renders in one process, after the first render (JIT)
    and WARM_UP seconds of renders after it, for both renderers alike;
    the fastest of --warm-runs rounds, each round one process of each,
    alternating, so that a drift of the VM's speed between the two
    measurements (seen here: one renderer's warm frame 1.5-2x slower from one
    minute to the next) does not pass for a difference between them;
  * cold process (the fastest of --cold-runs rounds, each round one process
    of every kind): process start to image written with no shader or kernel
    cache — Glint with MESA_SHADER_CACHE_DISABLE=true, Mitsuba with an empty
    Dr.Jit kernel cache (a fresh HOME) — for Glint's shaded render and depth
    view, and Mitsuba's depth and path (max depth 5) renders;
  * the viewer's cold first image: `glint view --first-image` under Xvfb
    (process start to the first complete image on screen, no shader cache),
    against Mitsuba's cold path process (issue 17: within 2x, ratio >= 0.5).
Absolute times on shared VMs vary 2-3x between machines and days: only the
ratios of one run mean anything.
"""

import argparse
import json
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
# Seconds of untimed renders after the first: lavapipe runs its first frames
# after a compile up to twice as slow (docs/decisions/053-warm-frames-after-the-compile-settles.md).
WARM_UP = 0.2
REPO = os.path.dirname(os.path.dirname(HERE))
CLASSIC = ["balls", "gears", "mount", "rings", "teapot", "tetra", "tree"]


def bunny_nff(path, work):
    """The Stanford bunny of the npm package `bunny` (3,674 triangles) as NFF."""
    subprocess.run(["npm", "pack", "bunny", "--silent"], cwd=work, check=True, stdout=subprocess.DEVNULL)
    tarball = next(f for f in os.listdir(work) if f.startswith("bunny-") and f.endswith(".tgz"))
    subprocess.run(["tar", "xzf", tarball], cwd=work, check=True)
    script = "const b = require('./package'); console.log(JSON.stringify({p: b.positions, c: b.cells}))"
    data = json.loads(subprocess.run(["node", "-e", script], cwd=work, check=True, capture_output=True, text=True).stdout)
    points, cells = data["p"], data["c"]
    lo = [min(p[i] for p in points) for i in range(3)]
    hi = [max(p[i] for p in points) for i in range(3)]
    center = [(a + b) / 2 for a, b in zip(lo, hi)]
    radius = max(b - a for a, b in zip(lo, hi)) / 2 * 3 ** 0.5
    eye = [center[0], center[1] + 0.2 * radius, center[2] + 1.9 * radius]
    with open(path, "w") as f:
        f.write(f"v\nfrom {eye[0]} {eye[1]} {eye[2]}\nat {center[0]} {center[1]} {center[2]}\nup 0 1 0\n"
                "angle 45\nhither 0.01\nresolution 512 512\nb 0.1 0.1 0.2\n")
        f.write(f"l {eye[0] + radius} {eye[1] + 2 * radius} {eye[2]}\n")
        f.write("f 0.8 0.7 0.6 0.8 0.2 30 0 1\n")
        for a, b, c in cells:
            f.write("p 3\n")
            for i in (a, b, c):
                f.write(f"{points[i][0]} {points[i][1]} {points[i][2]}\n")
    return len(cells)


def timed(command, env=None):
    start = time.perf_counter()
    subprocess.run(command, check=True, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.perf_counter() - start


def glint_warm(glint, nff, size, frames):
    out = subprocess.run([glint, "bench", nff, "--width", str(size), "--height", str(size), "--frames", str(frames),
                          "--warm-up", str(WARM_UP), "--json"],
                         check=True, capture_output=True, text=True).stdout
    return json.loads(out.splitlines()[-1])["primary_ms"] / 1e3


def glint_cold(glint, nff, size, view, work):
    env = dict(os.environ, MESA_SHADER_CACHE_DISABLE="true")
    out = os.path.join(work, f"glint-{view}.png")
    return timed([glint, "render", nff, "--width", str(size), "--height", str(size), "--view", view, "-o", out, "--quiet"], env)


def glint_viewer_cold(glint, nff):
    """`glint view --first-image` under Xvfb with no shader cache: the viewer's
    own report of process start to first complete image on screen."""
    env = dict(os.environ, MESA_SHADER_CACHE_DISABLE="true")
    out = subprocess.run(["xvfb-run", "-a", "-s", "-screen 0 1280x800x24", glint, "view", "--first-image", nff],
                         check=True, env=env, capture_output=True, text=True).stdout
    # "first image after 0.81 s (quick kernels, 256 bits)"
    return float(re.search(r"first image after ([0-9.]+) s", out).group(1))


def mitsuba_run(nff, size, mode, integrator, frames, work):
    """Runs this script as a Mitsuba worker in a fresh process; returns its report."""
    env = dict(os.environ)
    if mode == "cold":
        env["HOME"] = tempfile.mkdtemp(dir=work)  # Dr.Jit keeps its kernel cache in ~/.drjit
    command = [sys.executable, __file__, "--worker", nff, "--size", str(size), "--mode", mode,
               "--integrator", integrator, "--frames", str(frames), "--work", work]
    start = time.perf_counter()
    run = subprocess.run(command, env=env, capture_output=True, text=True)
    wall = time.perf_counter() - start
    if run.returncode != 0:
        sys.exit(f"Mitsuba ({integrator}, {mode}) failed on {nff}: {last_error(run)}")
    report = json.loads(run.stdout.splitlines()[-1])
    report["wall"] = wall
    return report


def last_error(run):
    """The last line a failed process wrote that is not a dump's indented detail."""
    errors = [line for line in run.stderr.splitlines() if line.strip() and not line.startswith(" ")]
    return errors[-1] if errors else f"exit code {run.returncode}"


def check_llvm():
    """Dr.Jit takes the first libLLVM it finds; with one older than 16 (Debian
    12's lavapipe brings libLLVM 15) Mitsuba's kernels can fail to compile."""
    probe = "import mitsuba as mi; mi.set_variant('llvm_ad_rgb'); import drjit as dr; print(dr.detail.llvm_version()[0])"
    run = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True)
    if run.returncode != 0:
        sys.exit(f"Mitsuba's llvm variant does not load: {last_error(run)}")
    if int(run.stdout.split()[-1]) < 16:
        sys.exit(f"Dr.Jit found libLLVM {run.stdout.split()[-1]}; Mitsuba's llvm variant needs 16 or later (Debian 12: apt-get install libllvm19)")


def worker(args):
    import mitsuba as mi
    mi.set_variant("llvm_ad_rgb")
    import drjit as dr
    sys.path.insert(0, HERE)
    from nff_scene import read_nff, scene_dict
    integrator = {"type": "aov", "aovs": "dd:depth"} if args.integrator == "depth" else {"type": "path", "max_depth": 5}
    nff = read_nff(args.worker)
    ply = os.path.join(args.work, os.path.basename(args.worker) + f".{os.getpid()}.ply")
    scene = mi.load_dict(scene_dict(mi, nff, ply, args.size, args.size, integrator))

    def render():
        image = mi.render(scene, spp=1)
        dr.eval(image)
        dr.sync_thread()
        return image

    if args.mode == "cold":
        mi.util.write_bitmap(os.path.join(args.work, f"mitsuba-{args.integrator}.exr"), render())
        print(json.dumps({}))
        return
    render()
    warm = time.perf_counter() + WARM_UP
    while time.perf_counter() < warm:
        render()
    times = []
    for _ in range(args.frames):
        start = time.perf_counter()
        render()
        times.append(time.perf_counter() - start)
    print(json.dumps({"median": statistics.median(times)}))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("scenes", nargs="*", help="SPD names or NFF files (default: the classic seven and the bunny)")
    parser.add_argument("--glint", default=os.path.join(REPO, "target", "release", "glint"))
    parser.add_argument("--size", type=int, default=512)
    parser.add_argument("--frames", type=int, default=5)
    parser.add_argument("--warm-runs", type=int, default=3,
                        help="rounds of warm processes (one of each renderer per round); the fastest of each counts")
    parser.add_argument("--no-cold", action="store_true", help="skip the cold-process measurements")
    parser.add_argument("--cold-runs", type=int, default=3,
                        help="rounds of cold processes (one of each kind per round); the fastest of each kind counts")
    parser.add_argument("--no-viewer", action="store_true", help="skip the viewer's cold first image (needs xvfb-run)")
    parser.add_argument("--worker", help=argparse.SUPPRESS)
    parser.add_argument("--mode", default="warm", help=argparse.SUPPRESS)
    parser.add_argument("--integrator", default="depth", help=argparse.SUPPRESS)
    parser.add_argument("--work", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.worker:
        return worker(args)

    check_llvm()
    work = tempfile.mkdtemp(prefix="glint-vs-mitsuba-")
    scenes = args.scenes or CLASSIC + ["bunny"]
    files = []
    for name in scenes:
        if os.path.exists(name):
            files.append((os.path.splitext(os.path.basename(name))[0], os.path.abspath(name)))
        elif name == "bunny":
            path = os.path.join(work, "bunny.nff")
            bunny_nff(path, work)
            files.append(("bunny", path))
        else:
            path = os.path.join(work, f"{name}.nff")
            subprocess.run([args.glint, "spd", name, "-o", path], check=True)
            files.append((name, path))

    print(f"{args.size}x{args.size}, warm: median of {args.frames} frames, fastest of {args.warm_runs} rounds; times in ms; "
          "each ratio is Mitsuba's time over Glint's (> 1: Glint faster)", flush=True)
    header = "| scene | Glint primary | Mitsuba depth | ratio |"
    rule = "|---|---:|---:|---:|"
    if not args.no_cold:
        header += " Glint cold depth | Mitsuba cold depth | ratio | Glint cold shaded | Mitsuba cold path | ratio |"
        rule += "---:|---:|---:|---:|---:|---:|"
        if not args.no_viewer:
            header += " Glint viewer cold first image | ratio to Mitsuba cold path |"
            rule += "---:|---:|"
    print(header)
    print(rule)
    for name, path in files:
        rounds = [(glint_warm(args.glint, path, args.size, args.frames),
                   mitsuba_run(path, args.size, "warm", "depth", args.frames, work)["median"])
                  for _ in range(args.warm_runs)]
        glint = min(g for g, _ in rounds)
        mitsuba = min(m for _, m in rounds)
        row = f"| {name} | {glint * 1e3:.1f} | {mitsuba * 1e3:.1f} | {mitsuba / glint:.2f} |"
        if not args.no_cold:
            measures = {
                "depth": lambda: glint_cold(args.glint, path, args.size, "depth", work),
                "m_depth": lambda: mitsuba_run(path, args.size, "cold", "depth", 1, work)["wall"],
                "shaded": lambda: glint_cold(args.glint, path, args.size, "shaded", work),
                "m_path": lambda: mitsuba_run(path, args.size, "cold", "path", 1, work)["wall"],
            }
            if not args.no_viewer:
                measures["viewer"] = lambda: glint_viewer_cold(args.glint, path)
            # The fastest of a few rounds: a shared VM's hiccups only ever add time.
            runs = [{kind: measure() for kind, measure in measures.items()} for _ in range(args.cold_runs)]
            t = {kind: min(run[kind] for run in runs) for kind in measures}
            row += f" {t['depth'] * 1e3:.0f} | {t['m_depth'] * 1e3:.0f} | {t['m_depth'] / t['depth']:.2f} |"
            row += f" {t['shaded'] * 1e3:.0f} | {t['m_path'] * 1e3:.0f} | {t['m_path'] / t['shaded']:.2f} |"
            if not args.no_viewer:
                row += f" {t['viewer'] * 1e3:.0f} | {t['m_path'] / t['viewer']:.2f} |"
        print(row, flush=True)


if __name__ == "__main__":
    main()
