// Primary rays. `pixel` is a position on the image in pixels, (0, 0) at the
// top-left corner; a pixel's centre is at (i + 0.5, j + 0.5), so that
// u_s = l + (r − l)(i + 0.5)/n_x with l = −r, and v_s = t − (t − b)(j + 0.5)/n_y.
// import: bindings types

fn camera_ray(pixel: vec2<f32>) -> Ray {
    let cam = uniforms.camera;
    let size = vec2<f32>(f32(uniforms.width), f32(uniforms.height));
    let us = -cam.half_width + 2.0 * cam.half_width * pixel.x / size.x;
    let vs = cam.half_height - 2.0 * cam.half_height * pixel.y / size.y;
    if cam.projection == PROJECTION_ORTHOGRAPHIC {
        return Ray(cam.eye + us * cam.u + vs * cam.v, -cam.w);
    }
    return Ray(cam.eye, normalize(-cam.w + us * cam.u + vs * cam.v));
}

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
