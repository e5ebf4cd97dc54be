// The order in which a dispatch's workgroups cover a band, and a workgroup's
// invocations its pixels, spread for lavapipe's threads and SIMD groups
// (docs/decisions/031-spread-order.md, 041-simd-group-on-a-2x2-block.md): the
// function of lib/band_order.wgsl.

// Where in the band invocation `lid` of workgroup `wid` traces, in invocations.
fn band_place(wid: vec3<u32>, lid: vec3<u32>, groups: vec3<u32>, size: vec2<u32>) -> vec2<u32> {
    return spread_workgroup(wid, groups) * size + spread_invocation(lid, size);
}

// Where in the band workgroup `wid` of a dispatch of `groups` traces, in
// workgroups. lavapipe hands each of its threads one run of consecutive
// workgroups (x fastest), so in that order one thread would trace the band's
// top and another its bottom, and a sky above a mountain would leave a core
// idle. Here the i-th workgroup takes place i / SPREAD_STRIPS of strip
// i % SPREAD_STRIPS of the band (the last few places one strip each), so
// every run holds its share of every strip: a permutation for any count.
fn spread_workgroup(wid: vec3<u32>, groups: vec3<u32>) -> vec2<u32> {
    let count = groups.x * groups.y;
    let i = wid.y * groups.x + wid.x;
    let strip_length = count / SPREAD_STRIPS;
    let longer_strips = count % SPREAD_STRIPS;
    let dealt = strip_length * SPREAD_STRIPS;
    let strip = select(i % SPREAD_STRIPS, i - dealt, i >= dealt);
    let place = select(i / SPREAD_STRIPS, strip_length, i >= dealt);
    let spread = strip * strip_length + min(strip, longer_strips) + place;
    return vec2<u32>(spread % groups.x, spread / groups.x);
}

// Where in its workgroup of `size` invocations invocation `lid` traces.
// lavapipe runs a workgroup's invocations a SIMD group at a time, four or
// eight consecutive ones (x fastest), and a group walks the BVH until its
// last lane is done; in row order its lanes would trace a 4×1 or 8×1 strip.
// Here every four consecutive invocations take a 2×2 block of places, the
// blocks in row order, so a group's rays are close together and walk more
// alike (counted on tetra's depth frames: 0.94× the kernel's instructions).
// A permutation when both sides of `size` are even.
fn spread_invocation(lid: vec3<u32>, size: vec2<u32>) -> vec2<u32> {
    let i = lid.y * size.x + lid.x;
    let block = i >> 2u;
    let blocks_per_row = size.x >> 1u;
    return 2u * vec2<u32>(block % blocks_per_row, block / blocks_per_row) + vec2<u32>(i & 1u, (i >> 1u) & 1u);
}
