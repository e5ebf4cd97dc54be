//! Rendering a case's scene with its render settings, as `glint render`
//! would with the same options.

use std::path::Path;

use glint_encoding::gpu_types::{Filter, View};
use glint_gpu::{Acceleration, Image, RenderOptions, Renderer, ToneMap};
use glint_scene::MAX_IMAGE_SIDE;
use glint_scene::nff::NffAngle;
use glint_scene::{LoadOptions, Scene};

use crate::settings::{FilterName, NffAngleName, RenderSettings, ToneMapName, ViewName};

/// A case's render and the settings it was made with, in words.
pub struct Rendered {
    pub image: Image,
    /// `view shaded, max depth 5, 4 spp, 320x240`: what a report shows, so
    /// that a reader sees which settings made an image differ.
    pub settings: String,
}

/// Renders `scene` with `settings`; the error is one line naming the scene
/// file or the GPU problem.
pub fn render(renderer: &Renderer, scene_file: &Path, settings: &RenderSettings) -> Result<Rendered, String> {
    let scene = load(scene_file, settings)?;
    render_scene(renderer, &scene, scene_file, settings)
}

/// Reads `scene_file` as `settings` say (NFF's angle) and applies the
/// settings that change the scene: depth, cutoff and the effect switches.
pub fn load(scene_file: &Path, settings: &RenderSettings) -> Result<Scene, String> {
    let load_options = LoadOptions {
        nff_angle: match settings.nff_angle {
            Some(NffAngleName::Edges) => NffAngle::Edges,
            Some(NffAngleName::Centers) | None => NffAngle::Centers,
        },
    };
    let mut scene = glint_scene::load_with(scene_file, &load_options).map_err(|e| e.to_string())?;
    if let Some(depth) = settings.max_depth {
        scene.render.max_depth = depth.0;
    }
    if settings.no_cutoff == Some(true) {
        scene.render.cutoff = 0.0;
    }
    scene.render.shadows &= settings.shadows.unwrap_or(true);
    scene.render.reflections &= settings.reflection.unwrap_or(true);
    scene.render.refractions &= settings.refraction.unwrap_or(true);
    Ok(scene)
}

/// Renders a loaded `scene` (read from `scene_file`) with `settings`.
pub fn render_scene(renderer: &Renderer, scene: &Scene, scene_file: &Path, settings: &RenderSettings) -> Result<Rendered, String> {
    let (width, height) = image_size(settings, scene.width, scene.height).map_err(|e| format!("{}: {e}", scene_file.display()))?;
    let prepared = renderer.prepare(scene, width, height, Acceleration::Bvh).map_err(|e| e.to_string())?;
    let view = view_of(settings.view);
    let options = RenderOptions {
        view,
        // The debug views trace one ray through each pixel centre.
        spp: if view.is_primary_only() { 1 } else { settings.spp.map_or(1, |s| s.0) },
        seed: settings.seed.unwrap_or(0),
        filter: match settings.filter {
            Some(FilterName::Tent) => Filter::Tent,
            Some(FilterName::Box) | None => Filter::Box,
        },
        exposure: settings.exposure.map_or(1.0, |e| e.value as f32),
        tone_map: match settings.tone_map {
            Some(ToneMapName::Clamp) | None => ToneMap::Clamp,
            Some(ToneMapName::Reinhard) => ToneMap::Reinhard,
            Some(ToneMapName::Aces) => ToneMap::Aces,
        },
        view_scale: prepared.view_scale(view),
        band_rows: None,
    };
    let (image, _) = renderer.render(&prepared.buffers, &options, &mut |_, _| {}).map_err(|e| e.to_string())?;
    // A depth image stores misses as +∞, as `glint render` writes it.
    let image = if view == View::Depth { image.with_misses_at_infinity() } else { image };
    let image = if view.is_data() && view != View::Normal { one_number_per_pixel(image) } else { image };
    let view_name = settings.view.map_or("shaded", ViewName::name);
    let mut settings = format!("view {view_name}, max depth {}, {} spp, {width}x{height}", scene.render.max_depth, options.spp);
    for (on, ray) in [(scene.render.shadows, "shadow"), (scene.render.reflections, "reflected"), (scene.render.refractions, "refracted")] {
        if !on {
            settings += &format!(", no {ray} rays");
        }
    }
    Ok(Rendered { image, settings })
}

