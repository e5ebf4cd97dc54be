//! Images read back from the device, and writing them to files atomically.

use std::io::Write;
use std::path::Path;

use crate::{ImageError, Region};

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
    /// Display values, 8 or 16 bits per channel, as bytes (P6) or text (P3):
    /// Netpbm's portable pixmap.
    Ppm,
    /// Linear 32-bit float RGB.
    Exr,
    /// Linear 32-bit float RGB, the Portable Float Map.
    Pfm,
}

impl Format {
    pub fn from_path(path: &Path) -> Result<Self, ImageError> {
        match path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).as_deref() {
            Some("png") => Ok(Format::Png),
            Some("ppm") => Ok(Format::Ppm),
            Some("exr") => Ok(Format::Exr),
            Some("pfm") => Ok(Format::Pfm),
            _ => Err(ImageError::Output(format!(
                "{}: unsupported output format: use {}",
                path.display(),
                Format::EXTENSIONS
            ))),
        }
    }

    /// The extensions [`Format::from_path`] knows, in words for messages.
    pub const EXTENSIONS: &'static str = ".png, .ppm, .exr or .pfm";

    /// Whether the file holds display values (sRGB-encoded, as a screen
    /// shows them) rather than linear ones.
    pub fn is_display(self) -> bool {
        matches!(self, Format::Png | Format::Ppm)
    }
}

impl Image {
    /// The display values as an 8-bit PNG or PPM stores them.
    pub fn to_rgb8(&self) -> image::RgbImage {
        image::RgbImage::from_fn(self.width, self.height, |x, y| {
            let p = self.display[(y * self.width + x) as usize];
            image::Rgb([p[0], p[1], p[2]].map(to_u8))
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

    /// Copies `part` into this image with its top-left corner at (`x`, `y`);
    /// it must fit.
    pub fn paste(&mut self, part: &Image, x: u32, y: u32) {
        let (width, row) = (self.width as usize, part.width as usize);
        for (r, (display, linear)) in part.display.chunks_exact(row).zip(part.linear.chunks_exact(row)).enumerate() {
            let start = (y as usize + r) * width + x as usize;
            self.display[start..start + row].copy_from_slice(display);
            self.linear[start..start + row].copy_from_slice(linear);
        }
    }

    /// The part of this image in `part`, which must lie inside it: what
    /// [`paste`](Image::paste) puts back.
    pub fn crop(&self, part: Region) -> Image {
        let at = |x: u32, y: u32| (y * self.width + x) as usize;
        let rows = part.y0..part.y1;
        let display = rows.clone().flat_map(|y| self.display[at(part.x0, y)..at(part.x1, y)].to_vec()).collect();
        let linear = rows.flat_map(|y| self.linear[at(part.x0, y)..at(part.x1, y)].to_vec()).collect();
        Image { width: part.width(), height: part.height(), display, linear }
    }

    /// Replaces the kernel's miss marker in a depth image (or tile) by +∞.
    pub fn with_misses_at_infinity(mut self) -> Self {
        for p in &mut self.linear {
            for c in &mut p[..3] {
                if *c >= glint_encoding::gpu_types::MISS {
                    *c = f32::INFINITY;
                }
            }
        }
        self
    }
}

/// A display value in [0, 1] as an 8-bit sample.
pub(crate) fn to_u8(v: f32) -> u8 {
    (v.clamp(0.0, 1.0) * 255.0).round() as u8
}

/// A display value in [0, 1] as a 16-bit sample.
pub(crate) fn to_u16(v: f32) -> u16 {
    (v.clamp(0.0, 1.0) * 65535.0).round() as u16
}

/// Bits per channel of PNG and PPM output.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Bits {
    #[default]
    Eight,
    Sixteen,
}

/// How a PNG or PPM file stores display values.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Samples {
    pub bits: Bits,
    /// For a PPM: bytes (`P6`) or text (`P3`).
    pub ppm: PpmForm,
}

impl From<Bits> for Samples {
    fn from(bits: Bits) -> Self {
        Samples { bits, ppm: PpmForm::Raw }
    }
}

/// How a PPM stores its samples.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum PpmForm {
    /// `P6`: one or two bytes a sample.
    #[default]
    Raw,
    /// `P3`: decimal text, as Netpbm's `-plain` writes it.
    Plain,
}

