//! Images as they are compared: linear RGB in f32, whichever file they came
//! from. PNG and PPM hold display values, so they are decoded from sRGB; EXR and PFM
//! already hold linear radiance. Comparing in one space is what lets a PNG be
//! checked against an EXR of the same render.

use std::path::{Path, PathBuf};

use glint_image::Format;

/// Linear RGB pixels, row 0 at the top.
#[derive(Debug, Clone, PartialEq)]
pub struct LinearImage {
    pub width: u32,
    pub height: u32,
    pub pixels: Vec<[f32; 3]>,
}

/// An image file that cannot be read: the file and what is wrong with it.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{}: {message}", path.display())]
pub struct ReadError {
    pub path: PathBuf,
    pub message: String,
}

impl ReadError {
    fn new(path: &Path, message: impl Into<String>) -> Self {
        Self { path: path.to_path_buf(), message: message.into().replace('\n', " ") }
    }
}

/// The image formats Glint compares, chosen by extension like the ones it writes.
pub fn format_of(path: &Path) -> Option<Format> {
    Format::from_path(path).ok()
}

/// Reads a .png, .ppm, .exr or .pfm file as linear RGB.
pub fn read(path: &Path) -> Result<LinearImage, ReadError> {
    let format = format_of(path).ok_or_else(|| ReadError::new(path, format!("unsupported image format: use {}", Format::EXTENSIONS)))?;
    let bytes = std::fs::read(path).map_err(|e| ReadError::new(path, format!("cannot read: {e}")))?;
    let image = decode(&bytes, format).map_err(|message| ReadError::new(path, message))?;
    if image.pixels.is_empty() {
        // No metric has a value over no pixels.
        return Err(ReadError::new(path, "the image has no pixels"));
    }
    Ok(image)
}

fn decode(bytes: &[u8], format: Format) -> Result<LinearImage, String> {
    let decoded = |kind| image::load_from_memory_with_format(bytes, kind).map_err(|e| format!("not a readable image: {e}"));
    match format {
        Format::Png => Ok(from_rgb32f(decoded(image::ImageFormat::Png)?.to_rgb32f(), srgb_to_linear)),
        Format::Exr => match decoded(image::ImageFormat::OpenExr) {
            Ok(rgb) => Ok(from_rgb32f(rgb.to_rgb32f(), |c| c)),
            // The image crate reads only RGB(A) EXRs.
            Err(e) => single_channel_exr(bytes).ok_or(e),
        },
        Format::Ppm => {
            let ppm = glint_image::read_ppm(bytes)?;
            let pixels = ppm.display_values().map(srgb_to_linear).collect::<Vec<_>>().chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
            Ok(LinearImage { width: ppm.width, height: ppm.height, pixels })
        }
        Format::Pfm => {
            let (width, height, pixels) = glint_image::read_pfm(bytes)?;
            Ok(LinearImage { width, height, pixels })
        }
    }
}

/// An EXR with one channel, such as `glint render` writes for the views that
/// are one number per pixel (depth, id, heatmap): that number in R, G and B,
/// as a greyscale PFM reads.
fn single_channel_exr(bytes: &[u8]) -> Option<LinearImage> {
    let (width, height, channels) = glint_image::read_exr_channels(bytes).ok()?;
    let [(_, values)] = &channels[..] else { return None };
    Some(LinearImage { width, height, pixels: values.iter().map(|&v| [v; 3]).collect() })
}

fn from_rgb32f(rgb: image::Rgb32FImage, to_linear: fn(f32) -> f32) -> LinearImage {
    let (width, height) = rgb.dimensions();
    let pixels = rgb.pixels().map(|p| p.0.map(to_linear)).collect();
    LinearImage { width, height, pixels }
}

impl LinearImage {
    /// A render as it reads back once written in `format`: PNG and PPM store
    /// the display values at 8 bits, EXR and PFM the linear values exactly. A
    /// render compared this way gives the same numbers as its file would.
    pub fn from_render(image: &glint_image::Image, format: Format) -> Self {
        let pixels = match format {
            Format::Png | Format::Ppm => image.to_rgb8().pixels().map(|p| p.0.map(|c| srgb_to_linear(f32::from(c) / 255.0))).collect(),
            Format::Exr | Format::Pfm => image.linear.iter().map(|p| [p[0], p[1], p[2]]).collect(),
        };
        Self { width: image.width, height: image.height, pixels }
    }

