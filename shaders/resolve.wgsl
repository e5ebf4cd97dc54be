// Resolve: the average of the accumulated samples, times the exposure, tone
// mapped and encoded as sRGB, one display value in [0, 1] per channel.

struct ResolveParams {
    pixel_count: u32,
    tone_map: u32, // 0 clamp, 1 Reinhard, 2 ACES filmic
    exposure: f32,
    _pad: u32,
}

const TONE_CLAMP: u32 = 0u;
const TONE_REINHARD: u32 = 1u;
const TONE_ACES: u32 = 2u;

@group(0) @binding(0) var<uniform> params: ResolveParams;
@group(0) @binding(1) var<storage, read> samples: array<vec4<f32>>;
@group(0) @binding(2) var<storage, read_write> display: array<vec4<f32>>;

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

@compute @workgroup_size(64)
fn resolve_main(@builtin(global_invocation_id) gid: vec3<u32>, @builtin(num_workgroups) groups: vec3<u32>) {
    let i = gid.y * groups.x * 64u + gid.x;
    if i >= params.pixel_count {
        return;
    }
    let s = samples[i];
    let linear = s.rgb / max(s.w, 1.0) * params.exposure;
    let mapped = clamp(tone_map(max(linear, vec3<f32>(0.0))), vec3<f32>(0.0), vec3<f32>(1.0));
    display[i] = vec4<f32>(srgb_encode(mapped), 1.0);
}
