// The order in which a dispatch's workgroups cover a band, and a workgroup's
// invocations its pixels: row order. A tuning may put fast/spread.wgsl in this
// file's place.
// A seam: `band_place` is a function, not arithmetic inline, only so that
// fast/spread.wgsl can deal the places in another order.

// Where in the band invocation `lid` of workgroup `wid` traces, in invocations;
// `groups` is the dispatch's count of workgroups, `size` a workgroup's.
fn band_place(wid: vec3<u32>, lid: vec3<u32>, groups: vec3<u32>, size: vec2<u32>) -> vec2<u32> {
    return wid.xy * size + lid.xy;
}
