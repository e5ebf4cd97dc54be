use glam::Vec3;

use crate::{Animation, Camera, Light, LoadError, Material, Shape};

/// A renderable scene, independent of the file format it came from.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    pub width: u32,
    pub height: u32,
    pub background: Vec3,
    pub camera: Camera,
    /// I_a: ambient colour times intensity.
    pub ambient: Vec3,
    pub lights: Vec<Light>,
    pub materials: Vec<Material>,
    pub objects: Vec<Object>,
    pub depth_cue: Option<DepthCue>,
    pub render: RenderSettings,
    /// How the camera and lights move from frame to frame; `None` for a still.
    /// A loaded scene's camera and lights are as the file writes them, until
    /// `Scene::set_frame` poses them at a frame.
    pub animation: Option<Animation>,
    /// Problems that did not stop loading (e.g. a degenerate polygon that was
    /// skipped), each naming file and line.
    pub warnings: Vec<LoadError>,
}

/// A named thing in the scene: one shape, or many for a mesh. Its index is the
/// object id seen in picking and the `id` AOV.
#[derive(Debug, Clone, PartialEq)]
pub struct Object {
    pub material: usize,
    pub shapes: Vec<Shape>,
}

/// Atmospheric attenuation: I' = s_o·I + (1 − s_o)·I_dc, with s_o going linearly
/// from `near_scale` (s_b) at distance `near` (z_b) to `far_scale` (s_f) at `far`
/// (z_f) and clamped outside. Distance is measured along each ray from its origin.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DepthCue {
    pub color: Vec3,
    pub near: f32,
    pub far: f32,
    pub near_scale: f32,
    pub far_scale: f32,
}

impl DepthCue {
    /// s_o at distance `d`.
    pub fn scale(&self, d: f64) -> f64 {
        let (near, far) = (f64::from(self.near), f64::from(self.far));
        let f = ((d - near) / (far - near)).clamp(0.0, 1.0);
        f64::from(self.near_scale) + f * (f64::from(self.far_scale) - f64::from(self.near_scale))
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ShadowMode {
    /// Every occluder blocks the light.
    Opaque,
    /// Transmissive occluders let light through, tinted by their k_t.
    Tinted,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RenderSettings {
    /// Longest ray path, counting the eye ray as depth 1.
    pub max_depth: u32,
    /// Rays whose accumulated weight falls below this are not traced; 0 traces all.
    pub cutoff: f32,
    pub shadows: bool,
    pub shadow_mode: ShadowMode,
    pub reflections: bool,
    pub refractions: bool,
    /// Normals turned towards the eye before lighting, as the lecture says.
    /// Off only in grading's diagnosis, which renders a student's lighting
    /// with the normals as the geometry gives them; no scene file sets it.
    pub turn_normals: bool,
}

/// The largest image side Glint accepts, in pixels, whatever the scene's format.
pub const MAX_IMAGE_SIDE: u32 = 16384;

/// The deepest ray tree the GPU kernel's explicit stack holds.
pub const MAX_DEPTH_LIMIT: u32 = 16;

/// The most lights a scene may have, on or off: as many as the kernels'
/// uniform buffer holds (glint-encoding's gpu_types.rs checks the two agree).
pub const MAX_LIGHTS: u32 = 1365;
/// The most materials a scene may have, for the same reason.
pub const MAX_MATERIALS: u32 = 585;

impl Default for RenderSettings {
    fn default() -> Self {
        Self {
            max_depth: 5,
            cutoff: 1.0 / 256.0,
            shadows: true,
            shadow_mode: ShadowMode::Opaque,
            reflections: true,
            refractions: true,
            turn_normals: true,
        }
    }
}

impl Scene {
    pub fn primitive_count(&self) -> usize {
        self.objects.iter().map(|o| o.shapes.len()).sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn depth_cue_is_linear_between_planes_and_clamped() {
        let dc = DepthCue { color: Vec3::ZERO, near: 2.0, far: 10.0, near_scale: 1.0, far_scale: 0.2 };
        assert_eq!(dc.scale(0.0), 1.0);
        assert!((dc.scale(6.0) - 0.6).abs() < 1e-7);
        assert!((dc.scale(50.0) - 0.2).abs() < 1e-7);
    }
}
