//! The CPU twin of `shaders/lib/display.wgsl`, the resolve: what one pixel's
//! accumulated samples become, as a linear value and as a display value. The
//! kernel is the definition; this twin states it in Rust so that a test
//! (`tests/resolve.rs`) can hold the GPU to it pixel by pixel, and resolves
//! renders on a CPU adapter, where compiling the kernel costs more than it saves.

use glint_encoding::gpu_types::View;

use crate::{Image, RenderOptions, ToneMap};

/// A tile's accumulated samples resolved on the host, as the kernel would.
pub fn resolve(samples: &[[f32; 4]], width: u32, height: u32, options: &RenderOptions) -> Image {
    let opaque = |[r, g, b]: [f32; 3]| [r, g, b, 1.0];
    Image {
        width,
        height,
        display: samples.iter().map(|&s| opaque(display_value(s, options))).collect(),
        linear: samples.iter().map(|&s| opaque(linear_value(s, options))).collect(),
    }
}

/// The mean of the samples; scaled by the exposure unless `view` is a data
/// view. A view of one number is its x alone.
pub fn linear_value(sample: [f32; 4], options: &RenderOptions) -> [f32; 3] {
    if options.view.is_one_number() {
        return [sample[0]; 3];
    }
    let n = sample[3].max(1.0);
    let scale = if options.view.is_data() { 1.0 } else { options.exposure };
    [0, 1, 2].map(|c| sample[c] / n * scale)
}

/// The display value in [0, 1] per channel (sRGB-encoded for light views);
/// what does not come out finite (ACES of a huge value) is shown as 0, as the
/// resolve and present kernels do.
pub fn display_value(sample: [f32; 4], options: &RenderOptions) -> [f32; 3] {
    mapped(linear_value(sample, options), options).map(finite_or_zero)
}

fn mapped(v: [f32; 3], options: &RenderOptions) -> [f32; 3] {
    match options.view {
        View::Normal => {
            let on_surface = v.iter().map(|c| c * c).sum::<f32>() > 0.25;
            if on_surface { v.map(|c| 0.5 + 0.5 * c) } else { [0.0; 3] }
        }
        View::Depth => [if v[0] < 1.0e38 { 1.0 - (v[0] / options.view_scale).clamp(0.0, 1.0) } else { 0.0 }; 3],
        View::Id => if v[0] >= 0.0 { id_colour(v[0]) } else { [0.0; 3] },
        View::Heatmap | View::RayDepth | View::RayCount => heat_ramp(v[0] / options.view_scale),
        View::Shaded | View::Albedo | View::Diffuse => {
            tone_map(v.map(|c| finite_or_zero(c).max(0.0)), options.tone_map).map(|c| srgb_encode(c.clamp(0.0, 1.0)))
        }
    }
}

fn finite_or_zero(c: f32) -> f32 {
    if c.abs() <= 3.0e38 { c } else { 0.0 }
}

fn tone_map(c: [f32; 3], tone_map: ToneMap) -> [f32; 3] {
    match tone_map {
        ToneMap::Clamp => c,
        ToneMap::Reinhard => c.map(|x| x / (1.0 + x)),
        // Narkowicz's fit of the ACES filmic curve.
        ToneMap::Aces => c.map(|x| (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14)),
    }
}

fn srgb_encode(c: f32) -> f32 {
    if c <= 0.0031308 { c * 12.92 } else { 1.055 * c.powf(1.0 / 2.4) - 0.055 }
}

/// Blue → cyan → green → yellow → red as t goes from 0 to 1.
fn heat_ramp(t: f32) -> [f32; 3] {
    let x = t.clamp(0.0, 1.0) * 4.0;
    [x - 2.0, if x > 2.0 { 4.0 - x } else { x }, 2.0 - x].map(|c| c.clamp(0.0, 1.0))
}

fn id_colour(id: f32) -> [f32; 3] {
    let mut h = (id as u32).wrapping_mul(2_654_435_761);
    h ^= h >> 15;
    [h & 255, (h >> 8) & 255, (h >> 16) & 255].map(|b| 0.25 + 0.75 * b as f32 / 255.0)
}
