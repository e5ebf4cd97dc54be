// The primary kernel: the data views and AOVs (depth, normal, albedo, id, BVH
// heat map) and picking, which need the eye ray's hit alone; dispatched for a
// view of the ray tree, it leaves each eye hit for the trace kernel. A kernel of its
// own, without the ray tree or shadow rays, compiles to far leaner code than
// the trace kernel (register and private-memory pressure), so these views and
// picking run faster and compile sooner. An invocation traces the eye ray of
// one pixel (`trace_eye_block`), or with PACKETS those of a 2×2 block of
// pixels as one packet (fast/eye_bvh.wgsl, fast/eye_tiles.wgsl).
// import: camera checker dispatch eye_block flush_counts primitive scene_arrays types

// What `view` shows of the eye ray `eye`'s closest hit, primitive `prim` at
// distance `t` (or MISS), in the views of more than one number.
fn primary_view(eye: Ray, t: f32, prim: u32) -> vec3<f32> {
    if t == MISS {
        switch dispatch_view() {
            case VIEW_ID: { return vec3<f32>(-1.0); }
            default: { return vec3<f32>(0.0); }
        }
    }
    let p = prim_at(prim);
    switch dispatch_view() {
        case VIEW_ALBEDO: { return material_at(p, eye.origin + t * eye.dir).color; }
        // x for display and AOVs (exact up to 2^24), y the index's own bits,
        // which picking reads: exact for any number of objects.
        case VIEW_ID: { return vec3<f32>(f32(p.object), bitcast<f32>(p.object), 0.0); }
        default: { return surface_at(p, eye, t).geometric; }
    }
}

@compute @workgroup_size(BAND_WORKGROUP_WIDTH, PRIMARY_WORKGROUP_HEIGHT)
fn primary_main(
    @builtin(local_invocation_id) lid: vec3<u32>,
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
) {
    // An invocation traces a 2×2 block of pixels with PACKETS, else one pixel;
    // bit k of `block` stands for pixel k of it, left to right, top to bottom.
    let corner = band_pixel(wid, lid, groups, vec2<u32>(BAND_WORKGROUP_WIDTH, PRIMARY_WORKGROUP_HEIGHT), select(1u, 2u, PACKETS));
    let block = select(1u, 0xfu, PACKETS);
    let hits = trace_eye_block(corner, in_band(corner));
    // The trace kernel counts the eye rays whose hits it takes.
    let for_trace = dispatch_view() == VIEW_SHADED || dispatch_view() == VIEW_RAY_DEPTH || dispatch_view() == VIEW_RAY_COUNT;
    // The loop over the block's pixels steps through its bits, as fast/eye_rays.wgsl does.
    var hit_count = 0u;
    var miss_count = 0u;
    var left = block;
    while left != 0u {
        let k = firstTrailingBit(left);
        left &= left - 1u;
        let pixel = block_pixel(corner, k);
        if in_band(pixel) {
            hit_count += u32(hits.t[k] != MISS);
            miss_count += u32(hits.t[k] == MISS);
            if for_trace {
                write_eye_hit(pixel, hits.t[k], hits.prim[k]);
            } else if dispatch_view() == VIEW_HEATMAP {
                write_number(pixel, f32(hits.visited[k]));
            } else if dispatch_view() == VIEW_DEPTH {
                write_number(pixel, hits.t[k]);
            } else {
                write_pixel(pixel, primary_view(camera_ray(vec2<f32>(pixel) + 0.5), hits.t[k], hits.prim[k]));
            }
        }
    }
    if !for_trace {
        count_rays(STAT_EYE_HIT, hit_count);
        count_rays(STAT_EYE_MISS, miss_count);
    }
    flush_ray_counts(wid, groups);
}
