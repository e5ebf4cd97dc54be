#!/usr/bin/env python3
"""Glint against Mitsuba 3 on the same NFF files, side by side in one run.

    pip install mitsuba matplotlib       # its llvm variant needs libLLVM >= 16 (Debian 12: libllvm19)
    cargo build --release
    python3 tools/mitsuba/compare.py     # every part below
    python3 tools/mitsuba/compare.py --part shaded --part sweep

Three parts, each chosen with --part (default: all three).

primary: for each scene (default: the classic seven and the Stanford bunny),
alternating the two renderers:
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

shaded: the same scenes' shaded frame, same work: Glint's Whitted frame at
`--max-depth 1` (`glint bench`'s render_ms: eye rays and a shadow ray per
light at each hit facing it) against Mitsuba's `direct` integrator with no
BSDF samples and one emitter sample per light (Mitsuba's emitter sample picks
one light, so emitter_samples is the number of lights); warm, as primary.

sweep: the primary frame (as primary) and the depth-1 shaded frame (as
shaded) against the primitive count: `glint spd tetra --size N`
(--tetra-sizes), `glint spd teapot --size N` (--teapot-sizes, its
tessellation), and a dense icosphere filling the view (--sphere-subdivisions:
20·n² triangles, 224 gives 1,003,520). Writes PREFIX.csv and a log-log plot
PREFIX.svg of time against primitives (--sweep-out; the plot needs matplotlib).

Absolute times on shared VMs vary 2-3x between machines and days: only the
ratios of one run mean anything.
"""

import argparse
import csv
import json
import math
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


def sphere_nff(path, n):
    """A unit icosphere of 20·n² triangles (each icosahedron face cut into n²,
    pushed onto the sphere), seen from close enough that it fills the view."""
    t = (1 + 5 ** 0.5) / 2
    corners = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
               (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2),
             (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5),
             (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]

    def point(weights):
        # Summed in corner order, so that faces sharing an edge write its
        # points to the same bits and the mesh stays watertight.
        p = [0.0, 0.0, 0.0]
        for corner, w in sorted(weights):
            for k in range(3):
                p[k] += w * corners[corner][k]
        r = math.sqrt(sum(c * c for c in p))
        return " ".join(f"{c / r:.7g}" for c in p)

    # From 1.8 radii a sphere spans 33.7° each side of the axis, beyond the
    # 30.4° of this view's corners: every eye ray hits.
    with open(path, "w") as f:
        f.write("v\nfrom 0 0 1.8\nat 0 0 0\nup 0 1 0\nangle 45\nhither 0.01\nresolution 512 512\nb 0.1 0.1 0.2\n"
                "l 1 1.5 3\nf 0.8 0.7 0.6 0.9 0 1 0 1\n")
        for a, b, c in faces:
            grid = {(i, j): point([(a, (n - i - j) / n), (b, i / n), (c, j / n)])
                    for i in range(n + 1) for j in range(n + 1 - i)}
            for i in range(n):
                for j in range(n - i):
                    f.write(f"p 3\n{grid[i, j]}\n{grid[i + 1, j]}\n{grid[i, j + 1]}\n")
                    if i + j < n - 1:
                        f.write(f"p 3\n{grid[i + 1, j]}\n{grid[i + 1, j + 1]}\n{grid[i, j + 1]}\n")


