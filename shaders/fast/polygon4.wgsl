// The crossing test of polygon.wgsl for the four rays of a packet.
// import: fast/plane4 fast/ray_frame4 fast/rays4 scene_arrays types

// `polygon_intersect` for the four rays of a packet, operation for operation,
// so each ray gets the same answer as alone; MISS for the rays that miss. Each
// vertex is loaded and moved into the four rays' frames once
// (docs/decisions/049-packet-polygon-vertices-once.md): the closing edge, from
// the last vertex back to the first, comes last, since the parity of the
// crossings does not depend on the order of the edges.
fn polygon_intersect4(p: GpuPrim, rays: Rays4, frame: RayFrame4, t_min: vec4<f32>, t_max: vec4<f32>) -> vec4<f32> {
    let t = plane_intersect4(p, rays, t_min, t_max);
    let miss = vec4<f32>(MISS);
    if all(t == miss) {
        return miss;
    }
    let first = to_frame4(frame, point_at(p.first).xyz);
    var inside = vec4<bool>(false);
    var prev = first;
    for (var i = 1u; i < p.count; i++) {
        let cur = to_frame4(frame, point_at(p.first + i).xyz);
        inside = inside != crosses4(prev, cur);
        prev = cur;
    }
    return select(miss, t, inside != crosses4(prev, first));
}

// Whether the edge a→b crosses the +x half-line, as polygon_intersect decides
// it for each ray. edge_sign(a, b) is 0 where its two products are equal and
// positive where the left one is greater, so they are compared here directly.
fn crosses4(a: Vec3x4, b: Vec3x4) -> vec4<bool> {
    let zero = vec4<f32>(0.0);
    let rising = b.y >= zero;
    let left = a.x * b.y;
    let right = a.y * b.x;
    return ((a.y >= zero) != rising) & ((left == right) | ((left > right) == rising));
}
