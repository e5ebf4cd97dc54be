//! The Render section's settings: how the image is traced (samples, view,
//! specular model) and how it is shown (exposure, tone map, resolution), and the
//! render options each gives the kernels.

use glint_encoding::gpu_types::View;
use glint_gpu::{RenderOptions, ToneMap};
use glint_scene::{Material, SpecularModel};

use crate::engine::Canvas;

/// Which specular model shading uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum SpecularChoice {
    /// Each material's own.
    PerMaterial,
    Phong,
    Blinn,
}

impl SpecularChoice {
    pub fn apply(self, m: &Material) -> Material {
        let specular_model = match self {
            SpecularChoice::PerMaterial => m.specular_model,
            SpecularChoice::Phong => SpecularModel::Phong,
            SpecularChoice::Blinn => SpecularModel::BlinnPhong,
        };
        Material { specular_model, ..m.clone() }
    }
}

/// How the image is rendered and shown.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Settings {
    /// Samples per pixel the image converges to.
    pub spp: u32,
    /// Show the image after every sample; otherwise only once all are in.
    pub progressive: bool,
    pub view: View,
    pub exposure: f32,
    pub tone_map: ToneMap,
    /// Render resolution relative to the panel's pixels.
    pub scale: f32,
    pub specular: SpecularChoice,
}

impl Default for Settings {
    fn default() -> Self {
        Self {
            spp: 16,
            progressive: true,
            view: View::Shaded,
            exposure: 1.0,
            tone_map: ToneMap::Clamp,
            scale: 1.0,
            specular: SpecularChoice::PerMaterial,
        }
    }
}

impl Settings {
    /// Samples per pixel the image converges to in the current view.
    pub fn target_samples(&self) -> u32 {
        if self.view.is_primary_only() { 1 } else { self.spp }
    }

    /// The change from `before` makes the traced samples wrong: tracing starts over.
    pub fn changes_samples(&self, before: &Settings) -> bool {
        (self.spp, self.progressive, self.view, self.specular) != (before.spp, before.progressive, before.view, before.specular)
    }

    /// The change from `before` only maps the samples differently: they are presented again.
    pub fn changes_display(&self, before: &Settings) -> bool {
        (self.exposure, self.tone_map) != (before.exposure, before.tone_map)
    }

    /// How `canvas`'s samples are resolved for display.
    pub fn present_options(&self, canvas: &Canvas) -> RenderOptions {
        RenderOptions {
            view: self.view,
            exposure: self.exposure,
            tone_map: self.tone_map,
            view_scale: canvas.prepared.view_scale(self.view),
            ..RenderOptions::default()
        }
    }

    /// How `canvas`'s samples are traced and resolved.
    pub fn trace_options(&self, canvas: &Canvas) -> RenderOptions {
        RenderOptions { spp: self.traced_samples(), ..self.present_options(canvas) }
    }

    /// The samples per pixel the trace kernel is told of. One sample goes
    /// through pixel centres; progressive samples are jittered without a
    /// fixed count (0), a fixed count is stratified.
    pub fn traced_samples(&self) -> u32 {
        match (self.spp, self.progressive) {
            (1, _) => 1,
            (_, true) => 0,
            (n, false) => n,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Settings;

    #[test]
    fn samples_through_pixel_centres_only_at_one_a_pixel() {
        let settings = |spp, progressive| Settings { spp, progressive, ..Settings::default() };
        assert_eq!(Settings::default().traced_samples(), 0, "the viewer opens with progressive samples");
        assert_eq!(settings(1, true).traced_samples(), 1);
        assert_eq!(settings(16, false).traced_samples(), 16);
    }
}
