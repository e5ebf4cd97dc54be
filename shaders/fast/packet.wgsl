// Ray packets: the eye rays of a 2×2 block of pixels walk the BVH together
// (Wald, Slusallek, Benthin & Wagner, "Interactive Rendering with Coherent
// Ray Tracing", 2001). A software rasteriser pays for every load a SIMD lane
// makes and every step of its loops; four neighbouring eye rays visit nearly
// the same nodes, so one lane tracing all four loads each node and primitive
// once and steps once for them; one interval test stands for the four rays'
// box tests, and the triangle, polygon and plane tests run on vec4s of the four
// rays. The packet visits every node one of its rays enters, and each ray gets
// exactly the hit `traverse` gives it alone: the same tests in the same
// arithmetic (triangle_intersect4 and the like), the same tie-break.
// import: bindings bvh bvh_nodes bvh_records fast/plane4 fast/polygon4 fast/ray_frame4 fast/rays4 fast/triangle4 scene_arrays types

struct Packet {
    rays: Rays4,
    frame: RayFrame4,
    bounds: PacketBounds,
}

struct PacketHit {
    t: vec4<f32>,
    prim: vec4<u32>,
    // The hit primitives' objects, for the tie-break.
    object: vec4<u32>,
}

// What one box test for all four rays needs (interval arithmetic: Boulos,
// Wald et al., "Packet-based Whitted and distribution ray tracing", 2007): per
// axis the range of the rays' inverse directions and the origins that bound
// their distances to a box's near and far planes. One scalar test then stands
// for four slab tests.
struct PacketBounds {
    // The near plane's corner byte (0 low, 8 high), as in `traverse`.
    near_byte: vec3<u32>,
    near_origin: vec3<f32>,
    far_origin: vec3<f32>,
    inv_lo: vec3<f32>,
    inv_hi: vec3<f32>,
    // Axes on which no ray runs parallel to the planes and all four go the
    // same way; the others do not cull.
    bounded: vec3<bool>,
}

fn packet(rays: Rays4) -> Packet {
    let one = vec4<f32>(1.0);
    let inv = Vec3x4(one / rays.dir.x, one / rays.dir.y, one / rays.dir.z);
    let inv_lo = vec3<f32>(min4(inv.x), min4(inv.y), min4(inv.z));
    let inv_hi = vec3<f32>(max4(inv.x), max4(inv.y), max4(inv.z));
    let o = rays.origin;
    let o_lo = vec3<f32>(min4(o.x), min4(o.y), min4(o.z));
    let o_hi = vec3<f32>(max4(o.x), max4(o.y), max4(o.z));
    let negative = inv_hi < vec3<f32>(0.0);
    let bounded = ((inv_lo > vec3<f32>(0.0)) & (inv_hi <= vec3<f32>(MISS))) | (negative & (inv_lo >= vec3<f32>(-MISS)));
    let near_byte = select(vec3<u32>(0u), vec3<u32>(8u), negative);
    let bounds = PacketBounds(near_byte, select(o_hi, o_lo, negative), select(o_lo, o_hi, negative), inv_lo, inv_hi, bounded);
    return Packet(rays, ray_frame4(rays), bounds);
}

// A lower bound of the four rays' entries into the box whose near and far
// corners are `near` and `far` (each ray's as `slab_entry` gives it, t_max the
// largest of theirs), or MISS when none of them enters it. Rounding is monotonic,
// so a product of the extreme operands bounds each ray's own product. Nothing
// here is NaN: the products on an axis that bounds are finite, the others are
// replaced by ±MISS.
fn packet_entry(b: PacketBounds, near: vec3<f32>, far: vec3<f32>, t_max: f32) -> f32 {
    let d_near = near - b.near_origin;
    let d_far = far - b.far_origin;
    let t_near = select(vec3<f32>(-MISS), lesser3(d_near * b.inv_lo, d_near * b.inv_hi), b.bounded);
    let t_far = select(vec3<f32>(MISS), greater3(d_far * b.inv_lo, d_far * b.inv_hi), b.bounded);
    let entry = greater(greater(t_near.x, t_near.y), t_near.z);
    let exit = lesser(lesser(t_far.x, t_far.y), t_far.z);
    return select(MISS, greater(entry, 0.0), entry <= exit && exit >= 0.0 && entry <= t_max);
}

