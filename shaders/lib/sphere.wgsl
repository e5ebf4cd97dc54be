// Ray–sphere intersection: |o + t·d − c|² = r², d of unit length.
// import: types

fn sphere_intersect(p: GpuPrim, ray: Ray, t_min: f32, t_max: f32) -> f32 {
    let center = p.a.xyz;
    let radius = p.a.w;
    let oc = ray.origin - center;
    let b = dot(oc, ray.dir);
    // r² − |oc − b·d|², the squared half-chord, rather than b² − (|oc|² − r²):
    // the same value without cancellation for distant spheres.
    let perp = oc - b * ray.dir;
    let disc = radius * radius - dot(perp, perp);
    if disc < 0.0 {
        return MISS;
    }
    let s = sqrt(disc);
    let t0 = -b - s;
    if t0 > t_min && t0 < t_max {
        return t0;
    }
    let t1 = -b + s;
    if t1 > t_min && t1 < t_max {
        return t1;
    }
    return MISS;
}

fn sphere_normal(p: GpuPrim, point: vec3<f32>) -> vec3<f32> {
    return normalize(point - p.a.xyz);
}
