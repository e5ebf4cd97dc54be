//! Images read back from the device and written to files atomically.

use std::path::Path;

use crate::GpuError;

/// A rendered image, row 0 at the top.
#[derive(Debug, Clone, PartialEq)]
pub struct Image {
    pub width: u32,
    pub height: u32,
    /// Tone-mapped, sRGB-encoded values in [0, 1].
    pub display: Vec<[f32; 4]>,
    /// Linear radiance (after exposure), for float outputs and tests.
    pub linear: Vec<[f32; 4]>,
}

impl Image {
    pub fn to_rgb8(&self) -> image::RgbImage {
        let q = |v: f32| (v.clamp(0.0, 1.0) * 255.0).round() as u8;
        image::RgbImage::from_fn(self.width, self.height, |x, y| {
            let p = self.display[(y * self.width + x) as usize];
            image::Rgb([q(p[0]), q(p[1]), q(p[2])])
        })
    }

    /// Linear radiance of pixel (x, y).
    pub fn linear_at(&self, x: u32, y: u32) -> [f32; 3] {
        let p = self.linear[(y * self.width + x) as usize];
        [p[0], p[1], p[2]]
    }
}

/// Writes `image` to `path`, choosing the format by extension. The file is
/// written beside its destination under a temporary name and renamed into place,
/// so a failure never leaves a truncated file or harms an existing one.
pub fn write_image(image: &Image, path: &Path) -> Result<(), GpuError> {
    let fail = |e: &dyn std::fmt::Display| GpuError::Output(format!("{}: {e}", path.display()));
    let format = image::ImageFormat::from_path(path).map_err(|e| fail(&e))?;
    if format != image::ImageFormat::Png {
        return Err(fail(&"unsupported output format: use .png"));
    }
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let mut builder = tempfile::Builder::new();
    builder.prefix(".glint-").suffix(".tmp");
    // Temporary files are private by default; the image gets ordinary permissions.
    #[cfg(unix)]
    builder.permissions(std::os::unix::fs::PermissionsExt::from_mode(0o666));
    let mut tmp = builder
        .tempfile_in(dir)
        .map_err(|e| fail(&e))?;
    let mut writer = std::io::BufWriter::new(tmp.as_file_mut());
    image.to_rgb8().write_to(&mut writer, format).map_err(|e| fail(&e))?;
    std::io::Write::flush(&mut writer).map_err(|e| fail(&e))?;
    drop(writer);
    tmp.persist(path).map_err(|e| fail(&e.error))?;
    Ok(())
}
