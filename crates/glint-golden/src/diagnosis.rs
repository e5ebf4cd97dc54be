//! What a failed submission most likely got wrong. Glint renders the case's
//! scene again with one effect of the lecture changed at a time (shadow rays
//! left out, the other highlight model, linear values stored as display
//! bytes, …) and names the variant the submission is closest to, when it is
//! clearly closer to that variant than to the full render. The variants are
//! made once per case and class, at the first submission that fails.

use std::path::Path;

use glint_gpu::{Format, Image, Renderer};
use glint_scene::nff::NffAngle;
use glint_scene::{Projection, Scene, SpecularModel};

use crate::case_render::{load, render_scene};
use crate::image_io::{linear_to_srgb, srgb_to_linear, LinearImage};
use crate::metrics::measure;
use crate::region::{worst_region, Region};
use crate::settings::{Bounded, NffAngleName, RenderSettings};

/// A submission is put down to a variant when its FLIP against the variant
/// is at most this fraction of its FLIP against the full render: clearly
/// nearer, not a toss-up between two wrong images.
const CLEARLY_NEARER: f64 = 0.5;

/// One effect of the lecture, changed the way students get it wrong.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Effect {
    NoShadows,
    NoReflection,
    NoRefraction,
    NoHighlights,
    /// Blinn-Phong's half vector where the scene asks for Phong's mirror
    /// vector, or the reverse.
    OtherHighlightModel,
    /// Linear values written as bytes, with no sRGB encoding.
    LinearAsSrgb,
    /// sRGB-encoded values encoded again.
    SrgbTwice,
    /// The field of view taken between the outer pixels' edges where the
    /// scene means their centres, or the reverse.
    OtherFieldOfView,
    /// Each pixel's ray through its top-left corner, not its centre.
    PixelCorners,
    /// Lighting with the normals the geometry gives, not turned towards the
    /// eye: back faces lit from behind.
    UnturnedNormals,
}

impl Effect {
    pub const ALL: [Effect; 10] = [
        Effect::NoShadows,
        Effect::NoReflection,
        Effect::NoRefraction,
        Effect::NoHighlights,
        Effect::OtherHighlightModel,
        Effect::LinearAsSrgb,
        Effect::SrgbTwice,
        Effect::OtherFieldOfView,
        Effect::PixelCorners,
        Effect::UnturnedNormals,
    ];
}

/// A render of the case's scene with one effect changed.
pub struct Variant {
    pub effect: Effect,
    /// `without shadow rays`: what Glint's render lacks or does otherwise.
    pub what: String,
    /// `check your shadow rays`: where a student should look.
    pub advice: &'static str,
    image: Image,
    /// Where it differs from the full render most.
    region: Region,
}

/// The submission's nearest variant, by how much, and where the variant
/// differs from the full render most.
#[derive(Debug, Clone, PartialEq)]
pub struct Diagnosis {
    pub effect: Effect,
    pub what: String,
    pub advice: &'static str,
    /// Mean FLIP of the submission against the variant.
    pub flip: f64,
    /// Mean FLIP of the submission against the full render.
    pub full_flip: f64,
    pub region: Region,
}

impl Diagnosis {
    /// `closest to Glint's render without shadow rays (flip 0.002, against
    /// 0.155 for the full render; the two differ most in 64x64 at (286, 415)):
    /// check your shadow rays`
    pub fn sentence(&self) -> String {
        format!(
            "closest to Glint's render {} (flip {}, against {} for the full render; the two differ most in {}): {}",
            self.what,
            short(self.flip),
            short(self.full_flip),
            self.region,
            self.advice
        )
    }
}

/// Three decimals, enough to rank a student's distances; smaller values in
/// scientific notation, so they never print as 0.
fn short(v: f64) -> String {
    if v == 0.0 || v >= 1e-3 { format!("{v:.3}") } else { format!("{v:.1e}") }
}

