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
