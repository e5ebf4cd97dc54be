//! Glint's GPU host: picks a device, composes and validates the WGSL kernels,
//! uploads a packed scene, dispatches the trace kernel in tiles, resolves the
//! accumulated samples and reads the image back.
//!
//! The modules that are a subsystem of their own are public (`shaders`,
//! `interactive`, `probe`, `display`, `schedule`, `kernel_dump`), and
//! `lavapipe`'s names and measures, for tests of what Glint asks of it; the
//! host pipeline's types are used from the crate root. Image files are
//! `glint-image`'s, re-exported here for the front ends that render them.
//! Front ends describe their work (`Workload`); the driver's environment and
//! the kernels' tuning are this crate's alone to choose.

mod depth_extent;
mod device;
mod error_scope;
pub mod display;
mod eye_tiles;
mod frame;
mod kernel;
pub mod interactive;
pub mod kernel_dump;
pub mod lavapipe;
mod pipelines;
pub mod primitive_dispatch;
pub mod probe;
mod profile;
mod readback;
mod renderer;
mod scene_textures;
pub mod schedule;
pub mod shaders;
mod tuning;
mod workload;

pub use device::{adapter_rank, backends, device_descriptor, driver_warning, Gpu, SceneLimits, ADAPTER_ENV, NO_ADAPTER_HINT};
pub use lavapipe::RenderedScenes;
pub use profile::{CompiledKernels, DeviceProfile, ProfileName, PACKET_EYE_RAYS, PROFILE_ENV};
pub use glint_encoding::eye_tiles::Footprints;
pub use tuning::{StandIn, Tuning, WorkgroupSizes, STAND_INS};
pub use workload::Workload;
pub use frame::{Acceleration, Prepared};
pub use glint_image::{
    check_output_path, read_exr_channels, read_pfm, read_pfm_channels, read_ppm, stitch, write_atomically, write_image, write_image_channels, Bits,
    Channels, Format, Image, ImageSink, OutputPathError, Ppm, PpmForm, Region, Samples, StagedImage,
};
pub use glint_encoding::RayStats;
pub use readback::Readback;
pub use renderer::{RenderOptions, Renderer, SceneBuffers, ToneMap};

/// Everything that can go wrong on the GPU side, one line each.
#[derive(Debug, thiserror::Error)]
pub enum GpuError {
    #[error("{0}")]
    NoAdapter(String),
    /// `GLINT_PROFILE` names no profile.
    #[error("{0}")]
    Profile(String),
    #[error("cannot open the GPU device: {0}")]
    Device(String),
    #[error("shader error: {0}")]
    Shader(String),
    #[error("the scene needs {need} bytes for {what}, but the device's {limit} is {have}")]
    Limit { what: String, limit: &'static str, need: u64, have: u64 },
    #[error("GPU error: {0}")]
    Runtime(String),
    /// A region to render that is not part of the image, or an interactive
    /// use of a scene whose image the device holds only in tiles.
    #[error("{0}")]
    Region(String),
    /// Parts that cannot be read or do not make one image.
    #[error("{0}")]
    Stitch(String),
    #[error("{0}")]
    Output(String),
    #[error("the scene cannot be rendered: {0}")]
    Invalid(#[from] glint_scene::validate::Invalid),
}

/// An error and its causes on one line (wgpu's own display spans several).
pub(crate) fn one_line(e: &dyn std::error::Error) -> String {
    let mut text = e.to_string();
    let mut source = e.source();
    while let Some(cause) = source {
        text.push_str(": ");
        text.push_str(&cause.to_string());
        source = cause.source();
    }
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}

impl From<glint_image::ImageError> for GpuError {
    fn from(e: glint_image::ImageError) -> Self {
        match e {
            glint_image::ImageError::Output(m) => GpuError::Output(m),
            glint_image::ImageError::Stitch(m) => GpuError::Stitch(m),
        }
    }
}
