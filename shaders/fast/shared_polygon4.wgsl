// polygon4.wgsl where every lane of a SIMD group tests the same polygon, as
// the eye tiles' walk has them (eye_tiles.wgsl): each lane loads one vertex
// and the lanes share them, where each lane would load every vertex
// (docs/decisions/052-eye-tile-polygons-load-a-vertex-a-lane.md). Each ray
// gets the same answer as in polygon4.wgsl: the same vertices, the same edges.
// import: fast/plane4 fast/ray_frame4 fast/rays4 scene_arrays types

// The lanes test one polygon, so the subgroup operations run in uniform
// control flow; no compiler can see that (as in eye_tiles.wgsl).
@diagnostic(off, subgroup_uniformity)
fn polygon_intersect4(p: GpuPrim, rays: Rays4, frame: RayFrame4, t_min: vec4<f32>, t_max: vec4<f32>) -> vec4<f32> {
    let t = plane_intersect4(p, rays, t_min, t_max);
    let miss = vec4<f32>(MISS);
    // Together: every lane takes part in the loads below.
    if subgroupAll(all(t == miss)) {
        return miss;
    }
    let lanes = subgroupAdd(1u);
    let lane = subgroupExclusiveAdd(1u);
    // The lanes load `lanes` vertices at a time, one each: `loaded` is this lane's.
    var loaded = point_at(p.first + min(lane, p.count - 1u)).xyz;
    let first = to_frame4(frame, subgroupShuffle(loaded, 0u));
    var inside = vec4<bool>(false);
    var prev = first;
    for (var i = 1u; i < p.count; i++) {
        let j = i & (lanes - 1u);
        if j == 0u {
            loaded = point_at(p.first + min(i + lane, p.count - 1u)).xyz;
        }
        let cur = to_frame4(frame, subgroupShuffle(loaded, j));
        inside = inside != crosses4(prev, cur);
        prev = cur;
    }
    return select(miss, t, inside != crosses4(prev, first));
}
