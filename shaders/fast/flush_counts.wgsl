// The flush of lib/flush_counts.wgsl, the same atomics in the same order, in a
// loop that lavapipe compiles once (docs/decisions/057-loops-over-bit-masks.md):
// it steps through a bit mask of the kinds counted, a count the compiler does
// not know, so it keeps one copy of the atomic instead of one per kind.
// import: bindings dispatch

fn flush_ray_counts(wid: vec3<u32>, groups: vec3<u32>) {
    let base = ((wid.y * groups.x + wid.x) & (STAT_SLOTS - 1u)) * STAT_COUNT;
    var counted = 0u;
    for (var k = 0u; k < STAT_COUNT; k++) {
        counted |= select(0u, 1u << k, local_stats[k] != 0u);
    }
    while counted != 0u {
        let k = firstTrailingBit(counted);
        counted &= counted - 1u;
        atomicAdd(&stats[base + k], local_stats[k]);
    }
}