/// The variants of a case's scene that differ from its `reference` render,
/// rendered with the case's `settings`. Effects the scene does not use (no
/// mirrors: no reflection variant) give the reference's pixels and are left
/// out.
pub fn variants(renderer: &Renderer, scene_file: &Path, settings: &RenderSettings, reference: &Image) -> Result<Vec<Variant>, String> {
    let scene = load(scene_file, settings)?;
    let nff_angle = nff_angle_of(scene_file, settings);
    let mut variants = Vec::new();
    for effect in Effect::ALL {
        let (what, advice) = describe(effect, &scene, nff_angle);
        let image = if effect == Effect::PixelCorners {
            through_pixel_corners(renderer, &scene, scene_file, settings, reference.width, reference.height)?
        } else {
            match changed_scene(effect, &scene, scene_file, settings, nff_angle)? {
                Some(changed) => render_scene(renderer, &changed, scene_file, settings)?.image,
                None => match changed_bytes(effect) {
                    Some(change) => with_display_bytes(reference, change),
                    None => continue,
                },
            }
        };
        if image.display != reference.display {
            let region = where_it_shows(&image, reference);
            variants.push(Variant { effect, what, advice, image, region });
        }
    }
    Ok(variants)
}

/// The variant `submitted` (read from a file in `format`) is clearly nearer
/// to than to the full render, `reference` as read back in that format.
pub fn diagnose(submitted: &LinearImage, format: Format, reference: &LinearImage, variants: &[Variant]) -> Option<Diagnosis> {
    if variants.is_empty() {
        return None;
    }
    let full_flip = measure(reference, submitted).ok()?.flip;
    let (variant, flip) = variants
        .iter()
        .filter_map(|v| measure(&LinearImage::from_render(&v.image, format), submitted).ok().map(|m| (v, m.flip)))
        .min_by(|a, b| a.1.total_cmp(&b.1))?;
    if flip > full_flip * CLEARLY_NEARER {
        return None;
    }
    Some(Diagnosis {
        effect: variant.effect,
        what: variant.what.clone(),
        advice: variant.advice,
        flip,
        full_flip,
        region: variant.region,
    })
}

/// Where `variant` differs from the full render most, by display values.
fn where_it_shows(variant: &Image, reference: &Image) -> Region {
    let errors: Vec<f32> = variant.display.iter().zip(&reference.display).map(|(a, b)| (0..3).map(|c| (a[c] - b[c]).abs()).sum()).collect();
    worst_region(&errors, variant.width, variant.height)
}

fn describe(effect: Effect, scene: &Scene, nff_angle: Option<NffAngle>) -> (String, &'static str) {
    let blinn = highlights_are_blinn(scene);
    let (what, advice) = match effect {
        Effect::NoShadows => ("without shadow rays", "check your shadow rays"),
        Effect::NoReflection => ("without reflected rays", "check your reflected rays"),
        Effect::NoRefraction => ("without refracted rays", "check your refracted rays and Snell's law"),
        Effect::NoHighlights => ("without specular highlights", "check your specular term"),
        Effect::OtherHighlightModel if blinn => ("with Phong's mirror vector R·V in place of Blinn-Phong's N·H", "use the half vector H = (L + V)/|L + V|"),
        Effect::OtherHighlightModel => ("with Blinn-Phong's N·H in place of Phong's mirror vector R·V", "use the mirror vector R = 2(N·L)N − L"),
        Effect::LinearAsSrgb => ("with linear values written as bytes (no sRGB encoding)", "encode each channel with the sRGB transfer function before writing it"),
        Effect::SrgbTwice => ("with sRGB encoding applied twice", "encode with sRGB once, just before writing"),
        Effect::OtherFieldOfView => match nff_angle {
            Some(NffAngle::Centers) => ("with the field of view measured edge to edge (NFF's angle runs between the outer pixels' centres)", "check how your view window follows from the angle"),
            _ => ("with the field of view measured between the outer pixels' centres (it runs edge to edge)", "check how your view window follows from the field of view"),
        },
        Effect::PixelCorners => ("with each ray through its pixel's corner, not its centre", "send pixel (i, j)'s ray through (i + 0.5, j + 0.5)"),
        Effect::UnturnedNormals => ("with normals not turned towards the eye (back faces lit from behind)", "turn the normal towards the viewer: when N·D > 0, use −N"),
    };
    (what.to_string(), advice)
}

