// The eye rays of lib/eye_rays.wgsl, the same rays in the same order, in a
// loop that lavapipe compiles once (docs/decisions/057-loops-over-bit-masks.md).
// import: bvh camera dispatch

// The closest hits of the eye rays of a 2×2 block of pixels, ray k's in
// component k (MISS for a miss), and the BVH nodes each ray visited.
struct EyeHits {
    t: vec4<f32>,
    prim: vec4<u32>,
    visited: vec4<u32>,
}

// The eye rays through the centres of the pixels of the block whose top-left
// pixel is `corner`, bit k of `block` for pixel k (block_pixel in dispatch.wgsl).
// The loop steps through the bits, a count the compiler does not know, so it
// keeps one copy of its body.
fn trace_eye_rays(corner: vec2<u32>, block: u32) -> EyeHits {
    var hits: EyeHits;
    var left = block;
    while left != 0u {
        let k = firstTrailingBit(left);
        left &= left - 1u;
        let hit = traverse(camera_ray(vec2<f32>(block_pixel(corner, k)) + 0.5), 0.0, MISS, false, false);
        hits.t[k] = hit.t;
        hits.prim[k] = hit.prim;
        hits.visited[k] = hit.nodes;
    }
    return hits;
}
