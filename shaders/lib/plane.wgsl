// Ray–plane intersection. The plane n·P = d, with a = (n, d), is met at
// t = (d − n·o)/(n·dir); a ray parallel to it (n·dir = 0) misses. Polygons
// test their own plane with it first. An infinite plane has no bounds to put
// in the BVH: traverse (bvh.wgsl) tests every ray against the scene's planes
// besides the tree.
// import: types

fn plane_intersect(p: GpuPrim, ray: Ray, t_min: f32, t_max: f32) -> f32 {
    let denom = dot(p.a.xyz, ray.dir);
    if denom == 0.0 {
        return MISS;
    }
    let t = (p.a.w - dot(p.a.xyz, ray.origin)) / denom;
    return select(MISS, t, t > t_min && t < t_max);
}

// `plane_intersect` for the four rays of a packet; MISS for the rays that miss.
fn plane_intersect4(p: GpuPrim, rays: Rays4, t_min: vec4<f32>, t_max: vec4<f32>) -> vec4<f32> {
    let denom = dot4(p.a.xyz, rays.dir);
    let t = (p.a.w - dot4(p.a.xyz, rays.origin)) / denom;
    return select(vec4<f32>(MISS), t, (denom != vec4<f32>(0.0)) & (t > t_min) & (t < t_max));
}

fn plane_normal(p: GpuPrim) -> vec3<f32> {
    return p.a.xyz;
}