/// Whether the materials that have highlights mostly use Blinn-Phong: the
/// model the diagnosis names as the one asked for.
fn highlights_are_blinn(scene: &Scene) -> bool {
    let shiny = scene.materials.iter().filter(|m| m.specular > 0.0);
    let blinn = shiny.clone().filter(|m| m.specular_model == SpecularModel::BlinnPhong).count();
    2 * blinn > shiny.count()
}

/// The scene with `effect` changed, or `None` when the effect is not in the
/// scene's description but in how the image is written.
fn changed_scene(effect: Effect, scene: &Scene, scene_file: &Path, settings: &RenderSettings, nff_angle: Option<NffAngle>) -> Result<Option<Scene>, String> {
    let mut changed = scene.clone();
    match effect {
        Effect::NoShadows => changed.render.shadows = false,
        Effect::NoReflection => changed.render.reflections = false,
        Effect::NoRefraction => changed.render.refractions = false,
        Effect::NoHighlights => changed.materials.iter_mut().for_each(|m| m.specular = 0.0),
        Effect::OtherHighlightModel => changed.materials.iter_mut().for_each(|m| {
            m.specular_model = match m.specular_model {
                SpecularModel::Phong => SpecularModel::BlinnPhong,
                SpecularModel::BlinnPhong => SpecularModel::Phong,
            }
        }),
        Effect::OtherFieldOfView => match nff_angle {
            // An NFF angle read the other way.
            Some(angle) => {
                let other = match angle {
                    NffAngle::Centers => NffAngleName::Edges,
                    NffAngle::Edges => NffAngleName::Centers,
                };
                return load(scene_file, &RenderSettings { nff_angle: Some(other), ..settings.clone() }).map(Some);
            }
            None => match &mut changed.camera.projection {
                Projection::Perspective { fov_y_degrees } => *fov_y_degrees = between_centres(*fov_y_degrees, scene.height),
                Projection::Orthographic { .. } => return Ok(None),
            },
        },
        Effect::UnturnedNormals => changed.render.turn_normals = false,
        Effect::LinearAsSrgb | Effect::SrgbTwice | Effect::PixelCorners => return Ok(None),
    }
    Ok(Some(changed))
}

/// Glint's render of `scene` at `width` × `height` with each pixel's ray
/// through its top-left corner, where a student who drops the lecture's
/// + 0.5 sends it: the pixel centres of a render one pixel wider and taller,
/// whose window reaches half a pixel further on every side, are the corners
/// of this one's pixels.
fn through_pixel_corners(renderer: &Renderer, scene: &Scene, scene_file: &Path, settings: &RenderSettings, width: u32, height: u32) -> Result<Image, String> {
    let size = RenderSettings { width: Some(Bounded(width + 1)), height: Some(Bounded(height + 1)), fit: None, ..settings.clone() };
    let image = render_scene(renderer, &half_a_pixel_wider(scene, height), scene_file, &size)?.image;
    Ok(image.crop(glint_image::Region { x0: 0, y0: 0, x1: width, y1: height }))
}

/// `scene` with its view window half a pixel of a `rows`-row image wider on
/// every side.
fn half_a_pixel_wider(scene: &Scene, rows: u32) -> Scene {
    let mut wider = scene.clone();
    let grow = f64::from(rows + 1) / f64::from(rows);
    match &mut wider.camera.projection {
        Projection::Perspective { fov_y_degrees } => *fov_y_degrees = window_grown(*fov_y_degrees, grow),
        Projection::Orthographic { height } => *height = (f64::from(*height) * grow) as f32,
    }
    wider
}

/// The field of view, edge to edge, of a window whose outer pixel centres
/// span `fov` degrees over `rows` rows.
fn between_centres(fov: f32, rows: u32) -> f32 {
    let rows = f64::from(rows.max(2));
    window_grown(fov, rows / (rows - 1.0))
}

/// The field of view, in degrees, of a window `factor` times as tall as
/// that of `fov`, at the same distance.
fn window_grown(fov: f32, factor: f64) -> f32 {
    (2.0 * ((f64::from(fov).to_radians() / 2.0).tan() * factor).atan()).to_degrees() as f32
}

/// How a student's written bytes relate to the right display value `d`.
fn changed_bytes(effect: Effect) -> Option<fn(f32) -> f32> {
    match effect {
        // The linear value srgb⁻¹(d) was written where d belongs.
        Effect::LinearAsSrgb => Some(srgb_to_linear),
        // d was encoded once more.
        Effect::SrgbTwice => Some(linear_to_srgb),
        _ => None,
    }
}

