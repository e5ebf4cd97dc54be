//! Glint's scene model: the loaders (TOML, NFF, OBJ), camera math,
//! validation and the BVH builder. How the kernels read a scene is
//! glint-encoding's business.

pub mod animation;
pub mod bvh;
mod camera;
pub mod camera_frame;
mod error;
pub mod icosphere;
mod light;
mod material;
pub mod nff;
pub mod opened_files;
pub mod obj;
pub mod polygon_split;
pub mod rayshade;
mod scene;
mod shape;
pub mod spd;
pub mod suggest;
pub mod test_rng;
mod token_reader;
mod toml_errors;
pub mod toml_scene;
pub mod toml_write;
pub mod validate;

pub use animation::Animation;
pub use camera::{Basis, Camera, Projection, Ray};
pub use error::{LoadError, Location};
pub use light::{Attenuation, Light, LightKind};
pub use material::{Checker, Material, SpecularModel};
pub use scene::{DepthCue, Object, RenderSettings, Scene, ShadowMode, MAX_DEPTH_LIMIT, MAX_IMAGE_SIDE, MAX_LIGHTS, MAX_MATERIALS};
pub use shape::{plane_axes, polygon_normal, Shape, ShapeProblem, SHAPE_NAMES};

use std::path::Path;

use glam::Vec3;

use crate::nff::{NffAngle, NffOptions};

/// Why [`read_text`] failed.
#[derive(Debug)]
pub(crate) enum ReadError {
    /// The file could not be read at all; the caller says where it was named.
    Io(std::io::Error),
    /// The file is not UTF-8 text: an error at the first bad byte.
    NotText(LoadError),
}

/// Reads a scene file, or a file a scene names, as text. Bytes that are not
/// UTF-8 (a binary file, a file in another encoding) are a malformed file, and
/// the error names the line and column where the text stops being UTF-8.
pub(crate) fn read_text(path: &Path) -> Result<String, ReadError> {
    let bytes = opened_files::read(path).map_err(ReadError::Io)?;
    String::from_utf8(bytes).map_err(|e| {
        let valid = e.utf8_error().valid_up_to();
        let bytes = e.as_bytes();
        // The prefix is valid UTF-8 by definition.
        let before = std::str::from_utf8(&bytes[..valid]).unwrap_or_default();
        let location = Location::of_offset(before, valid);
        ReadError::NotText(LoadError::new(
            path,
            Some(location),
            format!("not a text file: byte 0x{:02x} is not UTF-8", bytes[valid]),
        ))
    })
}

/// Whether the camera's eye and look-at point are so far apart that the view
/// direction overflows 32-bit floats (its basis would be NaN).
pub(crate) fn view_overflows(camera: &Camera) -> bool {
    !(camera.eye - camera.look_at).is_finite()
}

/// `v` scaled to unit length, or `None` for a zero vector. Computed in f64:
/// in f32 the length of (3e38, 0, 0) overflows and that of (1e-30, 0, 0)
/// underflows, and normalising either gives a zero vector.
pub(crate) fn unit(v: Vec3) -> Option<Vec3> {
    let d = v.as_dvec3();
    let length = d.length();
    (length > 0.0 && length.is_finite()).then(|| (d / length).as_vec3())
}

/// A token of a scene file as it appears in a message: control characters
/// escaped, and cut short when long.
pub(crate) fn quoted(text: &str) -> String {
    const MAX: usize = 40;
    let mut shown = error::escape_controls(&text.chars().take(MAX).collect::<String>());
    if text.chars().nth(MAX).is_some() {
        shown.push('…');
    }
    format!("`{shown}`")
}

/// Options for [`load_with`] that only some formats read.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct LoadOptions {
    /// How an NFF file's `angle` is read (the NFF spec's pixel-centre
    /// convention by default).
    pub nff_angle: NffAngle,
}

/// Loads a scene with default options, choosing the reader by the file's
/// extension: `.toml` (Glint's own format), `.nff`, `.ray` (Rayshade) or `.obj`.
pub fn load(path: &Path) -> Result<Scene, LoadError> {
    load_with(path, &LoadOptions::default())
}

/// Loads a scene, choosing the reader by the file's extension; a name
/// `spd:NAME[:SIZE]` generates one of the Standard Procedural Databases.
pub fn load_with(path: &Path, options: &LoadOptions) -> Result<Scene, LoadError> {
    let nff_options = NffOptions { angle: options.nff_angle };
    if let Some(spec) = spd::spec_of(path) {
        return nff::parse(&spd::generate(path, spec)?, path, &nff_options);
    }
    match path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).as_deref() {
        Some("toml") => toml_scene::load(path),
        Some("nff") => nff::load(path, &nff_options),
        Some("ray") => rayshade::load(path),
        Some("obj") => obj::load(path),
        _ => Err(LoadError::new(
            path,
            None,
            "unknown scene format: expected a .toml, .nff, .ray or .obj file, or spd:NAME",
        )),
    }
}
