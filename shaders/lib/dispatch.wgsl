// What every tracing kernel does around its rays: which pixel of the band an
// invocation has, adding its sample to the pixel's sum, and counting rays.
// import: band_order bindings

var<private> local_stats: array<u32, STAT_COUNT>;

fn count_ray(kind: u32) {
    local_stats[kind] += 1u;
}

fn count_rays(kind: u32, n: u32) {
    local_stats[kind] += n;
}

// The rays this invocation has traced so far, of every kind.
fn rays_counted() -> u32 {
    var total = 0u;
    for (var k = 0u; k < STAT_COUNT; k++) {
        total += local_stats[k];
    }
    return total;
}

// The view this dispatch renders: a constant in a kernel specialised to one
// view (ONLY_VIEW), so the compiler keeps that view's code alone.
fn dispatch_view() -> u32 {
    return select(dispatch.view, ONLY_VIEW, ONLY_VIEW != ANY_VIEW);
}

// The pixel an invocation traces in the current band, if the band covers one;
// the top-left pixel of its block for a kernel whose invocations trace blocks
// of `side`×`side` pixels. `size` is the kernel's workgroup size. Workgroups
// and invocations take their places in the order of band_order.wgsl.
fn band_pixel(wid: vec3<u32>, lid: vec3<u32>, groups: vec3<u32>, size: vec2<u32>, side: u32) -> vec2<u32> {
    return side * band_place(wid, lid, groups, size) + dispatch.origin;
}

// Pixel k of the 2×2 block whose top-left pixel is `corner`, left to right,
// top to bottom.
fn block_pixel(corner: vec2<u32>, k: u32) -> vec2<u32> {
    return corner + vec2<u32>(k & 1u, k >> 1u);
}

fn in_band(pixel: vec2<u32>) -> bool {
    return all(pixel < dispatch.end);
}

// The accumulation buffer holds the current tile alone, indexed from the
// tile's corner.
fn accum_index(pixel: vec2<u32>) -> u32 {
    return (pixel.y - dispatch.tile_y) * dispatch.tile_width + (pixel.x - dispatch.tile_x);
}

// The first sample of a render writes its pixel (the sum starts from zero), so
// it need not read it: a load saved.
fn accumulate(pixel: vec2<u32>, color: vec3<f32>) {
    let index = accum_index(pixel);
    if dispatch.sample_index == 0u {
        accum[index] = vec4<f32>(color, 1.0);
    } else {
        accum[index] += vec4<f32>(color, 1.0);
    }
}

// A data view's pixel is the value at its centre, the same at every sample,
// so each sample writes it with a count of one (the resolve divides by the
// count) rather than adding to it: no load, and no rounding of a sum.
fn write_pixel(pixel: vec2<u32>, value: vec3<f32>) {
    accum[accum_index(pixel)] = vec4<f32>(value, 1.0);
}

// A view of one number (depth, heat map) stores it alone, a quarter of the
// stores; the resolve reads x alone for such views (display.wgsl).
fn write_number(pixel: vec2<u32>, value: f32) {
    accum[accum_index(pixel)].x = value;
}

// The eye ray's closest hit at a pixel: its distance (MISS for a miss) and
// primitive.
struct EyeHit {
    t: f32,
    prim: u32,
}

// The primary kernel, dispatched for a view of the ray tree, leaves each
// pixel's eye hit in the accumulation buffer; the trace kernel may then shade
// from it instead of walking the eye ray again, and its sample overwrites it.
fn write_eye_hit(pixel: vec2<u32>, t: f32, prim: u32) {
    let index = accum_index(pixel);
    accum[index].x = t;
    accum[index].y = bitcast<f32>(prim);
}

fn eye_hit_written(pixel: vec2<u32>) -> EyeHit {
    let written = accum[accum_index(pixel)];
    return EyeHit(written.x, bitcast<u32>(written.y));
}
