// Resolve: the average of a pixel's accumulated samples becomes its linear
// value and its display value in [0, 1] per channel. One exposure rule for
// every output: the views of light and colour (shaded, albedo, diffuse) are
// scaled by the exposure, in the linear value as in the display value; the
// data views (normal, depth, id, heat map) keep their values. Light views are
// then tone mapped and encoded as sRGB; data views are mapped to colours:
// normals as 0.5 + 0.5·n, depth as grey (white near, black at `scale`), object
// ids as distinct colours, heat maps as a false-colour ramp of nodes visited
// over `scale`, and so are the teaching views' tree depths and ray counts.
// Misses are black. crates/glint-gpu/src/display.rs is its CPU twin.

struct ResolveParams {
    pixel_count: u32,
    tone_map: u32, // TONE_CLAMP, TONE_REINHARD or TONE_ACES (filmic)
    exposure: f32,
    view: u32,
    scale: f32,
    _pad0: u32,
    _pad1: u32,
    _pad2: u32,
}

@group(0) @binding(0) var<uniform> params: ResolveParams;
@group(0) @binding(1) var<storage, read> samples: array<vec4<f32>>;

fn tone_map(c: vec3<f32>) -> vec3<f32> {
    switch params.tone_map {
        case TONE_REINHARD: { return c / (vec3<f32>(1.0) + c); }
        case TONE_ACES: {
            // Narkowicz's fit of the ACES filmic curve.
            return (c * (2.51 * c + 0.03)) / (c * (2.43 * c + 0.59) + 0.14);
        }
        default: { return c; }
    }
}

fn srgb_encode(c: vec3<f32>) -> vec3<f32> {
    let lo = c * 12.92;
    let hi = 1.055 * pow(c, vec3<f32>(1.0 / 2.4)) - 0.055;
    return select(hi, lo, c <= vec3<f32>(0.0031308));
}

// Blue → cyan → green → yellow → red as t goes from 0 to 1.
fn heat_ramp(t: f32) -> vec3<f32> {
    let x = clamp(t, 0.0, 1.0) * 4.0;
    return clamp(vec3<f32>(x - 2.0, select(x, 4.0 - x, x > 2.0), 2.0 - x), vec3<f32>(0.0), vec3<f32>(1.0));
}

fn id_colour(id: f32) -> vec3<f32> {
    var h = u32(id) * 2654435761u;
    h ^= h >> 15u;
    return 0.25 + 0.75 * vec3<f32>(f32(h & 255u), f32((h >> 8u) & 255u), f32((h >> 16u) & 255u)) / 255.0;
}

fn finite_or_zero(c: vec3<f32>) -> vec3<f32> {
    // NaN fails every comparison, so it becomes 0 here, as do infinities.
    return select(vec3<f32>(0.0), c, abs(c) <= vec3<f32>(3.0e38));
}

fn is_data_view(view: u32) -> bool {
    return view == VIEW_NORMAL || view == VIEW_DEPTH || view == VIEW_ID || view == VIEW_HEATMAP
        || view == VIEW_RAY_DEPTH || view == VIEW_RAY_COUNT;
}

// Depth and the heat map store their one number alone, in x, with no count.
fn is_one_number_view(view: u32) -> bool {
    return view == VIEW_DEPTH || view == VIEW_HEATMAP;
}

fn linear_value(s: vec4<f32>) -> vec3<f32> {
    if is_one_number_view(params.view) {
        return vec3<f32>(s.x);
    }
    let mean = s.rgb / max(s.w, 1.0);
    return select(mean * params.exposure, mean, is_data_view(params.view));
}

fn display_value(s: vec4<f32>) -> vec3<f32> {
    let v = linear_value(s);
    switch params.view {
        case VIEW_NORMAL: {
            return select(vec3<f32>(0.0), 0.5 + 0.5 * v, dot(v, v) > 0.25);
        }
        case VIEW_DEPTH: {
            return vec3<f32>(select(0.0, 1.0 - clamp(v.x / params.scale, 0.0, 1.0), v.x < 1.0e38));
        }
        case VIEW_ID: {
            return select(vec3<f32>(0.0), id_colour(v.x), v.x >= 0.0);
        }
        case VIEW_HEATMAP, VIEW_RAY_DEPTH, VIEW_RAY_COUNT: {
            return heat_ramp(v.x / params.scale);
        }
        default: {
            return srgb_encode(clamp(tone_map(max(finite_or_zero(v), vec3<f32>(0.0))), vec3<f32>(0.0), vec3<f32>(1.0)));
        }
    }
}
