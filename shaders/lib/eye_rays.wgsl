// The primary kernel's eye rays, one at a time through the BVH. A tuning may
// put fast/eye_rays.wgsl in this file's place.
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
fn trace_eye_rays(corner: vec2<u32>, block: u32) -> EyeHits {
    var hits: EyeHits;
    for (var k = 0u; k < 4u; k++) {
        if (block & (1u << k)) != 0u {
            let hit = traverse(camera_ray(vec2<f32>(block_pixel(corner, k)) + 0.5), 0.0, MISS, false, false);
            hits.t[k] = hit.t;
            hits.prim[k] = hit.prim;
            hits.visited[k] = hit.nodes;
        }
    }
    return hits;
}
