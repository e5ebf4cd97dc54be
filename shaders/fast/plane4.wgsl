// The plane test of plane.wgsl for the four rays of a packet.
// import: fast/rays4 types

// `plane_intersect` for the four rays of a packet; MISS for the rays that miss.
fn plane_intersect4(p: GpuPrim, rays: Rays4, t_min: vec4<f32>, t_max: vec4<f32>) -> vec4<f32> {
    let denom = dot4(p.a.xyz, rays.dir);
    let t = (p.a.w - dot4(p.a.xyz, rays.origin)) / denom;
    return select(vec4<f32>(MISS), t, (denom != vec4<f32>(0.0)) & (t > t_min) & (t < t_max));
}