/// What an image's linear values are, which decides how many channels a
/// float file gets.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Channels {
    /// Colour (radiance, albedo, normals): three channels, R, G and B.
    #[default]
    Rgb,
    /// One number per pixel (depth, object id, nodes visited), the first
    /// linear channel: a greyscale PFM (`Pf`), and an EXR with the one
    /// channel named here. PNG and PPM output are unaffected.
    Single(&'static str),
}

/// Checks, before any work, that an image can be written to `path`: its
/// format is known, its directory exists and a file can be created there, and
/// it is not itself a directory. Leaves nothing behind.
pub fn check_output_path(path: &Path) -> Result<Format, OutputPathError> {
    let format = Format::from_path(path).map_err(|e| OutputPathError::Format(e.to_string()))?;
    let shown = path.display();
    let dir = parent_dir(path);
    if path.is_dir() {
        return Err(OutputPathError::Unwritable(format!("{shown}: is a directory, not a file name")));
    }
    if !dir.is_dir() {
        let what = if dir.exists() { "is not a directory" } else { "does not exist" };
        return Err(OutputPathError::Unwritable(format!("{shown}: cannot write there: the directory `{}` {what}", dir.display())));
    }
    temp_beside(path)
        .map_err(|e| OutputPathError::Unwritable(format!("{shown}: cannot write in the directory `{}`: {e}", dir.display())))?;
    Ok(format)
}

/// Why [`check_output_path`] refused a path.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum OutputPathError {
    /// An extension Glint does not write.
    Format(String),
    /// The file cannot be created.
    Unwritable(String),
}

impl std::fmt::Display for OutputPathError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            OutputPathError::Format(m) | OutputPathError::Unwritable(m) => f.write_str(m),
        }
    }
}

/// Writes `bytes` beside `path` under a temporary name and renames the file into
/// place, so a failure never leaves a truncated file or harms an existing one.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let mut tmp = temp_beside(path)?;
    tmp.write_all(bytes)?;
    tmp.as_file().sync_all()?;
    tmp.persist(path).map_err(|e| e.error)?;
    Ok(())
}

/// A new file beside `path` under a temporary name, removed when dropped
/// unless persisted: the same directory, so renaming it to `path` is atomic.
pub(crate) fn temp_beside(path: &Path) -> std::io::Result<tempfile::NamedTempFile> {
    let mut builder = tempfile::Builder::new();
    builder.prefix(".glint-").suffix(".tmp");
    // Temporary files are private by default; the result gets ordinary permissions.
    #[cfg(unix)]
    builder.permissions(std::os::unix::fs::PermissionsExt::from_mode(0o666));
    builder.tempfile_in(parent_dir(path))
}

