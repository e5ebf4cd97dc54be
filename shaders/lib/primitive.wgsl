// Dispatch on primitive kind: intersection and surface normals.
// import: ray_frame scene_arrays types

// Takes the primitive's index, not its value: each case then loads only the
// fields its kind uses. Triangles and polygons are tested in the ray's frame, which
// the caller makes once per ray. The HAS_ flags of the kernel's specialisation
// (glint-encoding's specialization.rs) remove the tests of kinds the scene lacks.
// The function is generated from glint-encoding's primitive_kinds.rs.
// generated: intersect_prim

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
    // generated: surface_normals
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
