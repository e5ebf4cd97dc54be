//! Glint's image files, with no GPU: the formats it writes and reads (PNG,
//! PPM, EXR, PFM), the regions and tiles of an image, writing a file tile by
//! tile as a render reads them back (`ImageSink`), and stitching parts
//! rendered apart (`stitch`). The GPU host writes through it, and the golden
//! runner and grading read through it without a device.

mod output;
mod ppm;
mod region;
mod sink;
pub mod stitch;

pub use output::{
    check_output_path, read_exr_channels, read_pfm, read_pfm_channels, write_atomically, Bits, Channels, Format, Image, OutputPathError, PpmForm,
    Samples,
};
pub use ppm::{read_ppm, Ppm};
pub use region::Region;
pub use sink::{write_image, write_image_channels, ImageSink, StagedImage};

/// What can go wrong with an image file, one line each.
#[derive(Debug, thiserror::Error)]
pub enum ImageError {
    /// A file that cannot be written.
    #[error("{0}")]
    Output(String),
    /// Parts that cannot be read or do not make one image.
    #[error("{0}")]
    Stitch(String),
}

#[cfg(test)]
mod tests {
    /// Image files need no device: no GPU crate is a dependency (nor one of
    /// glint-scene's or glint-encoding's, which their own rules forbid).
    #[test]
    fn no_gpu_crate_is_a_dependency() {
        let manifest = include_str!("../Cargo.toml");
        for name in ["wgpu", "naga", "glint-gpu", "egui", "eframe"] {
            assert!(!manifest.lines().any(|l| l.trim_start().starts_with(name)), "glint-image depends on {name}");
        }
    }
}
