// Dispatch on primitive kind: intersection and surface normals.
// import: cone plane polygon ray_frame scene_arrays sphere triangle types

// Takes the primitive's index, not its value: each case then loads only the
// fields its kind uses (a load per SIMD lane is what a software rasteriser
// pays most for). Triangles and polygons are tested in the ray's frame, which
// the caller makes once per ray. The HAS_ flags of the kernel's specialisation
// (glint-scene's specialization.rs) remove the tests of kinds the scene lacks.
fn intersect_prim(i: u32, ray: Ray, frame: RayFrame, t_min: f32, t_max: f32) -> f32 {
    let kind = prim_kind(prim_at(i));
    if HAS_SPHERES && kind == PRIM_SPHERE {
        return sphere_intersect(prim_at(i), ray, t_min, t_max);
    }
    if HAS_TRIANGLES && kind == PRIM_TRIANGLE {
        return triangle_intersect(prim_at(i), frame, t_min, t_max);
    }
    if HAS_POLYGONS && kind == PRIM_POLYGON {
        return polygon_intersect(prim_at(i), ray, frame, t_min, t_max);
    }
    if HAS_CONES && kind == PRIM_CONE {
        return cone_intersect(prim_at(i), ray, t_min, t_max);
    }
    if HAS_PLANES && kind == PRIM_PLANE {
        return plane_intersect(prim_at(i), ray, t_min, t_max);
    }
    return MISS;
}

struct Surface {
    point: vec3<f32>,
    // Unit normals, both turned towards the incoming ray: surfaces are two-sided.
    geometric: vec3<f32>,
    shading: vec3<f32>,
    // The ray arrived from the back of the surface (from inside a closed object).
    backface: bool,
}

fn surface_at(p: GpuPrim, ray: Ray, t: f32) -> Surface {
    let point = ray.origin + t * ray.dir;
    var geometric: vec3<f32>;
    var shading: vec3<f32>;
    let kind = prim_kind(p);
    if HAS_SPHERES && kind == PRIM_SPHERE {
        geometric = sphere_normal(p, point);
        shading = geometric;
    } else if HAS_TRIANGLES && kind == PRIM_TRIANGLE {
        geometric = triangle_geometric_normal(p);
        shading = triangle_shading_normal(p, point);
    } else if (HAS_POLYGONS && kind == PRIM_POLYGON) || (HAS_PLANES && kind == PRIM_PLANE) {
        geometric = plane_normal(p);
        shading = geometric;
    } else if HAS_CONES {
        geometric = cone_normal(p, point);
        shading = geometric;
    }
    let backface = dot(geometric, ray.dir) > 0.0;
    let sign = select(1.0, -1.0, backface);
    geometric *= sign;
    shading *= sign;
    // Interpolated normals can still face away; keep them on the viewer's side.
    if dot(shading, ray.dir) > 0.0 {
        shading = geometric;
    }
    return Surface(point, geometric, shading, backface);
}

// Offset for rays leaving a surface, relative to the magnitude of the
// coordinates so large scenes do not self-intersect.
fn ray_epsilon(point: vec3<f32>) -> f32 {
    let m = max(max(abs(point.x), abs(point.y)), abs(point.z));
    return 1e-4 * max(1.0, m);
}
