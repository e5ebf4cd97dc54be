"""NFF (Eric Haines' Neutral File Format) read into a Mitsuba 3 scene.

Glint and Mitsuba are measured on the same NFF file. Mitsuba has spheres and
cylinders of its own; cones (unequal radii) become triangle meshes of
CONE_SEGMENTS sides, polygons and polygon patches become triangles (ear
clipping, since SPD's gears are concave). Everything is gathered into one
triangle mesh, which Mitsuba hands to Embree whole.
"""

import math
import struct

CONE_SEGMENTS = 16


def read_nff(path):
    """The NFF's view, lights, and primitives as plain Python values."""
    tokens = open(path).read().split()
    pos = 0

    def take(n=1):
        nonlocal pos
        values = tokens[pos:pos + n]
        pos += n
        return values

    def numbers(n):
        return [float(x) for x in take(n)]

    scene = {"view": {}, "lights": [], "spheres": [], "cylinders": [], "triangles": [], "background": [0, 0, 0],
             "materials": [], "material": None}
    shape_material = []
    while pos < len(tokens):
        key = take()[0]
        if key == "v":
            view = scene["view"]
            for _ in range(6):
                name = take()[0]
                view[name] = numbers({"from": 3, "at": 3, "up": 3, "angle": 1, "hither": 1, "resolution": 2}[name])
        elif key == "b":
            scene["background"] = numbers(3)
        elif key == "l":
            rest = numbers(3)
            scene["lights"].append(rest)
            # An optional colour follows on the same line in NFF 2; SPD never writes it.
        elif key == "f":
            scene["materials"].append(numbers(8))
            scene["material"] = len(scene["materials"]) - 1
        elif key == "s":
            x, y, z, r = numbers(4)
            scene["spheres"].append(((x, y, z), r, scene["material"]))
        elif key == "c":
            base = numbers(4)
            apex = numbers(4)
            if abs(base[3] - apex[3]) <= 1e-9 * max(base[3], apex[3]):
                scene["cylinders"].append((base[:3], apex[:3], base[3], scene["material"]))
            else:
                scene["triangles"].extend(cone_triangles(base, apex))
                shape_material.append(scene["material"])
        elif key in ("p", "pp"):
            n = int(take()[0])
            verts = []
            for _ in range(n):
                verts.append(tuple(numbers(3)))
                if key == "pp":
                    numbers(3)  # the vertex normal: depth does not need it
            scene["triangles"].extend(triangulate(verts))
        else:
            raise ValueError(f"{path}: unknown NFF keyword {key!r} at token {pos}")
    return scene


def cone_triangles(base, apex):
    (bx, by, bz, br), (ax, ay, az, ar) = base, apex
    axis = (ax - bx, ay - by, az - bz)
    length = math.sqrt(sum(c * c for c in axis))
    w = tuple(c / length for c in axis)
    helper = (1.0, 0.0, 0.0) if abs(w[0]) < 0.9 else (0.0, 1.0, 0.0)
    u = cross(w, helper)
    u = scale(u, 1 / math.sqrt(dot(u, u)))
    v = cross(w, u)
    ring = []
    for i in range(CONE_SEGMENTS):
        a = 2 * math.pi * i / CONE_SEGMENTS
        d = add(scale(u, math.cos(a)), scale(v, math.sin(a)))
        ring.append((add((bx, by, bz), scale(d, br)), add((ax, ay, az), scale(d, ar))))
    tris = []
    for i in range(CONE_SEGMENTS):
        (b0, a0), (b1, a1) = ring[i], ring[(i + 1) % CONE_SEGMENTS]
        tris.append((b0, b1, a1))
        tris.append((b0, a1, a0))
    return tris


def triangulate(verts):
    """Ear clipping in the polygon's dominant plane: right for concave polygons."""
    if len(verts) == 3:
        return [tuple(verts)]
    n = newell(verts)
    drop = max(range(3), key=lambda i: abs(n[i]))
    keep = [i for i in range(3) if i != drop]
    pts = [(p[keep[0]], p[keep[1]]) for p in verts]
    area = sum(pts[i][0] * pts[(i + 1) % len(pts)][1] - pts[(i + 1) % len(pts)][0] * pts[i][1] for i in range(len(pts)))
    orient = 1.0 if area > 0 else -1.0
    index = list(range(len(verts)))
    tris = []
    guard = 0
    while len(index) > 3 and guard < 10 * len(verts) * len(verts):
        guard += 1
        for k in range(len(index)):
            i0, i1, i2 = index[k - 1], index[k], index[(k + 1) % len(index)]
            a, b, c = pts[i0], pts[i1], pts[i2]
            if orient * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])) <= 0:
                continue
            if any(inside(pts[j], a, b, c, orient) for j in index if j not in (i0, i1, i2)):
                continue
            tris.append((verts[i0], verts[i1], verts[i2]))
            del index[k]
            break
        else:
            break  # no ear: a degenerate remainder, fan it
    for k in range(1, len(index) - 1):
        tris.append((verts[index[0]], verts[index[k]], verts[index[k + 1]]))
    return tris


