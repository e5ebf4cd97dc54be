//! Glint's scene model and everything that needs no GPU: the loaders (TOML, NFF,
//! OBJ), camera math, the BVH builder and the packing of a scene into the plain
//! arrays the WGSL kernels read.

pub mod bvh;
pub mod camera;
pub mod error;
pub mod gpu_types;
pub mod light;
pub mod material;
pub mod nff;
pub mod obj;
pub mod scene;
pub mod shape;
pub mod toml_scene;

pub use camera::{Camera, Projection};
pub use error::{LoadError, Location};
pub use light::{Attenuation, Light, LightKind};
pub use material::{Material, SpecularModel};
pub use nff::{NffAngle, NffOptions};
pub use scene::{DepthCue, Object, RenderSettings, Scene, ShadowMode};
pub use shape::Shape;

use std::path::Path;

/// Options for [`load_with`] that only some formats read.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct LoadOptions {
    /// How an NFF file's `angle` is read (the NFF spec's pixel-centre
    /// convention by default).
    pub nff_angle: NffAngle,
}

/// Loads a scene with default options, choosing the reader by the file's
/// extension: `.toml` (Glint's own format), `.nff` or `.obj`.
pub fn load(path: &Path) -> Result<Scene, LoadError> {
    load_with(path, &LoadOptions::default())
}

/// Loads a scene, choosing the reader by the file's extension.
pub fn load_with(path: &Path, options: &LoadOptions) -> Result<Scene, LoadError> {
    match path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).as_deref() {
        Some("toml") => toml_scene::load(path),
        Some("nff") => nff::load(path, &NffOptions { angle: options.nff_angle }),
        Some("obj") => obj::load(path),
        _ => Err(LoadError::new(
            path,
            None,
            "unknown scene format: expected a .toml, .nff or .obj file",
        )),
    }
}
