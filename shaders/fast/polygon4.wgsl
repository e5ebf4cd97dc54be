// The crossing test of polygon.wgsl for the four rays of a packet.
// import: fast/plane4 fast/ray_frame4 fast/rays4 scene_arrays types

// `polygon_intersect` for the four rays of a packet, operation for operation,
// so each ray gets the same answer as alone; MISS for the rays that miss. Each
// vertex is loaded once for the four rays.
fn polygon_intersect4(p: GpuPrim, rays: Rays4, frame: RayFrame4, t_min: vec4<f32>, t_max: vec4<f32>) -> vec4<f32> {
    let t = plane_intersect4(p, rays, t_min, t_max);
    let miss = vec4<f32>(MISS);
    if all(t == miss) {
        return miss;
    }
    let zero = vec4<f32>(0.0);
    var inside = vec4<bool>(false);
    var prev: Vec3x4;
    for (var i = 0u; i <= p.count; i++) {
        let cur = to_frame4(frame, point_at(p.first + select(i - 1u, p.count - 1u, i == 0u)).xyz);
        let rising = cur.y >= zero;
        if i > 0u {
            let side = edge_sign4(prev, cur);
            let crossing = (prev.y >= zero) != rising;
            inside = inside != (crossing & ((side == zero) | ((side > zero) == rising)));
        }
        prev = cur;
    }
    return select(miss, t, inside);
}