def inside(p, a, b, c, orient):
    def side(p, q, r):
        return orient * ((q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]))
    return side(a, b, p) >= 0 and side(b, c, p) >= 0 and side(c, a, p) >= 0


def newell(verts):
    n = [0.0, 0.0, 0.0]
    for i, a in enumerate(verts):
        b = verts[(i + 1) % len(verts)]
        n[0] += (a[1] - b[1]) * (a[2] + b[2])
        n[1] += (a[2] - b[2]) * (a[0] + b[0])
        n[2] += (a[0] - b[0]) * (a[1] + b[1])
    return n


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def add(a, b):
    return tuple(x + y for x, y in zip(a, b))


def scale(a, s):
    return tuple(x * s for x in a)


def write_ply(path, triangles):
    """A binary PLY of unshared vertices, which Mitsuba loads without parsing text."""
    with open(path, "wb") as f:
        f.write(("ply\nformat binary_little_endian 1.0\n"
                 f"element vertex {3 * len(triangles)}\nproperty float x\nproperty float y\nproperty float z\n"
                 f"element face {len(triangles)}\nproperty list uchar int vertex_indices\nend_header\n").encode())
        for tri in triangles:
            for p in tri:
                f.write(struct.pack("<3f", *p))
        for i in range(len(triangles)):
            f.write(struct.pack("<B3i", 3, 3 * i, 3 * i + 1, 3 * i + 2))


def fov_degrees(view):
    """Glint's default reading of the NFF angle: it spans the centres of the
    outermost pixels (SPD's convention), so the image edges are a little wider."""
    width = view["resolution"][0]
    half = math.radians(view["angle"][0]) / 2
    return math.degrees(2 * math.atan(math.tan(half) * width / (width - 1)))


def scene_dict(mi, nff, ply_path, width, height, integrator):
    """The Mitsuba scene of `nff` (its triangles written to `ply_path`)."""
    view = nff["view"]
    scene = {
        "type": "scene",
        "integrator": integrator,
        "sensor": {
            "type": "perspective",
            "fov": fov_degrees(view),
            "fov_axis": "x",
            "near_clip": max(view["hither"][0], 1e-3),
            "to_world": mi.ScalarTransform4f().look_at(origin=view["from"], target=view["at"], up=view["up"]),
            "film": {"type": "hdrfilm", "width": width, "height": height, "rfilter": {"type": "box"}},
            "sampler": {"type": "independent", "sample_count": 1},
        },
    }
    materials = nff["materials"]

    def bsdf(index):
        if index is None:
            return {"type": "diffuse"}
        r, g, b, kd, ks, _shine, t, ior = materials[index]
        if t > 0:
            return {"type": "dielectric", "int_ior": max(ior, 1.0001)}
        if ks > 0:
            return {"type": "plastic", "diffuse_reflectance": {"type": "rgb", "value": [r * kd, g * kd, b * kd]}}
        return {"type": "diffuse", "reflectance": {"type": "rgb", "value": [r * kd, g * kd, b * kd]}}

    for i, (center, radius, material) in enumerate(nff["spheres"]):
        scene[f"sphere{i}"] = {"type": "sphere", "center": center, "radius": radius, "bsdf": bsdf(material)}
    for i, (p0, p1, radius, material) in enumerate(nff["cylinders"]):
        scene[f"cylinder{i}"] = {"type": "cylinder", "p0": p0, "p1": p1, "radius": radius, "bsdf": bsdf(material)}
    if nff["triangles"]:
        write_ply(ply_path, nff["triangles"])
        scene["mesh"] = {"type": "ply", "filename": ply_path, "face_normals": True,
                         "bsdf": bsdf(nff["material"] if materials else None)}
    for i, light in enumerate(nff["lights"]):
        scene[f"light{i}"] = {"type": "point", "position": light, "intensity": {"type": "rgb", "value": [1, 1, 1]}}
    return scene
