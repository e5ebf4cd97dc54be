// Present: the viewer's resolve. It shares `display_value` with the resolve
// kernel and writes display values straight into an rgba8
// texture that the UI draws, so no image goes through the CPU. egui treats
// rgba8unorm texels as sRGB-encoded, which is what `display_value` gives.
// import: display

@group(0) @binding(3) var image: texture_storage_2d<rgba8unorm, write>;

@compute @workgroup_size(8, 8)
fn present_main(@builtin(global_invocation_id) gid: vec3<u32>) {
    let size = textureDimensions(image);
    if gid.x >= size.x || gid.y >= size.y {
        return;
    }
    let value = finite_or_zero(display_value(samples[gid.y * size.x + gid.x]));
    textureStore(image, gid.xy, vec4<f32>(value, 1.0));
}
