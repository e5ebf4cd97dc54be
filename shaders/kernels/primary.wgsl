// The primary kernel: the data views and AOVs (depth, normal, albedo, id, BVH
// heat map) and picking, which need the eye ray's hit alone. A kernel of its
// own, without the ray tree or shadow rays, compiles to far leaner code than
// the trace kernel (register and private-memory pressure), so these views and
// picking run faster and compile sooner.
// import: bindings bvh camera checker dispatch primitive types

fn primary_view(eye: Ray) -> vec3<f32> {
    let hit = traverse(eye, 0.0, MISS, false, false);
    count_ray(select(STAT_EYE_HIT, STAT_EYE_MISS, hit.t == MISS));
    if dispatch_view() == VIEW_HEATMAP {
        return vec3<f32>(f32(hit.nodes));
    }
    if hit.t == MISS {
        switch dispatch_view() {
            case VIEW_DEPTH: { return vec3<f32>(MISS); }
            case VIEW_ID: { return vec3<f32>(-1.0); }
            default: { return vec3<f32>(0.0); }
        }
    }
    let p = prims[hit.prim];
    switch dispatch_view() {
        case VIEW_DEPTH: { return vec3<f32>(hit.t); }
        case VIEW_ALBEDO: { return material_at(p, eye.origin + hit.t * eye.dir).color; }
        // x for display and AOVs (exact up to 2^24), y the index's own bits,
        // which picking reads: exact for any number of objects.
        case VIEW_ID: { return vec3<f32>(f32(p.object), bitcast<f32>(p.object), 0.0); }
        default: { return surface_at(p, eye, hit.t).geometric; }
    }
}

@compute @workgroup_size(8, 8)
fn primary_main(
    @builtin(global_invocation_id) gid: vec3<u32>,
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
) {
    let pixel = band_pixel(gid);
    if in_band(pixel) {
        // Data views take the pixel centre: they are not averaged.
        accumulate(pixel, primary_view(camera_ray(vec2<f32>(pixel) + 0.5)));
    }
    flush_ray_counts(wid, groups);
}
