// Ray packets: the eye rays of a 2×2 block of pixels walk the BVH together
// (Wald, Slusallek, Benthin & Wagner, "Interactive Rendering with Coherent
// Ray Tracing", 2001). A software rasteriser pays for every load a SIMD lane
// makes and every step of its loops; four neighbouring eye rays visit nearly
// the same nodes, so one lane tracing all four loads each node and primitive
// once and steps once for them, while the box and triangle tests run on vec4s
// of the four rays. The packet visits every node one of its rays enters, and
// each ray gets exactly the hit `traverse` gives it alone: the same tests in
// the same arithmetic (triangle_intersect4), the same tie-break.
// import: bindings bvh primitive ray_frame triangle types

struct Packet {
    rays: Rays4,
    inv_dir: Vec3x4,
    frame: RayFrame4,
}

struct PacketHit {
    t: vec4<f32>,
    prim: vec4<u32>,
    // The hit primitives' objects, for the tie-break.
    object: vec4<u32>,
}

fn packet(rays: Rays4) -> Packet {
    let one = vec4<f32>(1.0);
    return Packet(rays, Vec3x4(one / rays.dir.x, one / rays.dir.y, one / rays.dir.z), ray_frame4(rays));
}

// The distances of four rays to a box's near and far plane on one axis.
struct Span4 {
    near: vec4<f32>,
    far: vec4<f32>,
}

fn axis_span4(lo: f32, hi: f32, origin: vec4<f32>, inv_dir: vec4<f32>) -> Span4 {
    let negative = inv_dir < vec4<f32>(0.0);
    return Span4((select(vec4<f32>(lo), vec4<f32>(hi), negative) - origin) * inv_dir, (select(vec4<f32>(hi), vec4<f32>(lo), negative) - origin) * inv_dir);
}

// Each ray's entry into the box [lo, hi] as `slab_entry` gives it, or MISS.
fn packet_entry(p: Packet, lo: vec3<f32>, hi: vec3<f32>, t_max: vec4<f32>) -> vec4<f32> {
    let x = axis_span4(lo.x, hi.x, p.rays.origin.x, p.inv_dir.x);
    let y = axis_span4(lo.y, hi.y, p.rays.origin.y, p.inv_dir.y);
    let z = axis_span4(lo.z, hi.z, p.rays.origin.z, p.inv_dir.z);
    let near = max(max(x.near, y.near), z.near);
    let far = min(min(x.far, y.far), z.far);
    let zero = vec4<f32>(0.0);
    return select(vec4<f32>(MISS), max(near, zero), (near <= far) & (far >= zero) & (near <= t_max));
}

// `test_prims` for a packet's closest hits: primitive i against its four rays.
fn packet_test(i: u32, p: Packet, hit: PacketHit) -> PacketHit {
    let bound = bitcast<vec4<f32>>(bitcast<vec4<u32>>(hit.t) + vec4<u32>(1u));
    var t = vec4<f32>(MISS);
    let only_triangles = !(HAS_SPHERES || HAS_POLYGONS || HAS_CONES || HAS_PLANES);
    if only_triangles || (HAS_TRIANGLES && prim_kind(prims[i]) == PRIM_TRIANGLE) {
        t = triangle_intersect4(prims[i], p.frame, vec4<f32>(0.0), bound);
    } else {
        // Other kinds one ray at a time (scenes of them trace fast alone), in
        // a loop whose count the compiler does not know, so that it keeps one
        // copy of the tests instead of four.
        var left = 0xfu;
        while left != 0u {
            let k = firstTrailingBit(left);
            left &= left - 1u;
            t[k] = intersect_prim(i, ray_of(p.rays, k), frame_of(p.frame, k), 0.0, bound[k]);
        }
    }
    // t < hit.t fails for a miss (MISS is the largest distance).
    let closer = t < hit.t;
    let tie = (t == hit.t) & (t != vec4<f32>(MISS));
    if !any(closer | tie) {
        return hit;
    }
    let object = vec4<u32>(prims[i].object);
    let take = closer | (tie & (object < hit.object));
    return PacketHit(select(hit.t, t, take), select(hit.prim, vec4<u32>(i), take), select(hit.object, object, take));
}

fn min4(v: vec4<f32>) -> f32 {
    return min(min(v.x, v.y), min(v.z, v.w));
}

fn max4(v: vec4<f32>) -> f32 {
    return max(max(v.x, v.y), max(v.z, v.w));
}

// `traverse` for the closest hits of a packet's rays in (0, MISS): the same
// while-while walk, each child entered when one of the rays enters it, the
// child entered first that one of them enters first.
fn traverse_packet(p: Packet) -> PacketHit {
    var hit = PacketHit(vec4<f32>(MISS), vec4<u32>(0u), vec4<u32>(0u));
    if HAS_PLANES {
        for (var i = uniforms.plane_first; i < uniforms.plane_first + uniforms.plane_count; i++) {
            hit = packet_test(i, p, hit);
        }
    }
    var top = 0u;
    var index = uniforms.bvh_root;
    var grid = stored_grid(0u);
    while index != NO_NODE {
        if (index & LEAF) == 0u {
            loop {
                let node = nodes[index];
                let left_lo = decode(grid, node.quantized, vec3<u32>(0u));
                let left_hi = decode(grid, node.quantized, vec3<u32>(8u));
                let right_lo = decode(grid, node.quantized, vec3<u32>(16u));
                let right_hi = decode(grid, node.quantized, vec3<u32>(24u));
                let t_left = min4(packet_entry(p, left_lo, left_hi, hit.t));
                let t_right = min4(packet_entry(p, right_lo, right_hi, hit.t));
                index = descend(node, t_left, t_right, &top);
                if index != NEEDS_POP {
                    let near_first = t_left <= t_right;
                    grid = derived_grid(select(right_lo, left_lo, near_first), select(right_hi, left_hi, near_first));
                }
                if (index & LEAF) != 0u {
                    break;
                }
            }
        }
        if index != NEEDS_POP {
            let leaf = nodes[index & ~LEAF].quantized;
            for (var i = leaf.x; i < leaf.x + leaf.y; i++) {
                hit = packet_test(i, p, hit);
            }
        }
        index = pop(&top, max4(hit.t), &grid);
    }
    return hit;
}
