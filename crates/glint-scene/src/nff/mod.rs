//! Eric Haines' Neutral File Format (NFF), as written by the Standard Procedural
//! Databases (SPD).
//!
//! The file is read as a stream of whitespace-separated tokens, not lines (the
//! SPD generators write `c` on one line, the NFF spec shows it on three), but
//! every token remembers its line and column so that errors name the place.
//! `#` starts a comment that runs to the end of its line.
//!
//! | keyword | operands | becomes |
//! |---|---|---|
//! | `v` | `from x y z`, `at x y z`, `up x y z`, `angle a`, `hither h`, `resolution w h` | camera and image size (see [`fov_y_from_angle`]); `hither` is checked and then ignored: the scene model has no near plane |
//! | `b` | `r g b` | background colour |
//! | `l` | `x y z [r g b]` | a point light (see [`light_intensity`]) |
//! | `f` | `r g b Kd Ks Shine T ior` | the current material (see [`material`]) |
//! | `c` | `bx by bz br ax ay az ar` | an open cone or cylinder, no caps |
//! | `s` | `x y z r` | a sphere |
//! | `p` | `n` then n vertices | a planar polygon, convex or concave, kept whole |
//! | `pp` | `n` then n × (vertex, normal) | a smooth-shaded triangle (n = 3) or a fan of them |
//!
//! Every primitive becomes one [`Object`] (a `pp` fan is one object with several
//! triangles). Malformed input is an error naming file, line and column; each
//! primitive is built by the constructors of [`Shape`], whose policy for
//! degenerate and non-planar shapes every format shares (see [`crate::shape`]).

use std::path::Path;

use glam::Vec3;

mod parse;
#[cfg(test)]
mod tests;

pub use parse::parse_contents;

use crate::{Camera, Light, LoadError, Location, Material, Object, RenderSettings, Scene, SpecularModel};

/// How to read the `angle` of the `v` block.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum NffAngle {
    /// The NFF spec: `angle` spans from the centre of the top pixel row to the
    /// centre of the bottom row (and left to right column).
    #[default]
    Centers,
    /// `angle` spans from the top edge of the image to the bottom edge, as many
    /// renderers read it.
    Edges,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct NffOptions {
    pub angle: NffAngle,
}

/// Converts NFF's `angle` (degrees) into the scene model's vertical,
/// edge-to-edge field of view (degrees) for an image `height` pixels tall.
///
/// With [`NffAngle::Centers`] the angle spans the centres of the outer pixel
/// rows, which lie (H − 1)/2 pixels from the image centre, while the image edge
/// lies H/2 pixels away, so
///
/// ```text
/// tan(fov_edge / 2) = tan(angle / 2) · H / (H − 1)
/// ```
///
/// with H the number of rows (for a non-square image the vertical count is used
/// and pixels are square, so the horizontal extent follows from the aspect
/// ratio). [`NffAngle::Edges`] returns `angle` unchanged. `None` when the
/// centre convention meets a one-row image (both centres coincide).
pub fn fov_y_from_angle(angle_degrees: f64, height: u32, convention: NffAngle) -> Option<f64> {
    match convention {
        NffAngle::Edges => Some(angle_degrees),
        NffAngle::Centers if height < 2 => None,
        NffAngle::Centers => {
            let h = f64::from(height);
            let t = (angle_degrees.to_radians() / 2.0).tan() * h / (h - 1.0);
            Some(2.0 * t.atan().to_degrees())
        }
    }
}

/// NFF leaves light intensity open. Glint follows SPD's Readme: with `n`
/// lights, each light and the ambient light have intensity √n / (2n), which
/// keeps a scene about as bright whether it has one light or many.
pub fn light_intensity(light_count: usize) -> f32 {
    let n = light_count.max(1) as f32;
    n.sqrt() / (2.0 * n)
}

/// The material of an NFF `f r g b Kd Ks Shine T index_of_refraction` line:
///
/// * colour O_d = (r, g, b), k_d = Kd, and k_a = Kd (SPD asks for an ambient
///   term on every object; NFF has no coefficient of its own for it);
/// * highlights k_s = Ks, white (O_s unset), Phong exponent n = Shine, with the
///   Phong (R·V) model, the NFF/SPD convention;
/// * mirror reflectance k_m = Ks (grey), transmittance k_t = T (grey), and the
///   index of refraction `ior` (an ior ≤ 0 on an opaque material, as some SPD
///   files write, is read as 1);
/// * a transmitter also reflects, by Schlick's Fresnel term: a classic tracer
///   spawns a reflection ray wherever it spawns a refraction ray, and SPD's ray
///   counts assume it (gears' glass has Ks = 0 and would otherwise not reflect).
pub fn material(name: String, color: Vec3, kd: f32, ks: f32, shine: f32, t: f32, ior: f32) -> Material {
    Material {
        name,
        ambient: kd,
        diffuse: kd,
        specular: ks,
        shininess: shine,
        color,
        specular_color: None,
        specular_model: SpecularModel::Phong,
        metallic_f0: None,
        reflect: Vec3::splat(ks),
        transmit: Vec3::splat(t),
        ior: if ior > 0.0 { ior } else { 1.0 },
        fresnel: t > 0.0,
        checker: None,
    }
}

/// Reads an NFF file into a scene.
pub fn load(path: &Path, options: &NffOptions) -> Result<Scene, LoadError> {
    let source = crate::read_text(path).map_err(|e| match e {
        crate::ReadError::Io(e) => LoadError::new(path, None, format!("cannot read NFF file: {e}")),
        crate::ReadError::NotText(e) => e,
    })?;
    parse(&source, path, options)
}

/// Parses NFF text; `path` names the file in errors and warnings.
pub fn parse(source: &str, path: &Path, options: &NffOptions) -> Result<Scene, LoadError> {
    let contents = parse_contents(source, path, options)?;
    let Some(view) = contents.view else {
        // Named at the end of the file, where the reader gave up looking.
        let last_line = source.lines().count().max(1);
        return Err(LoadError::new(
            path,
            Some(Location::line(last_line)),
            "no viewpoint: an NFF scene needs a `v` block (none found by the end of the file)",
        ));
    };
    Ok(Scene {
        width: view.width,
        height: view.height,
        background: contents.background.unwrap_or(Vec3::ZERO),
        camera: view.camera,
        ambient: Vec3::splat(light_intensity(contents.lights.len())),
        lights: contents.lights,
        materials: contents.materials,
        objects: contents.objects,
        depth_cue: None,
        render: RenderSettings::default(),
        animation: None,
        warnings: contents.warnings,
    })
}

/// The viewpoint of an NFF file.
#[derive(Debug, Clone, PartialEq)]
pub struct NffView {
    pub camera: Camera,
    pub width: u32,
    pub height: u32,
    /// The `hither` distance; the scene model has no near plane, so only
    /// callers that want it look at it.
    pub hither: Option<f32>,
}

/// Everything an NFF file holds, before it becomes a scene; the TOML loader's
/// `[[include]]` merges these into a TOML scene. Objects index `materials`.
#[derive(Debug, Clone, PartialEq)]
pub struct NffContents {
    pub view: Option<NffView>,
    pub background: Option<Vec3>,
    pub lights: Vec<Light>,
    pub materials: Vec<Material>,
    pub objects: Vec<Object>,
    pub warnings: Vec<LoadError>,
}