def timed(command, env=None):
    start = time.perf_counter()
    subprocess.run(command, check=True, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.perf_counter() - start


def glint_bench(glint, nff, size, frames, max_depth=None):
    """`glint bench --json`'s report: primary_ms (the depth view with its view's
    host work), render_ms (the Whitted frame), prims, and the rays by kind."""
    command = [glint, "bench", nff, "--width", str(size), "--height", str(size), "--frames", str(frames),
               "--warm-up", str(WARM_UP), "--json"]
    if max_depth is not None:
        command += ["--max-depth", str(max_depth)]
    out = subprocess.run(command, check=True, capture_output=True, text=True).stdout
    return json.loads(out.splitlines()[-1])


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
    """Runs this script as a Mitsuba worker in a fresh process; returns its
    report. Warm, `integrator` may name several, comma-separated: each is timed
    on the one loaded scene and the report has a median for each."""
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


def integrator_dict(name, nff):
    if name == "depth":
        return {"type": "aov", "aovs": "dd:depth"}
    if name == "direct":
        # Glint's depth-1 frame casts a shadow ray per light; each of Mitsuba's
        # emitter samples picks one light.
        return {"type": "direct", "emitter_samples": max(len(nff["lights"]), 1), "bsdf_samples": 0}
    return {"type": "path", "max_depth": 5}


def worker(args):
    import mitsuba as mi
    mi.set_variant("llvm_ad_rgb")
    import drjit as dr
    sys.path.insert(0, HERE)
    from nff_scene import read_nff, scene_dict
    names = args.integrator.split(",")
    nff = read_nff(args.worker)
    ply = os.path.join(args.work, os.path.basename(args.worker) + f".{os.getpid()}.ply")
    scene = mi.load_dict(scene_dict(mi, nff, ply, args.size, args.size, integrator_dict(names[0], nff)))
    integrators = [scene.integrator()] + [mi.load_dict(integrator_dict(name, nff)) for name in names[1:]]

    def render(integrator):
        image = mi.render(scene, integrator=integrator, spp=1)
        dr.eval(image)
        dr.sync_thread()
        return image

    if args.mode == "cold":
        mi.util.write_bitmap(os.path.join(args.work, f"mitsuba-{args.integrator}.exr"), render(integrators[0]))
        print(json.dumps({}))
        return
    medians = {}
    for name, integrator in zip(names, integrators):
        render(integrator)
        warm = time.perf_counter() + WARM_UP
        while time.perf_counter() < warm:
            render(integrator)
        times = []
        for _ in range(args.frames):
            start = time.perf_counter()
            render(integrator)
            times.append(time.perf_counter() - start)
        medians[name] = statistics.median(times)
    print(json.dumps({"median": medians}))


def fastest(rounds):
    """The fastest of each measure over rounds of {measure: seconds}: a shared
    VM's hiccups only ever add time."""
    return {key: min(r[key] for r in rounds) for key in rounds[0]}


def sizes(text):
    return [int(n) for n in text.split(",") if n]


def scene_files(args, work):
    files = []
    for name in args.scenes or CLASSIC + ["bunny"]:
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
    return files


def primary_part(args, files, work):
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
        t = fastest([{"glint": glint_bench(args.glint, path, args.size, args.frames)["primary_ms"] / 1e3,
                      "mitsuba": mitsuba_run(path, args.size, "warm", "depth", args.frames, work)["median"]["depth"]}
                     for _ in range(args.warm_runs)])
        row = f"| {name} | {t['glint'] * 1e3:.1f} | {t['mitsuba'] * 1e3:.1f} | {t['mitsuba'] / t['glint']:.2f} |"
        if not args.no_cold:
            measures = {
                "depth": lambda: glint_cold(args.glint, path, args.size, "depth", work),
                "m_depth": lambda: mitsuba_run(path, args.size, "cold", "depth", 1, work)["wall"],
                "shaded": lambda: glint_cold(args.glint, path, args.size, "shaded", work),
                "m_path": lambda: mitsuba_run(path, args.size, "cold", "path", 1, work)["wall"],
            }
            if not args.no_viewer:
                measures["viewer"] = lambda: glint_viewer_cold(args.glint, path)
            t = fastest([{kind: measure() for kind, measure in measures.items()} for _ in range(args.cold_runs)])
            row += f" {t['depth'] * 1e3:.0f} | {t['m_depth'] * 1e3:.0f} | {t['m_depth'] / t['depth']:.2f} |"
            row += f" {t['shaded'] * 1e3:.0f} | {t['m_path'] * 1e3:.0f} | {t['m_path'] / t['shaded']:.2f} |"
            if not args.no_viewer:
                row += f" {t['viewer'] * 1e3:.0f} | {t['m_path'] / t['viewer']:.2f} |"
        print(row, flush=True)


def warm_pair(args, path, work, mitsuba_integrators):
    """The fastest of --warm-runs rounds, each a `glint bench --max-depth 1`
    then a Mitsuba process timing `mitsuba_integrators`; and Glint's report."""
    rounds = []
    for _ in range(args.warm_runs):
        report = glint_bench(args.glint, path, args.size, args.frames, max_depth=1)
        t = {"primary": report["primary_ms"] / 1e3, "shaded": report["render_ms"] / 1e3}
        medians = mitsuba_run(path, args.size, "warm", ",".join(mitsuba_integrators), args.frames, work)["median"]
        t.update({f"m_{name}": seconds for name, seconds in medians.items()})
        rounds.append(t)
    return fastest(rounds), report


def shaded_part(args, files, work):
    print(f"\nShaded frame, same work: Glint's Whitted frame at --max-depth 1 against Mitsuba `direct` "
          f"(one emitter sample per light, no BSDF samples); {args.size}x{args.size}, warm: median of {args.frames} "
          f"frames, fastest of {args.warm_runs} rounds; Glint's speed is Mitsuba's time over Glint's (> 1: Glint faster)",
          flush=True)
    print("| scene | primitives | lights | eye rays | shadow rays | Glint ms | Mitsuba ms | Glint's speed |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    for name, path in files:
        t, report = warm_pair(args, path, work, ["direct"])
        kinds = report["kinds"]
        lights = sum(1 for line in open(path) if line.startswith("l "))
        print(f"| {name} | {report['prims']:,} | {lights} | {kinds['eye']['rays']:,} | {kinds['shadow']['rays']:,} "
              f"| {t['shaded'] * 1e3:.1f} | {t['m_direct'] * 1e3:.1f} | {t['m_direct'] / t['shaded']:.2f}× |", flush=True)


def sweep_part(args, work):
    points = [("tetra", n) for n in sizes(args.tetra_sizes)] + [("teapot", n) for n in sizes(args.teapot_sizes)]
    if args.sphere_subdivisions:
        points.append(("sphere", args.sphere_subdivisions))
    print(f"\nScale sweep: the primary frame (with its view's host work) against Mitsuba's depth AOV, and the "
          f"depth-1 shaded frame against Mitsuba `direct`; {args.size}x{args.size}, warm: median of {args.frames} "
          f"frames, fastest of {args.warm_runs} rounds; Glint's speed is Mitsuba's time over Glint's", flush=True)
    print("| scene | primitives | Glint primary ms | Mitsuba depth ms | Glint's speed "
          "| Glint shaded ms | Mitsuba direct ms | Glint's speed |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|")
    rows = []
    for family, n in points:
        path = os.path.join(work, f"{family}_s{n}.nff")
        if family == "sphere":
            sphere_nff(path, n)
        else:
            subprocess.run([args.glint, "spd", family, "--size", str(n), "-o", path], check=True)
        t, report = warm_pair(args, path, work, ["depth", "direct"])
        name = f"{family} s{n}"
        for frame, glint, mitsuba in [("primary", t["primary"], t["m_depth"]), ("shaded", t["shaded"], t["m_direct"])]:
            rows.append({"scene": name, "family": family, "size": n, "primitives": report["prims"], "frame": frame,
                         "glint_ms": round(glint * 1e3, 2), "mitsuba_ms": round(mitsuba * 1e3, 2),
                         "glint_speed": round(mitsuba / glint, 3)})
        print(f"| {name} | {report['prims']:,} | {t['primary'] * 1e3:.1f} | {t['m_depth'] * 1e3:.1f} "
              f"| {t['m_depth'] / t['primary']:.2f}× | {t['shaded'] * 1e3:.1f} | {t['m_direct'] * 1e3:.1f} "
              f"| {t['m_direct'] / t['shaded']:.2f}× |", flush=True)
        # Each point's file is large (the sphere's is 100 MB): keep one at a time.
        os.remove(path)
    with open(args.sweep_out + ".csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    plot(rows, args.sweep_out + ".svg", args.size)
    print(f"wrote {args.sweep_out}.csv and {args.sweep_out}.svg")


def plot(rows, path, size):
    """Time against primitives, log-log: a colour per renderer, a line style per
    frame kind, a marker per scene family."""
    import matplotlib
    matplotlib.use("svg")
    import matplotlib.pyplot as plt
    plt.rcParams["svg.fonttype"] = "none"  # text stays text: a small file
    colours = {"Glint": "tab:orange", "Mitsuba": "tab:blue"}
    styles = {"primary": "-", "shaded": "--"}
    markers = {"tetra": "o", "teapot": "s", "sphere": "D"}
    labels = {("Glint", "primary"): "Glint primary", ("Mitsuba", "primary"): "Mitsuba depth AOV",
              ("Glint", "shaded"): "Glint shaded, depth 1", ("Mitsuba", "shaded"): "Mitsuba direct"}
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for (renderer, frame), label in labels.items():
        key = "glint_ms" if renderer == "Glint" else "mitsuba_ms"
        labelled = False
        for family, marker in markers.items():
            points = sorted((r["primitives"], r[key]) for r in rows if r["frame"] == frame and r["family"] == family)
            if points:
                ax.plot(*zip(*points), linestyle=styles[frame], marker=marker, color=colours[renderer],
                        label=None if labelled else label)
                labelled = True
    for family, marker in markers.items():
        if any(r["family"] == family for r in rows):
            ax.plot([], [], linestyle="none", marker=marker, color="grey", label=family)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("primitives")
    ax.set_ylabel(f"ms per {size}×{size} frame")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize="small")
    fig.tight_layout()
    fig.savefig(path, metadata={"Date": None})


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("scenes", nargs="*", help="SPD names or NFF files for the primary and shaded parts "
                                                  "(default: the classic seven and the bunny)")
    parser.add_argument("--part", action="append", choices=["primary", "shaded", "sweep"],
                        help="a part to run, repeatable (default: all three)")
    parser.add_argument("--glint", default=os.path.join(REPO, "target", "release", "glint"))
    parser.add_argument("--size", type=int, default=512)
    parser.add_argument("--frames", type=int, default=5)
    parser.add_argument("--warm-runs", type=int, default=3,
                        help="rounds of warm processes (one of each renderer per round); the fastest of each counts")
    parser.add_argument("--no-cold", action="store_true", help="skip the cold-process measurements")
    parser.add_argument("--cold-runs", type=int, default=3,
                        help="rounds of cold processes (one of each kind per round); the fastest of each kind counts")
    parser.add_argument("--no-viewer", action="store_true", help="skip the viewer's cold first image (needs xvfb-run)")
    parser.add_argument("--tetra-sizes", default="6,7,8,9,10", help="the sweep's tetra sizes (4^N triangles)")
    parser.add_argument("--teapot-sizes", default="6,12,24,48", help="the sweep's teapot tessellations")
    parser.add_argument("--sphere-subdivisions", type=int, default=224,
                        help="the sweep's dense icosphere: 20·N² triangles (0: none)")
    parser.add_argument("--sweep-out", default="scale-sweep", help="the sweep's PREFIX.csv and PREFIX.svg")
    parser.add_argument("--worker", help=argparse.SUPPRESS)
    parser.add_argument("--mode", default="warm", help=argparse.SUPPRESS)
    parser.add_argument("--integrator", default="depth", help=argparse.SUPPRESS)
    parser.add_argument("--work", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.worker:
        return worker(args)

    parts = args.part or ["primary", "shaded", "sweep"]
    check_llvm()
    if "sweep" in parts:
        try:
            import matplotlib  # noqa: F401
        except ImportError:
            sys.exit("the sweep's plot needs matplotlib (pip install matplotlib)")
    work = tempfile.mkdtemp(prefix="glint-vs-mitsuba-")
    files = scene_files(args, work) if {"primary", "shaded"} & set(parts) else []
    if "primary" in parts:
        primary_part(args, files, work)
    if "shaded" in parts:
        shaded_part(args, files, work)
    if "sweep" in parts:
        sweep_part(args, work)


if __name__ == "__main__":
    main()