// min and max for what a packet computes, which is never NaN, as a compare
// and a select: lavapipe makes WGSL's min and max NaN-safe, a compare for NaN
// and a blend beside each min or max instruction.
fn lesser(a: f32, b: f32) -> f32 {
    return select(b, a, a < b);
}

fn greater(a: f32, b: f32) -> f32 {
    return select(b, a, a > b);
}

fn lesser3(a: vec3<f32>, b: vec3<f32>) -> vec3<f32> {
    return select(b, a, a < b);
}

fn greater3(a: vec3<f32>, b: vec3<f32>) -> vec3<f32> {
    return select(b, a, a > b);
}

// `test_prims` for a packet's closest hits: primitive i, `prim`, against its four rays.
fn packet_test(i: u32, prim: GpuPrim, p: Packet, hit: PacketHit) -> PacketHit {
    let bound = bitcast<vec4<f32>>(bitcast<vec4<u32>>(hit.t) + vec4<u32>(1u));
    var t = vec4<f32>(MISS);
    let kind = prim_kind(prim);
    // generated: packet_test
    // t < hit.t fails for a miss (MISS is the largest distance).
    let closer = t < hit.t;
    let tie = (t == hit.t) & (t != vec4<f32>(MISS));
    if !any(closer | tie) {
        return hit;
    }
    let object = vec4<u32>(prim.object);
    let take = closer | (tie & (object < hit.object));
    return PacketHit(select(hit.t, t, take), select(hit.prim, vec4<u32>(i), take), select(hit.object, object, take));
}

// The packet's closest hits on the infinite planes, which are in no BVH or
// list and which every ray tests first, so that a floor it hits already
// shortens the walk.
fn packet_planes(p: Packet) -> PacketHit {
    var hit = PacketHit(vec4<f32>(MISS), vec4<u32>(0u), vec4<u32>(0u));
    if HAS_PLANES {
        for (var i = uniforms.plane_first; i < uniforms.plane_first + uniforms.plane_count; i++) {
            hit = packet_test(i, prim_at(i), p, hit);
        }
    }
    return hit;
}

fn min4(v: vec4<f32>) -> f32 {
    return lesser(lesser(v.x, v.y), lesser(v.z, v.w));
}

fn max4(v: vec4<f32>) -> f32 {
    return greater(greater(v.x, v.y), greater(v.z, v.w));
}

// `traverse` for the closest hits of a packet's rays in (0, MISS): the same
// while-while walk, each child entered when the interval test says one of the
// rays may enter it, so each ray visits at least the nodes it visits alone.
fn traverse_packet(p: Packet) -> PacketHit {
    var hit = packet_planes(p);
    // The farthest of the four closest hits so far: beyond it no ray needs a node.
    var t_bound = max4(hit.t);
    var top = 0u;
    var index = uniforms.bvh_root;
    var grid = stored_grid(0u);
    while index != NO_NODE {
        if (index & LEAF) == 0u {
            loop {
                let node = node_at(index);
                let c = child_corners(grid, node.quantized, p.bounds.near_byte);
                let t_left = packet_entry(p.bounds, c.left_near, c.left_far, t_bound);
                let t_right = packet_entry(p.bounds, c.right_near, c.right_far, t_bound);
                index = descend(node, t_left, t_right, &top);
                // Unused when the walk pops (pop restores the grid it needs).
                grid = entered_grid(c, t_left <= t_right, p.bounds.near_byte);
                if (index & LEAF) != 0u {
                    break;
                }
            }
        }
        if index != NEEDS_POP {
            let leaf = node_at(index & ~LEAF).quantized;
            for (var i = leaf.x; i < leaf.x + leaf.y; i++) {
                hit = packet_test(i, prim_at(i), p, hit);
            }
            t_bound = max4(hit.t);
        }
        index = pop(&top, t_bound, &grid);
    }
    return hit;
}
