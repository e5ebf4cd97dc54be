//! Images read back from the device, and writing them to files atomically.

use std::io::Write;
use std::path::Path;

use crate::GpuError;

/// A rendered image, row 0 at the top.
#[derive(Debug, Clone, PartialEq)]
pub struct Image {
    pub width: u32,
    pub height: u32,
    /// Tone-mapped, display-encoded values in [0, 1].
    pub display: Vec<[f32; 4]>,
    /// Linear radiance (after exposure), or the raw values of a data view.
    pub linear: Vec<[f32; 4]>,
}

/// The file formats Glint writes, chosen by extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// Display values, 8 or 16 bits per channel.
    Png,
    /// Linear 32-bit float RGB.
    Exr,
    /// Linear 32-bit float RGB, the Portable Float Map.
    Pfm,
}

impl Format {
    pub fn from_path(path: &Path) -> Result<Self, GpuError> {
        match path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).as_deref() {
            Some("png") => Ok(Format::Png),
            Some("exr") => Ok(Format::Exr),
            Some("pfm") => Ok(Format::Pfm),
            _ => Err(GpuError::Output(format!(
                "{}: unsupported output format: use .png, .exr or .pfm",
                path.display()
            ))),
        }
    }
}

impl Image {
    pub fn to_rgb8(&self) -> image::RgbImage {
        image::RgbImage::from_fn(self.width, self.height, |x, y| {
            let p = self.display[(y * self.width + x) as usize];
            image::Rgb([0, 1, 2].map(|c| (p[c].clamp(0.0, 1.0) * 255.0).round() as u8))
        })
    }

    fn to_rgb16(&self) -> image::ImageBuffer<image::Rgb<u16>, Vec<u16>> {
        image::ImageBuffer::from_fn(self.width, self.height, |x, y| {
            let p = self.display[(y * self.width + x) as usize];
            image::Rgb([0, 1, 2].map(|c| (p[c].clamp(0.0, 1.0) * 65535.0).round() as u16))
        })
    }

    fn to_rgb32f(&self) -> image::Rgb32FImage {
        image::Rgb32FImage::from_fn(self.width, self.height, |x, y| {
            let p = self.linear[(y * self.width + x) as usize];
            image::Rgb([p[0], p[1], p[2]])
        })
    }

    /// Linear value of pixel (x, y).
    pub fn linear_at(&self, x: u32, y: u32) -> [f32; 3] {
        let p = self.linear[(y * self.width + x) as usize];
        [p[0], p[1], p[2]]
    }

    /// Display value of pixel (x, y), in [0, 1].
    pub fn display_at(&self, x: u32, y: u32) -> [f32; 3] {
        let p = self.display[(y * self.width + x) as usize];
        [p[0], p[1], p[2]]
    }

    /// Replaces the kernel's miss marker in a depth image by +∞.
    pub fn with_misses_at_infinity(mut self) -> Self {
        for p in &mut self.linear {
            for c in &mut p[..3] {
                if *c >= glint_scene::gpu_types::MISS {
                    *c = f32::INFINITY;
                }
            }
        }
        self
    }
}

/// Bits per channel of PNG output.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum PngBits {
    #[default]
    Eight,
    Sixteen,
}

/// Writes `image` to `path` in the format its extension names, atomically
/// (see [`write_atomically`]).
pub fn write_image(image: &Image, path: &Path, bits: PngBits) -> Result<(), GpuError> {
    let format = Format::from_path(path)?;
    let fail = |e: &dyn std::fmt::Display| GpuError::Output(format!("{}: {e}", path.display()));
    let mut bytes = std::io::Cursor::new(Vec::new());
    match (format, bits) {
        (Format::Png, PngBits::Eight) => image.to_rgb8().write_to(&mut bytes, image::ImageFormat::Png),
        (Format::Png, PngBits::Sixteen) => image.to_rgb16().write_to(&mut bytes, image::ImageFormat::Png),
        (Format::Exr, _) => image.to_rgb32f().write_to(&mut bytes, image::ImageFormat::OpenExr),
        (Format::Pfm, _) => write_pfm(image, &mut bytes).map_err(image::ImageError::IoError),
    }
    .map_err(|e| fail(&e))?;
    write_atomically(path, bytes.get_ref()).map_err(|e| fail(&e))
}

/// Writes `bytes` beside `path` under a temporary name and renames the file into
/// place, so a failure never leaves a truncated file or harms an existing one.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let mut builder = tempfile::Builder::new();
    builder.prefix(".glint-").suffix(".tmp");
    // Temporary files are private by default; the result gets ordinary permissions.
    #[cfg(unix)]
    builder.permissions(std::os::unix::fs::PermissionsExt::from_mode(0o666));
    let mut tmp = builder.tempfile_in(dir)?;
    tmp.write_all(bytes)?;
    tmp.as_file().sync_all()?;
    tmp.persist(path).map_err(|e| e.error)?;
    Ok(())
}

/// PFM: a text header, then little-endian floats, rows from the bottom up.
fn write_pfm(image: &Image, w: &mut impl Write) -> std::io::Result<()> {
    write!(w, "PF\n{} {}\n-1.0\n", image.width, image.height)?;
    for y in (0..image.height).rev() {
        for x in 0..image.width {
            for c in image.linear_at(x, y) {
                w.write_all(&c.to_le_bytes())?;
            }
        }
    }
    Ok(())
}

/// Reads a colour PFM written by `write_pfm` (or any little- or big-endian `PF`
/// file): (width, height, rgb rows top first).
pub fn read_pfm(bytes: &[u8]) -> Result<(u32, u32, Vec<[f32; 3]>), String> {
    let mut fields = Vec::new();
    let mut pos = 0;
    while fields.len() < 4 {
        while pos < bytes.len() && bytes[pos].is_ascii_whitespace() {
            pos += 1;
        }
        let start = pos;
        while pos < bytes.len() && !bytes[pos].is_ascii_whitespace() {
            pos += 1;
        }
        if start == pos {
            return Err("truncated PFM header".into());
        }
        fields.push(std::str::from_utf8(&bytes[start..pos]).map_err(|e| e.to_string())?.to_string());
    }
    pos += 1; // the single whitespace byte after the scale
    if fields[0] != "PF" {
        return Err(format!("not a colour PFM: {}", fields[0]));
    }
    let width: u32 = fields[1].parse().map_err(|_| "bad PFM width")?;
    let height: u32 = fields[2].parse().map_err(|_| "bad PFM height")?;
    let little = fields[3].parse::<f32>().map_err(|_| "bad PFM scale")? < 0.0;
    let count = width as usize * height as usize * 3;
    let data = bytes.get(pos..pos + count * 4).ok_or("truncated PFM data")?;
    let floats: Vec<f32> = data
        .chunks_exact(4)
        .map(|b| {
            let b = [b[0], b[1], b[2], b[3]];
            if little { f32::from_le_bytes(b) } else { f32::from_be_bytes(b) }
        })
        .collect();
    let mut rows = Vec::with_capacity(count / 3);
    for y in (0..height as usize).rev() {
        for x in 0..width as usize {
            let i = (y * width as usize + x) * 3;
            rows.push([floats[i], floats[i + 1], floats[i + 2]]);
        }
    }
    Ok((width, height, rows))
}
