// BVH traversal with a private stack, nearest child first. The host builder
// guarantees the tree depth fits BVH_STACK. How a node stores its children's
// boxes is bvh_nodes.wgsl's business: here they are corners to slab-test.
// import: bindings bvh_nodes bvh_records primitive ray_frame scene_arrays types

// A ray that missed both children pops in the leaf phase, so the descent loop
// only descends (docs/decisions/033-descent-without-early-return.md).
const NEEDS_POP: u32 = 0xfffffffeu;

// Pending far children with their entry distances, so a pop needs no second
// box test: it is skipped once a closer hit has been found. At module scope, so
// they are zeroed once per invocation, not once per traversal (a kernel traces
// several rays, e.g. shadow rays, per pixel).
var<private> stack_node: array<u32, BVH_STACK>;
var<private> stack_t: array<f32, BVH_STACK>;

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

// Entry distance into a box from the distances to its near and far plane on
// each axis, or MISS. A NaN distance (a ray in a box's face plane, 0·∞) drops
// out of max and min, so such a ray counts as inside: the test stays conservative.
fn slab_entry(t_near: vec3<f32>, t_far: vec3<f32>, t_max: f32) -> f32 {
    let near = max(max(t_near.x, t_near.y), t_near.z);
    let far = min(min(t_far.x, t_far.y), t_far.z);
    return select(MISS, max(near, 0.0), near <= far && far >= 0.0 && near <= t_max);
}

// Closest hit in (t_min, t_max) when `any_hit` is false. With `any_hit`, a shadow
// query: stops at the first opaque occluder (transmittance 0); with `tinted`,
// transmissive occluders let light through, multiplying the transmittance by
// their k_t, and only opaque ones stop it.
//
// The loop descends through interior nodes until it reaches a leaf (or misses
// both children), then tests the leaf's primitives and pops ("while-while",
// Aila & Laine 2009): rays walked side by side then do one kind of work at a
// time instead of both in every iteration.
fn traverse(ray: Ray, t_min: f32, t_max_in: f32, any_hit: bool, tinted: bool) -> Hit {
    var hit = Hit(MISS, 0u, vec3<f32>(1.0), 0u);
    var t_max = t_max_in;
    let inv_dir = 1.0 / ray.dir;
    let frame = ray_frame(ray);
    // Per axis, the corner byte of a quantised box the ray meets first (0 low,
    // 8 high) and last: choosing the planes by the direction's sign saves the
    // per-axis min and max of the textbook slab test.
    let near_byte = select(vec3<u32>(0u), vec3<u32>(8u), inv_dir < vec3<f32>(0.0));
    // Infinite planes have no bounds to put in the tree: every ray tests them,
    // first, so that a floor it hits already shortens the walk.
    if HAS_PLANES && test_prims(uniforms.plane_first, uniforms.plane_count, ray, frame, t_min, &t_max, &hit, any_hit, tinted) {
        return hit;
    }
    var top = 0u;
    var index = uniforms.bvh_root;
    // The root's grid (unused when the root is a leaf).
    var grid = stored_grid(0u);
    while index != NO_NODE {
        // The root, or a node returned to, may be a leaf already.
        if (index & LEAF) == 0u {
            loop {
                hit.nodes++;
                let node = node_at(index);
                let c = child_corners(grid, node.quantized, near_byte);
                let t_left = slab_entry((c.left_near - ray.origin) * inv_dir, (c.left_far - ray.origin) * inv_dir, t_max);
                let t_right = slab_entry((c.right_near - ray.origin) * inv_dir, (c.right_far - ray.origin) * inv_dir, t_max);
                index = descend(node, t_left, t_right, &top);
                // Unused when the walk pops (pop restores the grid it needs).
                grid = entered_grid(c, t_left <= t_right, near_byte);
                if (index & LEAF) != 0u {
                    break;
                }
            }
        }
        if index != NEEDS_POP {
            hit.nodes++;
            let leaf = node_at(index & ~LEAF).quantized;
            if test_prims(leaf.x, leaf.y, ray, frame, t_min, &t_max, &hit, any_hit, tinted) {
                return hit;
            }
        }
        index = pop(&top, t_max, &grid);
    }
    return hit;
}

// The walk's step down from an interior node whose children it enters at
// distances t_left and t_right (MISS: not at all): the nearer child entered,
// the farther pushed with its distance when both are, NEEDS_POP when neither.
fn descend(node: GpuNode, t_left: f32, t_right: f32, top: ptr<function, u32>) -> u32 {
    let first = node.children & ~(LEAF | RIGHT_LEAF);
    let left = first | (node.children & LEAF);
    let right = (first + 1u) | ((node.children << 1u) & LEAF);
    let near_first = t_left <= t_right;
    if max(t_left, t_right) != MISS {
        stack_node[*top] = select(left, right, near_first);
        stack_t[*top] = max(t_left, t_right);
        *top += 1u;
    }
    return select(select(right, left, near_first), NEEDS_POP, min(t_left, t_right) == MISS);
}

// Tests primitives first .. first + count (a leaf's, or the infinite planes)
// as `traverse` asks, narrowing `t_max` to the closest hit so far; true when
// an any-hit query has its answer.
fn test_prims(
    first: u32,
    count: u32,
    ray: Ray,
    frame: RayFrame,
    t_min: f32,
    t_max: ptr<function, f32>,
    hit: ptr<function, Hit>,
    any_hit: bool,
    tinted: bool,
) -> bool {
    for (var i = first; i < first + count; i++) {
        // One intersection call for both queries: the walk holds one copy
        // of the tests (docs/decisions/024-one-walk-in-the-trace-kernel.md).
        let t = intersect_prim(i, ray, frame, t_min, select(*t_max, next_up(*t_max), !any_hit));
        if t == MISS {
            continue;
        }
        if !any_hit {
            // Equal distances (coincident surfaces) go to the lower object
            // id, so the winner does not depend on the order of visits.
            if t < *t_max || (t == *t_max && (*hit).t != MISS && prim_at(i).object < prim_at((*hit).prim).object) {
                *t_max = t;
                (*hit).t = t;
                (*hit).prim = i;
            }
            continue;
        }
        let m = materials[prim_material(prim_at(i))];
        if tinted && any(m.transmit > vec3<f32>(0.0)) {
            (*hit).transmittance *= m.transmit;
        } else {
            (*hit).t = t;
            (*hit).prim = i;
            (*hit).transmittance = vec3<f32>(0.0);
            return true;
        }
    }
    return false;
}

// The most recently pushed node still closer than `t_max`, or NO_NODE; the
// grid of an interior node returned to.
fn pop(top: ptr<function, u32>, t_max: f32, grid: ptr<function, Grid>) -> u32 {
    // An empty stack ends the walk before the loop.
    if *top == 0u {
        return NO_NODE;
    }
    while *top > 0u {
        *top -= 1u;
        if stack_t[*top] <= t_max {
            let index = stack_node[*top];
            if (index & LEAF) == 0u {
                *grid = stored_grid(index);
            }
            return index;
        }
    }
    return NO_NODE;
}
