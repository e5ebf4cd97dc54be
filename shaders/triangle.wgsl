// Ray–triangle intersection (Möller–Trumbore), two-sided.

fn triangle_intersect(p: GpuPrim, ray: Ray, t_min: f32, t_max: f32) -> f32 {
    let e1 = p.b.xyz - p.a.xyz;
    let e2 = p.c.xyz - p.a.xyz;
    let pv = cross(ray.dir, e2);
    let det = dot(e1, pv);
    if det == 0.0 {
        return MISS;
    }
    let inv = 1.0 / det;
    let tv = ray.origin - p.a.xyz;
    let u = dot(tv, pv) * inv;
    if u < 0.0 || u > 1.0 {
        return MISS;
    }
    let qv = cross(tv, e1);
    let v = dot(ray.dir, qv) * inv;
    if v < 0.0 || u + v > 1.0 {
        return MISS;
    }
    let t = dot(e2, qv) * inv;
    return select(MISS, t, t > t_min && t < t_max);
}

fn triangle_geometric_normal(p: GpuPrim) -> vec3<f32> {
    return normalize(cross(p.b.xyz - p.a.xyz, p.c.xyz - p.a.xyz));
}

// The interpolated vertex normal at `point` for a smooth triangle, else the
// geometric normal.
fn triangle_shading_normal(p: GpuPrim, point: vec3<f32>) -> vec3<f32> {
    let n = cross(p.b.xyz - p.a.xyz, p.c.xyz - p.a.xyz);
    if p.count != 3u {
        return normalize(n);
    }
    // Barycentric weights from sub-triangle areas.
    let inv_area2 = 1.0 / dot(n, n);
    let w1 = dot(cross(p.c.xyz - p.b.xyz, point - p.b.xyz), n) * inv_area2;
    let w2 = dot(cross(p.a.xyz - p.c.xyz, point - p.c.xyz), n) * inv_area2;
    let w3 = 1.0 - w1 - w2;
    let s = w1 * points[p.first].xyz + w2 * points[p.first + 1u].xyz + w3 * points[p.first + 2u].xyz;
    return normalize(s);
}