/// The reference with every display value changed as a student's file would
/// hold it; linear values follow, so a float file compares the same way.
fn with_display_bytes(reference: &Image, change: fn(f32) -> f32) -> Image {
    let map = |p: &[f32; 4]| [change(p[0]), change(p[1]), change(p[2]), p[3]];
    let display: Vec<[f32; 4]> = reference.display.iter().map(map).collect();
    let linear = display.iter().map(|p| [srgb_to_linear(p[0]), srgb_to_linear(p[1]), srgb_to_linear(p[2]), p[3]]).collect();
    Image { width: reference.width, height: reference.height, display, linear }
}

/// How the case reads an NFF file's angle, or `None` for a scene that has no
/// NFF angle (TOML, OBJ).
fn nff_angle_of(scene_file: &Path, settings: &RenderSettings) -> Option<NffAngle> {
    let name = scene_file.to_string_lossy();
    let nff = name.starts_with("spd:") || scene_file.extension().is_some_and(|e| e.eq_ignore_ascii_case("nff"));
    nff.then(|| match settings.nff_angle {
        Some(NffAngleName::Edges) => NffAngle::Edges,
        Some(NffAngleName::Centers) | None => NffAngle::Centers,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_window_whose_centres_span_the_angle_is_wider_by_a_pixel() {
        // Two rows whose centres span 90°: the centres sit at ±1 on the
        // window at distance 1, a row apart, so the edges are at ±2.
        assert!((between_centres(90.0, 2) - 2.0 * 2f32.atan().to_degrees()).abs() < 1e-4);
        assert!(between_centres(40.0, 200) > 40.0 && between_centres(40.0, 200) < 40.3);
    }

    #[test]
    fn the_wider_windows_pixel_centres_are_the_pixel_corners() {
        let mut scene = glint_scene::toml_scene::parse("[image]\nwidth = 40\nheight = 30\n[camera]\neye = [1, 2, 5]\nlook_at = [0, 0.5, 0]\nfov = 50\n", Path::new("s.toml")).unwrap();
        for projection in [Projection::Perspective { fov_y_degrees: 50.0 }, Projection::Orthographic { height: 3.0 }] {
            scene.camera.projection = projection;
            let wider = half_a_pixel_wider(&scene, 30);
            for (i, j) in [(0, 0), (39, 0), (17, 29), (39, 29)] {
                let corner = scene.camera.ray(40, 30, f64::from(i), f64::from(j)).unwrap();
                let centre = wider.camera.ray(41, 31, f64::from(i) + 0.5, f64::from(j) + 0.5).unwrap();
                assert!(corner.origin.distance(centre.origin) < 1e-5 && corner.direction.distance(centre.direction) < 1e-6, "{projection:?} ({i}, {j})");
            }
        }
    }

    #[test]
    fn written_bytes_follow_the_mistake() {
        let reference = Image { width: 1, height: 1, display: vec![[0.5, 1.0, 0.0, 1.0]], linear: vec![[0.214, 1.0, 0.0, 1.0]] };
        let linear = with_display_bytes(&reference, srgb_to_linear);
        assert!((linear.display[0][0] - srgb_to_linear(0.5)).abs() < 1e-6 && linear.display[0][1] == 1.0);
        assert!((linear.linear[0][0] - srgb_to_linear(srgb_to_linear(0.5))).abs() < 1e-6);
        let twice = with_display_bytes(&reference, linear_to_srgb);
        assert!(twice.display[0][0] > 0.7);
    }

    #[test]
    fn a_diagnosis_reads_as_advice() {
        let d = Diagnosis {
            effect: Effect::NoShadows,
            what: "without shadow rays".into(),
            advice: "check your shadow rays",
            flip: 0.002,
            full_flip: 0.155,
            region: Region { x: 286, y: 415, width: 64, height: 64 },
        };
        assert_eq!(
            d.sentence(),
            "closest to Glint's render without shadow rays (flip 0.002, against 0.155 for the full render; the two differ most in 64x64 at (286, 415)): check your shadow rays"
        );
    }
}
