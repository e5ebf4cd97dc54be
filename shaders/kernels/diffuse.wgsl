// The diffuse kernel: the `diffuse` debug view, direct diffuse light alone. A
// kernel apart from the primary one because its shadow rays are a second BVH
// traversal, which every data view (depth, normal, id…) would otherwise
// compile too (docs/decisions/008-diffuse-view-kernel.md).
// import: bvh camera checker diffuse_view dispatch flush_counts primitive scene_arrays

@compute @workgroup_size(BAND_WORKGROUP_WIDTH, BAND_WORKGROUP_HEIGHT)
fn diffuse_main(
    @builtin(local_invocation_id) lid: vec3<u32>,
    @builtin(workgroup_id) wid: vec3<u32>,
    @builtin(num_workgroups) groups: vec3<u32>,
) {
    let pixel = band_pixel(wid, lid, groups, vec2<u32>(BAND_WORKGROUP_WIDTH, BAND_WORKGROUP_HEIGHT), 1u);
    if in_band(pixel) {
        // The pixel centre, like the data views: the view is not averaged.
        let eye = camera_ray(vec2<f32>(pixel) + 0.5);
        let hit = traverse(eye, 0.0, MISS, false, false);
        count_ray(select(STAT_EYE_HIT, STAT_EYE_MISS, hit.t == MISS));
        var color = vec3<f32>(0.0);
        if hit.t != MISS {
            let p = prim_at(hit.prim);
            let s = surface_at(p, eye, hit.t);
            color = diffuse_only(s, material_at(p, s.point));
        }
        accumulate(pixel, color);
    }
    flush_ray_counts(wid, groups);
}
