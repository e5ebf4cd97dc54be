// The trace kernel: one sample per pixel per dispatch, Whitted's ray tree
// (lib/ray_tree.wgsl). The teaching views show the tree's size instead of its
// colour: how deep it went, and how many rays it took.
// import: dispatch flush_counts ray_tree

@compute @workgroup_size(BAND_WORKGROUP_WIDTH, BAND_WORKGROUP_HEIGHT)
fn trace_main(
    @builtin(local_invocation_id) lid: vec3<u32>,
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
) {
    let pixel = band_pixel(wid, lid, groups, vec2<u32>(BAND_WORKGROUP_WIDTH, BAND_WORKGROUP_HEIGHT), 1u);
    if in_band(pixel) {
        let color = trace_pixel(pixel);
        switch dispatch_view() {
            case VIEW_RAY_DEPTH: { accumulate(pixel, vec3<f32>(f32(deepest))); }
            case VIEW_RAY_COUNT: { accumulate(pixel, vec3<f32>(f32(rays_counted()))); }
            default: { accumulate(pixel, color); }
        }
    }
    flush_ray_counts(wid, groups);
}

