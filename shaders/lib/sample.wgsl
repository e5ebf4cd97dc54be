// Where in its pixel each sample's ray goes, as an offset from the pixel's
// top-left corner. One sample per pixel goes through the centre. N samples are
// stratified: the first k² (k = ⌊√N⌋) are jittered within the cells of a k × k
// grid, any others anywhere. With the tent filter the offsets are drawn from a
// tent over [−1, 1] around the centre instead of a box, so every sample weighs
// the same. Random numbers come from a hash of pixel, sample index and seed, so
// a render is the same for the same seed.
// import: bindings

fn pcg_hash(v: u32) -> u32 {
    let state = v * 747796405u + 2891336453u;
    let word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

fn unit_float(bits: u32) -> f32 {
    return f32(bits >> 8u) / 16777216.0;
}

// Warps a uniform number in [0, 1) to the tent distribution on [−1, 1].
fn tent(u: f32) -> f32 {
    let v = 2.0 * u;
    return select(1.0 - sqrt(2.0 - v), sqrt(v) - 1.0, v < 1.0);
}

fn sample_offset(pixel: vec2<u32>) -> vec2<f32> {
    if dispatch.sample_count == 1u {
        return vec2<f32>(0.5);
    }
    let h = pcg_hash(pcg_hash(pcg_hash(dispatch.seed ^ pixel.x) ^ pixel.y) ^ dispatch.sample_index);
    var u = vec2<f32>(unit_float(h), unit_float(pcg_hash(h)));
    let k = u32(floor(sqrt(f32(dispatch.sample_count))));
    if dispatch.sample_count > 1u && dispatch.sample_index < k * k {
        let cell = vec2<f32>(f32(dispatch.sample_index % k), f32(dispatch.sample_index / k));
        u = (cell + u) / f32(k);
    }
    if dispatch.pixel_filter == FILTER_TENT {
        return vec2<f32>(0.5 + tent(u.x), 0.5 + tent(u.y));
    }
    return u;
}
