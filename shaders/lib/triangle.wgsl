// Ray–triangle intersection, watertight (Woop, Benthin & Wald 2013; see
// ray_frame.wgsl) and two-sided. A ray through a shared edge or vertex gets a
// zero edge function from every triangle there and hits them all.
// import: ray_frame scene_arrays types

fn triangle_intersect(p: GpuPrim, frame: RayFrame, t_min: f32, t_max: f32) -> f32 {
    let a = to_frame(frame, p.a.xyz);
    let b = to_frame(frame, p.b.xyz);
    let c = to_frame(frame, p.c.xyz);
    let sides = vec3<f32>(edge_sign(b.xy, c.xy), edge_sign(c.xy, a.xy), edge_sign(a.xy, b.xy));
    if any(sides < vec3<f32>(0.0)) && any(sides > vec3<f32>(0.0)) {
        return MISS;
    }
    let u = edge(b, c);
    let v = edge(c, a);
    let w = edge(a, b);
    let det = u + v + w;
    if det == 0.0 {
        return MISS;
    }
    let t = (u * a.z + v * b.z + w * c.z) / det;
    return select(MISS, t, t > t_min && t < t_max);
}

fn triangle_geometric_normal(p: GpuPrim) -> vec3<f32> {
    return normalize(cross(p.b.xyz - p.a.xyz, p.c.xyz - p.a.xyz));
}

// The interpolated vertex normal at `point` for a smooth triangle, else the
// geometric normal. A kernel for a scene without smooth triangles
// (HAS_SMOOTH_TRIANGLES false) compiles without the interpolation.
fn triangle_shading_normal(p: GpuPrim, point: vec3<f32>) -> vec3<f32> {
    let n = cross(p.b.xyz - p.a.xyz, p.c.xyz - p.a.xyz);
    if !HAS_SMOOTH_TRIANGLES || p.count != 3u {
        return normalize(n);
    }
    // Barycentric weights from sub-triangle areas.
    let inv_area2 = 1.0 / dot(n, n);
    let w1 = dot(cross(p.c.xyz - p.b.xyz, point - p.b.xyz), n) * inv_area2;
    let w2 = dot(cross(p.a.xyz - p.c.xyz, point - p.c.xyz), n) * inv_area2;
    let w3 = 1.0 - w1 - w2;
    let s = w1 * point_at(p.first).xyz + w2 * point_at(p.first + 1u).xyz + w3 * point_at(p.first + 2u).xyz;
    return normalize(s);
}
