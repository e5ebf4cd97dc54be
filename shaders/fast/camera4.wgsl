// The eye rays of a 2×2 block of pixels, for ray packets (packet.wgsl).
// import: camera fast/rays4

// The eye rays through the centres of the 2×2 block of pixels whose top-left
// pixel is `corner`: ray k through pixel k, left to right, top to bottom
// (block_pixel in dispatch.wgsl).
fn camera_rays4(corner: vec2<u32>) -> Rays4 {
    let r0 = camera_ray(vec2<f32>(corner) + 0.5);
    let r1 = camera_ray(vec2<f32>(corner + vec2<u32>(1u, 0u)) + 0.5);
    let r2 = camera_ray(vec2<f32>(corner + vec2<u32>(0u, 1u)) + 0.5);
    let r3 = camera_ray(vec2<f32>(corner + vec2<u32>(1u, 1u)) + 0.5);
    return Rays4(gather4(r0.origin, r1.origin, r2.origin, r3.origin), gather4(r0.dir, r1.dir, r2.dir, r3.dir));
}