    /// The pixels sRGB-encoded at 8 bits, clamped to [0, 1]: what FLIP and a
    /// browser take. An 8-bit PNG comes back as the bytes it was read from.
    pub fn to_srgb8(&self) -> Vec<u8> {
        self.pixels.iter().flat_map(|p| p.map(|c| (linear_to_srgb(c.clamp(0.0, 1.0)) * 255.0).round() as u8)).collect()
    }

    /// The image as an 8-bit sRGB PNG file's bytes.
    pub fn to_png(&self) -> Vec<u8> {
        let rgb = image::RgbImage::from_raw(self.width, self.height, self.to_srgb8()).expect("three bytes per pixel");
        encode_png(&rgb)
    }
}

/// PNG bytes of an RGB image. Encoding into memory cannot fail.
pub fn encode_png(rgb: &image::RgbImage) -> Vec<u8> {
    let mut bytes = std::io::Cursor::new(Vec::new());
    rgb.write_to(&mut bytes, image::ImageFormat::Png).expect("PNG encoding into memory");
    bytes.into_inner()
}

/// The sRGB transfer function's inverse (IEC 61966-2-1).
pub fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 { c / 12.92 } else { ((c + 0.055) / 1.055).powf(2.4) }
}

/// The sRGB transfer function, as the resolve kernel applies it.
pub fn linear_to_srgb(c: f32) -> f32 {
    if c <= 0.003_130_8 { c * 12.92 } else { 1.055 * c.powf(1.0 / 2.4) - 0.055 }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_8_bit_value_survives_decoding_and_encoding() {
        let bytes: Vec<u8> = (0..=255).flat_map(|v| [v, v, v]).collect();
        let rgb = image::RgbImage::from_raw(256, 1, bytes.clone()).unwrap();
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("ramp.png");
        std::fs::write(&path, encode_png(&rgb)).unwrap();
        let image = read(&path).unwrap();
        assert_eq!(image.to_srgb8(), bytes);
        // Decoding really goes to linear: mid-grey 128 is 0.2158 in linear light.
        assert!((image.pixels[128][0] - 0.215_861).abs() < 1e-5, "{}", image.pixels[128][0]);
    }

    #[test]
    fn float_formats_keep_linear_values() {
        let render = glint_image::Image {
            width: 2,
            height: 1,
            display: vec![[1.0, 1.0, 1.0, 1.0]; 2],
            linear: vec![[0.25, 2.5, 0.0, 1.0], [1e-3, 0.5, 7.0, 1.0]],
        };
        let dir = tempfile::tempdir().unwrap();
        for name in ["r.exr", "r.pfm"] {
            let path = dir.path().join(name);
            glint_image::write_image(&render, &path, glint_image::Bits::Eight).unwrap();
            let read_back = read(&path).unwrap();
            assert_eq!(read_back.pixels, vec![[0.25, 2.5, 0.0], [1e-3, 0.5, 7.0]], "{name}");
            assert_eq!(read_back, LinearImage::from_render(&render, format_of(&path).unwrap()), "{name}");
        }
    }

    #[test]
    fn one_channel_files_read_as_grey() {
        let render = glint_image::Image {
            width: 3,
            height: 1,
            display: vec![[0.0; 4]; 3],
            linear: vec![[1.5, 0.0, 0.0, 1.0], [f32::INFINITY, 0.0, 0.0, 1.0], [-1.0, 7.0, 0.0, 1.0]],
        };
        let dir = tempfile::tempdir().unwrap();
        for name in ["z.exr", "z.pfm"] {
            let path = dir.path().join(name);
            glint_image::write_image_channels(&render, &path, glint_image::Bits::Eight.into(), glint_image::Channels::Single("Z")).unwrap();
            assert_eq!(read(&path).unwrap().pixels, vec![[1.5; 3], [f32::INFINITY; 3], [-1.0; 3]], "{name}");
        }
    }

    #[test]
    fn a_ppm_reads_as_the_png_of_the_same_bytes_at_any_maxval() {
        let bytes: Vec<u8> = (0..=255).flat_map(|v| [v, 255 - v, v / 2]).collect();
        let dir = tempfile::tempdir().unwrap();
        let png = dir.path().join("ramp.png");
        std::fs::write(&png, encode_png(&image::RgbImage::from_raw(256, 1, bytes.clone()).unwrap())).unwrap();
        let png = read(&png).unwrap();
        let raw = dir.path().join("raw.ppm");
        std::fs::write(&raw, [b"P6\n256 1\n255\n".as_slice(), &bytes].concat()).unwrap();
        assert_eq!(read(&raw).unwrap(), png);
        let plain = dir.path().join("plain.PPM");
        let text: Vec<String> = bytes.iter().map(u8::to_string).collect();
        std::fs::write(&plain, format!("P3\n# a comment\n256 1\n255\n{}\n", text.join("\n"))).unwrap();
        assert_eq!(read(&plain).unwrap(), png);
        // Other maxvals scale to [0, 1] before decoding: 500 of 1000 is 128 of 255's neighbour 0.5.
        let thousand = dir.path().join("thousand.ppm");
        std::fs::write(&thousand, b"P6 1 1 1000\n\x03\xe8\x01\xf4\x00\x00").unwrap();
        assert_eq!(read(&thousand).unwrap().pixels, [[1.0, srgb_to_linear(0.5), 0.0]]);
        let one = dir.path().join("one.ppm");
        std::fs::write(&one, b"P3 2 1 1  1 0 1  0 1 0").unwrap();
        assert_eq!(read(&one).unwrap().pixels, [[1.0, 0.0, 1.0], [0.0, 1.0, 0.0]]);
    }

    #[test]
    fn a_render_compares_as_its_png_would_read() {
        let render = glint_image::Image {
            width: 1,
            height: 2,
            display: vec![[0.5, 0.25, 1.0, 1.0], [0.0, 0.999, 0.1, 1.0]],
            linear: vec![[0.0; 4]; 2],
        };
        let dir = tempfile::tempdir().unwrap();
        for (name, format) in [("r.png", Format::Png), ("r.ppm", Format::Ppm)] {
            let path = dir.path().join(name);
            glint_image::write_image(&render, &path, glint_image::Bits::Eight).unwrap();
            assert_eq!(read(&path).unwrap(), LinearImage::from_render(&render, format), "{name}");
        }
    }

    #[test]
    fn unreadable_files_name_the_file_and_the_problem() {
        let dir = tempfile::tempdir().unwrap();
        let missing = dir.path().join("missing.png");
        let e = read(&missing).unwrap_err();
        assert!(e.to_string().starts_with(&format!("{}: cannot read: ", missing.display())), "{e}");
        let garbage = dir.path().join("garbage.exr");
        std::fs::write(&garbage, b"not an image").unwrap();
        let e = read(&garbage).unwrap_err().to_string();
        assert!(e.starts_with(&format!("{}: not a readable image", garbage.display())), "{e}");
        let truncated = dir.path().join("truncated.ppm");
        std::fs::write(&truncated, b"P6\n2 2\n255\n\x00\x00").unwrap();
        let e = read(&truncated).unwrap_err().to_string();
        assert_eq!(e, format!("{}: truncated: the header promises 2x2 pixels (12 bytes of samples), but 2 bytes follow it", truncated.display()));
        let empty = dir.path().join("empty.pfm");
        std::fs::write(&empty, b"PF\n0 0\n-1.0\n").unwrap();
        assert_eq!(read(&empty).unwrap_err().to_string(), format!("{}: the image has no pixels", empty.display()));
        let bmp = dir.path().join("picture.bmp");
        let e = read(&bmp).unwrap_err().to_string();
        assert_eq!(e, format!("{}: unsupported image format: use .png, .ppm, .exr or .pfm", bmp.display()));
    }
}
