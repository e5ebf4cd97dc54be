// Ray–polygon intersection, as the lecture shows: hit the polygon's plane, then
// decide inside/outside with the even-odd (crossing) rule in 2D, projecting onto
// the coordinate plane where the polygon's normal is largest. Works for convex
// and concave polygons alike.

fn polygon_intersect(p: GpuPrim, ray: Ray, t_min: f32, t_max: f32) -> f32 {
    let n = p.a.xyz;
    let denom = dot(n, ray.dir);
    if denom == 0.0 {
        return MISS;
    }
    let t = (p.a.w - dot(n, ray.origin)) / denom;
    if !(t > t_min && t < t_max) {
        return MISS;
    }
    let hit = ray.origin + t * ray.dir;
    // Drop the dominant axis of the normal.
    let an = abs(n);
    var ax = 1u;
    var ay = 2u;
    if an.y >= an.x && an.y >= an.z {
        ax = 0u;
        ay = 2u;
    } else if an.z >= an.x && an.z >= an.y {
        ax = 0u;
        ay = 1u;
    }
    let q = vec2<f32>(hit[ax], hit[ay]);
    var inside = false;
    var prev = points[p.first + p.count - 1u].xyz;
    for (var i = 0u; i < p.count; i++) {
        let cur = points[p.first + i].xyz;
        let a = vec2<f32>(prev[ax], prev[ay]) - q;
        let b = vec2<f32>(cur[ax], cur[ay]) - q;
        // Does edge a→b cross the +x half-line from q?
        if (a.y > 0.0) != (b.y > 0.0) {
            let x = a.x + (b.x - a.x) * (0.0 - a.y) / (b.y - a.y);
            if x > 0.0 {
                inside = !inside;
            }
        }
        prev = cur;
    }
    return select(MISS, t, inside);
}

fn polygon_normal(p: GpuPrim) -> vec3<f32> {
    return p.a.xyz;
}
