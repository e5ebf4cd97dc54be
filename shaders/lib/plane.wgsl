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

fn plane_normal(p: GpuPrim) -> vec3<f32> {
    return p.a.xyz;
}