/// The directory `path` is in, `.` for a bare file name.
fn parent_dir(path: &Path) -> &Path {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

/// Reads a PFM, colour (`PF`) or greyscale (`Pf`), little- or big-endian:
/// (width, height, channels per pixel, values row by row, top row first).
pub fn read_pfm_channels(bytes: &[u8]) -> Result<(u32, u32, usize, Vec<f32>), String> {
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
    let channels = match fields[0].as_str() {
        "PF" => 3,
        "Pf" => 1,
        other => return Err(format!("not a PFM: {other}")),
    };
    let width: u32 = fields[1].parse().map_err(|_| "bad PFM width")?;
    let height: u32 = fields[2].parse().map_err(|_| "bad PFM height")?;
    let little = fields[3].parse::<f32>().map_err(|_| "bad PFM scale")? < 0.0;
    let row = width as usize * channels;
    let count = row * height as usize;
    let data = bytes.get(pos..pos + count * 4).ok_or("truncated PFM data")?;
    let floats: Vec<f32> = data
        .chunks_exact(4)
        .map(|b| {
            let b = [b[0], b[1], b[2], b[3]];
            if little { f32::from_le_bytes(b) } else { f32::from_be_bytes(b) }
        })
        .collect();
    let values = floats.chunks_exact(row.max(1)).rev().flatten().copied().collect();
    Ok((width, height, channels, values))
}

/// Reads an EXR's first layer: (width, height, each channel's name and values
/// row by row, top row first), as `glint render` writes them (R, G and B, or
/// one named channel).
pub fn read_exr_channels(bytes: &[u8]) -> Result<(u32, u32, Vec<(String, Vec<f32>)>), String> {
    use exr::prelude::{ReadChannels, ReadLayers};
    let read = exr::prelude::read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .first_valid_layer()
        .all_attributes()
        .from_buffered(std::io::Cursor::new(bytes))
        .map_err(|e| format!("not a readable EXR: {e}"))?;
    let layer = read.layer_data;
    let channels = layer.channel_data.list.iter().map(|c| (c.name.to_string(), c.sample_data.values_as_f32().collect())).collect();
    Ok((layer.size.width() as u32, layer.size.height() as u32, channels))
}

/// Reads a PFM as colour: a greyscale file's value fills all three channels.
/// (width, height, rgb rows top first).
pub fn read_pfm(bytes: &[u8]) -> Result<(u32, u32, Vec<[f32; 3]>), String> {
    let (width, height, channels, values) = read_pfm_channels(bytes)?;
    let rgb = if channels == 1 {
        values.iter().map(|&v| [v; 3]).collect()
    } else {
        values.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect()
    };
    Ok((width, height, rgb))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_crop_is_the_part_paste_puts_back() {
        let pixels = |w: u32, h: u32| (0..w * h).map(|i| [i as f32, 0.0, 0.0, 1.0]).collect::<Vec<_>>();
        let image = Image { width: 4, height: 3, display: pixels(4, 3), linear: pixels(4, 3) };
        let corner = image.crop(Region { x0: 0, y0: 0, x1: 3, y1: 2 });
        assert_eq!((corner.width, corner.height), (3, 2));
        assert_eq!(corner.display.iter().map(|p| p[0]).collect::<Vec<_>>(), [0.0, 1.0, 2.0, 4.0, 5.0, 6.0]);
        assert_eq!(corner.linear, corner.display);
        let mut back = image.clone();
        back.paste(&image.crop(Region { x0: 1, y0: 1, x1: 4, y1: 3 }), 1, 1);
        assert_eq!(back, image);
    }

    #[test]
    fn output_paths_are_checked_without_leaving_files() {
        let dir = tempfile::tempdir().unwrap();
        assert_eq!(check_output_path(&dir.path().join("a.png")), Ok(Format::Png));
        assert_eq!(check_output_path(&dir.path().join("a.PPM")), Ok(Format::Ppm));
        assert!(matches!(check_output_path(&dir.path().join("a.bmp")), Err(OutputPathError::Format(_))));
        let e = check_output_path(&dir.path().join("nodir/a.png")).unwrap_err().to_string();
        assert!(e.contains("a.png") && e.contains("does not exist"), "{e}");
        std::fs::write(dir.path().join("file"), b"").unwrap();
        let e = check_output_path(&dir.path().join("file/a.png")).unwrap_err().to_string();
        assert!(e.contains("is not a directory"), "{e}");
        std::fs::create_dir(dir.path().join("d.png")).unwrap();
        let e = check_output_path(&dir.path().join("d.png")).unwrap_err().to_string();
        assert!(e.contains("is a directory"), "{e}");
        let left: Vec<_> = std::fs::read_dir(dir.path()).unwrap().map(|e| e.unwrap().file_name()).collect();
        assert_eq!(left.len(), 2, "only the file and the directory made here: {left:?}");
    }
}
