// The watertight triangle test of triangle.wgsl for the four rays of a packet.
// import: fast/ray_frame4 types

// `triangle_intersect` for the four rays of a packet, operation for operation,
// so each ray gets the same answer as alone; MISS for the rays that miss.
fn triangle_intersect4(p: GpuPrim, frame: RayFrame4, t_min: vec4<f32>, t_max: vec4<f32>) -> vec4<f32> {
    let a = to_frame4(frame, p.a.xyz);
    let b = to_frame4(frame, p.b.xyz);
    let c = to_frame4(frame, p.c.xyz);
    let s0 = edge_sign4(b, c);
    let s1 = edge_sign4(c, a);
    let s2 = edge_sign4(a, b);
    let zero = vec4<f32>(0.0);
    let outside = ((s0 < zero) | (s1 < zero) | (s2 < zero)) & ((s0 > zero) | (s1 > zero) | (s2 > zero));
    let u = edge4(b, c);
    let v = edge4(c, a);
    let w = edge4(a, b);
    let det = u + v + w;
    let t = (u * a.z + v * b.z + w * c.z) / det;
    return select(vec4<f32>(MISS), t, !outside & (det != zero) & (t > t_min) & (t < t_max));
}
