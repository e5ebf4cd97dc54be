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

// The cell size of biased exponent byte `e` (bits 0-7), 2^(e - 127).
fn cell_size(e: vec3<u32>) -> vec3<f32> {
    return bitcast<vec3<f32>>((e & vec3<u32>(0xffu)) << vec3<u32>(23u));
}

// Entry distances into both children of `node`; MISS for a missing child.
fn child_entries(node: GpuNode, origin: vec3<f32>, inv_dir: vec3<f32>, t_max: f32) -> vec2<f32> {
    let cell = cell_size(vec3<u32>(node.exponents, node.exponents >> 8u, node.exponents >> 16u));
    let q = node.quantized;
    let byte = vec3<u32>(0xffu);
    let left_lo = node.origin + vec3<f32>(q & byte) * cell;
    let left_hi = node.origin + vec3<f32>((q >> vec3<u32>(8u)) & byte) * cell;
    let right_lo = node.origin + vec3<f32>((q >> vec3<u32>(16u)) & byte) * cell;
    let right_hi = node.origin + vec3<f32>(q >> vec3<u32>(24u)) * cell;
    let t_left = box_entry(left_lo, left_hi, origin, inv_dir, t_max);
    let t_right = box_entry(right_lo, right_hi, origin, inv_dir, t_max);
    return vec2<f32>(select(t_left, MISS, node.left == NO_NODE), select(t_right, MISS, node.right == NO_NODE));
}

// Closest hit in (t_min, t_max) when `any_hit` is false. With `any_hit`, a shadow
// query: stops at the first opaque occluder (transmittance 0); with `tinted`,
// transmissive occluders let light through, multiplying the transmittance by
// their k_t, and only opaque ones stop it.
//
// The loop descends through interior nodes until it reaches a leaf, then tests
// the leaf's primitives ("while-while", Aila & Laine 2009): the lanes of a SIMD
// group that walk in step then run one kind of work at a time instead of paying
// for both in every iteration.
fn traverse(ray: Ray, t_min: f32, t_max_in: f32, any_hit: bool, tinted: bool) -> Hit {
    var hit = Hit(MISS, 0u, vec3<f32>(1.0), 0u);
    var t_max = t_max_in;
    let inv_dir = 1.0 / ray.dir;
    // Pending far children with their entry distances, so a pop needs no
    // second box test: it is skipped once a closer hit has been found.
    var stack_node: array<u32, BVH_STACK>;
    var stack_t: array<f32, BVH_STACK>;
    var top = 0u;
    var index = 0u;
    while index != NO_NODE {
        while (index & LEAF) == 0u {
            hit.nodes++;
            let node = nodes[index];
            let t = child_entries(node, ray.origin, inv_dir, t_max);
            let near_first = t.x <= t.y;
            if min(t.x, t.y) == MISS {
                index = pop(&stack_node, &stack_t, &top, t_max);
            } else {
                if max(t.x, t.y) != MISS {
                    stack_node[top] = select(node.left, node.right, near_first);
                    stack_t[top] = max(t.x, t.y);
                    top++;
                }
                index = select(node.right, node.left, near_first);
            }
        }
        if index == NO_NODE {
            break;
        }
        hit.nodes++;
        let first = index & 0x0fffffffu;
        let end = first + ((index >> 28u) & 7u) + 1u;
        for (var i = first; i < end; i++) {
            if !any_hit {
                // Equal distances (coincident surfaces) go to the lower object
                // id, so the winner does not depend on the order of visits.
                let t = intersect_prim(i, ray, t_min, next_up(t_max));
                if t != MISS && (t < t_max || (t == t_max && prims[i].object < prims[hit.prim].object)) {
                    t_max = t;
                    hit.t = t;
                    hit.prim = i;
                }
                continue;
            }
            let t = intersect_prim(i, ray, t_min, t_max);
            if t == MISS {
                continue;
            }
            let m = materials[prim_material(prims[i])];
            if tinted && any(m.transmit > vec3<f32>(0.0)) {
                hit.transmittance *= m.transmit;
            } else {
                hit.t = t;
                hit.prim = i;
                hit.transmittance = vec3<f32>(0.0);
                return hit;
            }
        }
        index = pop(&stack_node, &stack_t, &top, t_max);
    }
    return hit;
}

// The most recently pushed node still closer than `t_max`, or NO_NODE.
fn pop(
    stack_node: ptr<function, array<u32, BVH_STACK>>,
    stack_t: ptr<function, array<f32, BVH_STACK>>,
    top: ptr<function, u32>,
    t_max: f32,
) -> u32 {
    while *top > 0u {
        *top -= 1u;
        if (*stack_t)[*top] <= t_max {
            return (*stack_node)[*top];
        }
    }
    return NO_NODE;
}
