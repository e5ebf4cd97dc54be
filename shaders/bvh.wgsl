// BVH traversal with a private stack, nearest child first. The host builder
// guarantees the tree depth fits BVH_STACK.

const BVH_STACK: u32 = 32u;

struct Hit {
    t: f32,
    prim: u32,
    // For any-hit queries: light let through by transmissive occluders.
    transmittance: vec3<f32>,
    // Nodes visited, for the heat-map view.
    nodes: u32,
}

// The next float above a positive finite `t`.
fn next_up(t: f32) -> f32 {
    return bitcast<f32>(bitcast<u32>(t) + 1u);
}

// Entry distance of the ray into the box, or MISS.
fn box_entry(lo: vec3<f32>, hi: vec3<f32>, origin: vec3<f32>, inv_dir: vec3<f32>, t_max: f32) -> f32 {
    let t0 = (lo - origin) * inv_dir;
    let t1 = (hi - origin) * inv_dir;
    let near = max(max(min(t0.x, t1.x), min(t0.y, t1.y)), min(t0.z, t1.z));
    let far = min(min(max(t0.x, t1.x), max(t0.y, t1.y)), max(t0.z, t1.z));
    return select(MISS, max(near, 0.0), near <= far && far >= 0.0 && near <= t_max);
}

// Closest hit in (t_min, t_max) when `any_hit` is false. With `any_hit`, a shadow
// query: stops at the first opaque occluder (transmittance 0); with `tinted`,
// transmissive occluders let light through, multiplying the transmittance by
// their k_t, and only opaque ones stop it.
fn traverse(ray: Ray, t_min: f32, t_max_in: f32, any_hit: bool, tinted: bool) -> Hit {
    var hit = Hit(MISS, 0u, vec3<f32>(1.0), 1u);
    var t_max = t_max_in;
    let inv_dir = 1.0 / ray.dir;
    // Pending far children with their entry distances, so a pop needs no
    // second box test: it is skipped once a closer hit has been found.
    var stack_node: array<u32, BVH_STACK>;
    var stack_t: array<f32, BVH_STACK>;
    var top = 0u;
    var index = 0u;
    if box_entry(nodes[0].min, nodes[0].max, ray.origin, inv_dir, t_max) == MISS {
        return hit;
    }
    loop {
        let node = nodes[index];
        hit.nodes++;
        if node.count > 0u {
            for (var i = node.left_or_first; i < node.left_or_first + node.count; i++) {
                let p = prims[i];
                if !any_hit {
                    // Equal distances (coincident surfaces) go to the lower object
                    // id, so the winner does not depend on the order of visits.
                    let t = intersect_prim(p, ray, t_min, next_up(t_max));
                    if t != MISS && (t < t_max || (t == t_max && p.object < prims[hit.prim].object)) {
                        t_max = t;
                        hit.t = t;
                        hit.prim = i;
                    }
                    continue;
                }
                let t = intersect_prim(p, ray, t_min, t_max);
                if t == MISS {
                    continue;
                }
                let m = materials[prim_material(p)];
                if tinted && any(m.transmit > vec3<f32>(0.0)) {
                    hit.transmittance *= m.transmit;
                } else {
                    hit.t = t;
                    hit.prim = i;
                    hit.transmittance = vec3<f32>(0.0);
                    return hit;
                }
            }
        } else {
            let left = node.left_or_first;
            let right = left + 1u;
            let t_left = box_entry(nodes[left].min, nodes[left].max, ray.origin, inv_dir, t_max);
            let t_right = box_entry(nodes[right].min, nodes[right].max, ray.origin, inv_dir, t_max);
            let near_first = t_left <= t_right;
            let near = select(right, left, near_first);
            let far = select(left, right, near_first);
            let t_near = min(t_left, t_right);
            let t_far = max(t_left, t_right);
            if t_near != MISS {
                if t_far != MISS {
                    stack_node[top] = far;
                    stack_t[top] = t_far;
                    top++;
                }
                index = near;
                continue;
            }
        }
        // Pop the next node still closer than the current hit.
        var found = false;
        while top > 0u {
            top--;
            if stack_t[top] <= t_max {
                index = stack_node[top];
                found = true;
                break;
            }
        }
        if !found {
            break;
        }
    }
    return hit;
}
