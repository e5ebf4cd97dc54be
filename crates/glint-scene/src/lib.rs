//! Glint's scene model and everything that needs no GPU: the loaders (TOML, NFF,
//! OBJ), camera math, the BVH builder and the packing of a scene into the plain
//! arrays the WGSL kernels read.

pub mod bvh;
pub mod camera;
pub mod error;
pub mod gpu_types;
pub mod light;
pub mod material;
pub mod scene;
pub mod shape;
pub mod toml_scene;

pub use camera::{Camera, Projection};
pub use error::{LoadError, Location};
pub use light::{Attenuation, Light, LightKind};
pub use material::{Material, SpecularModel};
pub use scene::{DepthCue, Object, RenderSettings, Scene, ShadowMode};
pub use shape::Shape;

use std::path::Path;

/// Loads a scene, choosing the reader by the file's extension.
pub fn load(path: &Path) -> Result<Scene, LoadError> {
    match path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).as_deref() {
        Some("toml") => toml_scene::load(path),
        _ => Err(LoadError::new(
            path,
            None,
            "unknown scene format: expected a .toml file",
        )),
    }
}
