// The ray counts of an invocation, added to its workgroup's slot (of
// STAT_SLOTS) when it is done: a workgroup barrier to sum them first would
// cost more than the few uncontended atomics. A tuning may put
// fast/flush_counts.wgsl in this file's place.
// import: bindings dispatch

fn flush_ray_counts(wid: vec3<u32>, groups: vec3<u32>) {
    let base = ((wid.y * groups.x + wid.x) & (STAT_SLOTS - 1u)) * STAT_COUNT;
    for (var k = 0u; k < STAT_COUNT; k++) {
        if local_stats[k] != 0u {
            atomicAdd(&stats[base + k], local_stats[k]);
        }
    }
}
