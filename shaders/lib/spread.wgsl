// The order in which a dispatch's workgroups cover a band.

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