/// The data views but normals (depth, id, heatmap, ray depth and count) are
/// one number per pixel, the first linear channel, and `glint render` writes
/// them as one channel; with that
/// number in all three channels the render compares with such a file, and a
/// golden blessed from it holds the same.
fn one_number_per_pixel(mut image: Image) -> Image {
    for p in &mut image.linear {
        p[1] = p[0];
        p[2] = p[0];
    }
    image
}

/// The size `glint render` would use: both sides as set; one side alone
/// keeps the scene's aspect ratio; neither, the scene's. Then scaled to fit
/// inside `fit` with the aspect ratio kept (up or down), each side at least 1.
fn image_size(settings: &RenderSettings, scene_width: u32, scene_height: u32) -> Result<(u32, u32), String> {
    let aspect = f64::from(scene_width) / f64::from(scene_height);
    let (width, height) = match (settings.width, settings.height) {
        (Some(w), Some(h)) => (f64::from(w.0), f64::from(h.0)),
        (Some(w), None) => (f64::from(w.0), (f64::from(w.0) / aspect).round().max(1.0)),
        (None, Some(h)) => ((f64::from(h.0) * aspect).round().max(1.0), f64::from(h.0)),
        (None, None) => (f64::from(scene_width), f64::from(scene_height)),
    };
    let (width, height) = match settings.fit {
        Some([fit_width, fit_height]) => {
            let scale = (f64::from(fit_width.0) / width).min(f64::from(fit_height.0) / height);
            ((width * scale).round().max(1.0), (height * scale).round().max(1.0))
        }
        None => (width, height),
    };
    let limit = f64::from(MAX_IMAGE_SIDE);
    if width > limit || height > limit {
        return Err(format!("the image would be {width}x{height}, beyond {MAX_IMAGE_SIDE} pixels a side: set both width and height"));
    }
    Ok((width as u32, height as u32))
}

fn view_of(view: Option<ViewName>) -> View {
    match view {
        Some(ViewName::Shaded) | None => View::Shaded,
        Some(ViewName::Normals) => View::Normal,
        Some(ViewName::Depth) => View::Depth,
        Some(ViewName::Albedo) => View::Albedo,
        Some(ViewName::Diffuse) => View::Diffuse,
        Some(ViewName::Id) => View::Id,
        Some(ViewName::Heatmap) => View::Heatmap,
        Some(ViewName::RayDepth) => View::RayDepth,
        Some(ViewName::RayCount) => View::RayCount,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::settings::Bounded;

    #[test]
    fn fitting_keeps_the_aspect_ratio_inside_the_box() {
        let fit = RenderSettings { fit: Some([Bounded(160), Bounded(120)]), ..RenderSettings::default() };
        assert_eq!(image_size(&fit, 800, 600), Ok((160, 120)));
        assert_eq!(image_size(&fit, 1920, 1080), Ok((160, 90)));
        assert_eq!(image_size(&fit, 512, 512), Ok((120, 120)));
        assert_eq!(image_size(&fit, 80, 60), Ok((160, 120)));
        assert_eq!(image_size(&fit, 10000, 1), Ok((160, 1)));
        assert_eq!(image_size(&RenderSettings::default(), 800, 600), Ok((800, 600)));
    }

    #[test]
    fn one_side_alone_keeps_the_aspect_ratio_as_glint_render_does() {
        let width = RenderSettings { width: Some(Bounded(64)), ..RenderSettings::default() };
        assert_eq!(image_size(&width, 800, 600), Ok((64, 48)));
        let height = RenderSettings { height: Some(Bounded(100)), ..RenderSettings::default() };
        assert_eq!(image_size(&height, 320, 240), Ok((133, 100)));
        let both = RenderSettings { width: Some(Bounded(64)), height: Some(Bounded(64)), ..RenderSettings::default() };
        assert_eq!(image_size(&both, 800, 600), Ok((64, 64)));
        let wide = RenderSettings { height: Some(Bounded(MAX_IMAGE_SIDE)), ..RenderSettings::default() };
        assert!(image_size(&wide, 1000, 10).unwrap_err().contains("set both width and height"));
    }
}
