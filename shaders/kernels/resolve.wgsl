// The resolve kernel: each pixel's display and linear values, for read-back.
// import: display

@group(0) @binding(2) var<storage, read_write> display: array<vec4<f32>>;
@group(0) @binding(3) var<storage, read_write> linear: array<vec4<f32>>;

@compute @workgroup_size(64)
fn resolve_main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = gid.y * groups.x * 64u + gid.x;
    if i >= params.pixel_count {
        return;
    }
    display[i] = vec4<f32>(finite_or_zero(display_value(samples[i])), 1.0);
    linear[i] = vec4<f32>(linear_value(samples[i]), 1.0);
}
