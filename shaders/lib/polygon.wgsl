// Ray–polygon intersection, as the lecture shows: hit the polygon's plane, then
// decide inside/outside with the even-odd (crossing) rule, convex and concave
// alike. The crossing test runs in the ray's frame (ray_frame.wgsl), where the
// hit point is the origin and each edge's side is an exact function of its two
// sheared vertices, so polygons sharing an edge leave no gap and no overlap.
// import: plane ray_frame scene_arrays types

fn polygon_intersect(p: GpuPrim, ray: Ray, frame: RayFrame, t_min: f32, t_max: f32) -> f32 {
    let t = plane_intersect(p, ray, t_min, t_max);
    if t == MISS {
        return MISS;
    }
    // Count the edges crossing the +x half-line from the origin. A vertex on
    // the line counts as above it, and an edge through the origin as crossing
    // to its right: one consistent tie rule, as if the ray moved a hair up and
    // then left, so a ray on a shared edge is inside exactly one polygon.
    // Each vertex is moved into the frame at one place in the code, so that
    // every polygon holding it gets the same numbers.
    var inside = false;
    var prev: vec2<f32>;
    for (var i = 0u; i <= p.count; i++) {
        let cur = to_frame_xy(frame, point_at(p.first + select(i - 1u, p.count - 1u, i == 0u)).xyz);
        let rising = cur.y >= 0.0;
        if i > 0u && (prev.y >= 0.0) != rising {
            // The edge meets y = 0 at x = edge(prev, cur) / (cur.y − prev.y).
            let side = edge_sign(prev, cur);
            if side == 0.0 || (side > 0.0) == rising {
                inside = !inside;
            }
        }
        prev = cur;
    }
    return select(MISS, t, inside);
}
