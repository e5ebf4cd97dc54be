//! Image files written as their tiles arrive. Each output keeps only what its
//! file needs: a PNG or PPM writes its rows as soon as they are complete and
//! holds no more than the rows still waiting for pixels (one band of tiles when
//! they arrive in reading order); EXR and PFM hold their linear values, only the
//! channels written, until the whole image is there (EXR compresses the whole
//! image at once, PFM runs bottom up). The file is written under a temporary
//! name beside its path and appears there only when committed, so a failure
//! midway leaves nothing at the path and no temporary file behind.

use std::collections::VecDeque;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

use tempfile::TempPath;

use crate::output::{temp_beside, to_u16, to_u8, Bits, Channels, Format, Image, PpmForm, Samples};
use crate::ppm;
use crate::ImageError;

/// An image file of `width` × `height` being written, tile by tile.
pub struct ImageSink {
    path: PathBuf,
    temp: TempPath,
    width: u32,
    height: u32,
    /// Pixels pasted so far: all of them before the file can be finished.
    pasted: u64,
    pixels: Pixels,
}

/// What an output holds until its file is complete.
enum Pixels {
    /// Display values, PNG or PPM. Boxed: the PNG encoder's state is far
    /// larger than the other variant.
    Rows(Box<RowStream>),
    /// Linear values, `channels` per pixel, row by row from the top.
    Float { format: Format, channels: Channels, file: File, values: Vec<f32> },
}

/// Rows of display values on their way to the file, which takes them in order.
struct RowStream {
    out: RowOut,
    bits: Bits,
    /// The first row not yet encoded.
    first: u32,
    /// Rows from `first` on, as PNG samples (a raw PPM's too), up to the
    /// lowest row pasted into.
    rows: Vec<u8>,
    /// Pixels pasted so far into each of those rows.
    filled: VecDeque<u32>,
}

/// Where complete rows go.
enum RowOut {
    Png { encoder: png::StreamWriter<'static, SharedFile>, file: SharedFile },
    Ppm { form: PpmForm, file: BufWriter<File> },
}

/// The temporary file, shared between the PNG encoder and the sink: the
/// encoder writes the file's last chunk when it is dropped and discards any
/// error then, so the first error is kept here for [`ImageSink::finish`].
#[derive(Clone)]
struct SharedFile(Arc<Mutex<(File, Option<std::io::Error>)>>);

impl Write for SharedFile {
    fn write(&mut self, bytes: &[u8]) -> std::io::Result<usize> {
        let mut shared = self.0.lock().unwrap_or_else(|e| e.into_inner());
        let (file, failed) = &mut *shared;
        file.write(bytes).inspect_err(|e| {
            failed.get_or_insert_with(|| std::io::Error::new(e.kind(), e.to_string()));
        })
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.0.lock().unwrap_or_else(|e| e.into_inner()).0.flush()
    }
}

/// A PNG's IDAT chunks: larger than the encoder's 4 KiB default to spare a
/// chunk header per 4 KiB, and still a small fixed amount.
const PNG_CHUNK_BYTES: usize = 1 << 20;

impl ImageSink {
    /// Starts the file for `path`, in the format its extension names: display
    /// values as `samples` says for PNG and PPM, linear values with `channels`
    /// for EXR and PFM.
    pub fn create(path: &Path, width: u32, height: u32, samples: Samples, channels: Channels) -> Result<Self, ImageError> {
        let Samples { bits, ppm: form } = samples;
        let format = Format::from_path(path)?;
        let fail = |e: &dyn std::fmt::Display| ImageError::Output(format!("{}: {e}", path.display()));
        let (file, temp) = temp_beside(path).map_err(|e| fail(&e))?.into_parts();
        let pixels = match format {
            Format::Png => {
                let file = SharedFile(Arc::new(Mutex::new((file, None))));
                let mut encoder = png::Encoder::new(file.clone(), width, height);
                encoder.set_color(png::ColorType::Rgb);
                encoder.set_depth(match bits {
                    Bits::Eight => png::BitDepth::Eight,
                    Bits::Sixteen => png::BitDepth::Sixteen,
                });
                // What the `image` crate chooses by default: fast compression,
                // each row filtered as suits it best.
                encoder.set_compression(png::Compression::Fast);
                encoder.set_filter(png::Filter::Adaptive);
                let encoder = encoder
                    .write_header()
                    .and_then(|w| w.into_stream_writer_with_size(PNG_CHUNK_BYTES))
                    .map_err(|e| fail(&e))?;
                Pixels::Rows(Box::new(RowStream::new(RowOut::Png { encoder, file }, bits)))
            }
            Format::Ppm => {
                let mut file = BufWriter::new(file);
                file.write_all(ppm::header(form, width, height, bits).as_bytes()).map_err(|e| fail(&e))?;
                Pixels::Rows(Box::new(RowStream::new(RowOut::Ppm { form, file }, bits)))
            }
            Format::Exr | Format::Pfm => {
                let count = width as usize * height as usize * channel_count(channels);
                Pixels::Float { format, channels, file, values: vec![0.0; count] }
            }
        };
        Ok(Self { path: path.to_path_buf(), temp, width, height, pasted: 0, pixels })
    }

    /// Copies `tile` into the image with its top-left corner at (`x`, `y`).
    /// Tiles may come in any order but must not overlap; PNG and PPM rows are written
    /// as soon as they and all rows above them are complete.
    pub fn paste(&mut self, tile: &Image, x: u32, y: u32) -> Result<(), ImageError> {
        if x + tile.width > self.width || y + tile.height > self.height {
            return Err(self.error(format!("a {}x{} tile at ({x}, {y}) is outside the image", tile.width, tile.height)));
        }
        if tile.width == 0 || tile.height == 0 {
            return Ok(());
        }
        let width = self.width as usize;
        match &mut self.pixels {
            Pixels::Rows(stream) => stream.paste(tile, x, y, width).map_err(|e| self.error(e))?,
            Pixels::Float { channels, values, .. } => {
                let count = channel_count(*channels);
                for (r, row) in tile.linear.chunks_exact(tile.width as usize).enumerate() {
                    let start = ((y as usize + r) * width + x as usize) * count;
                    for (out, p) in values[start..start + row.len() * count].chunks_exact_mut(count).zip(row) {
                        out.copy_from_slice(&p[..count]);
                    }
                }
            }
        }
        self.pasted += u64::from(tile.width) * u64::from(tile.height);
        Ok(())
    }

    /// Bytes of pixel values this output holds now: for a PNG or PPM the rows
    /// not yet written, for EXR and PFM the whole image's linear values.
    pub fn retained_bytes(&self) -> usize {
        match &self.pixels {
            Pixels::Rows(stream) => stream.rows.capacity() + stream.filled.capacity() * size_of::<u32>(),
            Pixels::Float { values, .. } => values.capacity() * size_of::<f32>(),
        }
    }

    /// Completes the file under its temporary name, on disk; it appears at
    /// its path when the result is committed.
    pub fn finish(self) -> Result<StagedImage, ImageError> {
        let Self { path, temp, width, height, pasted, pixels } = self;
        let fail = |e: &dyn std::fmt::Display| ImageError::Output(format!("{}: {e}", path.display()));
        let total = u64::from(width) * u64::from(height);
        if pasted != total {
            return Err(fail(&format!("only {pasted} of the image's {total} pixels were rendered")));
        }
        let file = match pixels {
            Pixels::Rows(stream) => match stream.out {
                RowOut::Png { encoder, file } => {
                    encoder.finish().map_err(|e| fail(&e))?;
                    let (file, failed) =
                        Arc::into_inner(file.0).expect("the encoder is gone").into_inner().unwrap_or_else(|e| e.into_inner());
                    if let Some(e) = failed {
                        return Err(fail(&e));
                    }
                    file
                }
                RowOut::Ppm { file, .. } => file.into_inner().map_err(|e| fail(&e.into_error()))?,
            },
            Pixels::Float { format, channels, file, values } => {
                let mut out = BufWriter::new(file);
                match (format, channels) {
                    (Format::Exr, Channels::Rgb) => image::Rgb32FImage::from_raw(width, height, values)
                        .expect("three values a pixel")
                        .write_to(&mut out, image::ImageFormat::OpenExr)
                        .map_err(|e| fail(&e))?,
                    (Format::Exr, Channels::Single(name)) => {
                        write_exr_channel(values, name, width, height, &mut out).map_err(|e| fail(&e))?
                    }
                    _ => write_pfm(&values, channels, width, height, &mut out).map_err(|e| fail(&e))?,
                }
                out.into_inner().map_err(|e| fail(&e.into_error()))?
            }
        };
        file.sync_all().map_err(|e| fail(&e))?;
        Ok(StagedImage { path, temp })
    }

    fn error(&self, message: String) -> ImageError {
        ImageError::Output(format!("{}: {message}", self.path.display()))
    }
}

impl RowStream {
    fn new(out: RowOut, bits: Bits) -> Self {
        RowStream { out, bits, first: 0, rows: Vec::new(), filled: VecDeque::new() }
    }

    fn paste(&mut self, tile: &Image, x: u32, y: u32, width: usize) -> Result<(), String> {
        let sample = match self.bits {
            Bits::Eight => 3,
            Bits::Sixteen => 6,
        };
        let row_bytes = width * sample;
        let overlap = || format!("a {}x{} tile at ({x}, {y}) overlaps pixels already pasted", tile.width, tile.height);
        if y < self.first {
            return Err(overlap());
        }
        let (top, rows) = ((y - self.first) as usize, tile.height as usize);
        if self.filled.len() < top + rows {
            // Exactly what is needed: a band of tiles is as much as is ever held.
            self.rows.reserve_exact((top + rows) * row_bytes - self.rows.len());
            self.rows.resize((top + rows) * row_bytes, 0);
            self.filled.reserve_exact(top + rows - self.filled.len());
            self.filled.resize(top + rows, 0);
        }
        if self.filled.range(top..top + rows).any(|&n| (n + tile.width) as usize > width) {
            return Err(overlap());
        }
        for (r, values) in tile.display.chunks_exact(tile.width as usize).enumerate() {
            self.filled[top + r] += tile.width;
            let start = (top + r) * row_bytes + x as usize * sample;
            let out = &mut self.rows[start..start + values.len() * sample];
            match self.bits {
                Bits::Eight => out.iter_mut().zip(values.iter().flat_map(|p| &p[..3])).for_each(|(o, &v)| *o = to_u8(v)),
                Bits::Sixteen => {
                    for (o, &v) in out.chunks_exact_mut(2).zip(values.iter().flat_map(|p| &p[..3])) {
                        o.copy_from_slice(&to_u16(v).to_be_bytes());
                    }
                }
            }
        }
        let complete = self.filled.iter().take_while(|&&n| n as usize == width).count();
        if complete > 0 {
            let rows = &self.rows[..complete * row_bytes];
            match &mut self.out {
                RowOut::Png { encoder, .. } => encoder.write_all(rows),
                RowOut::Ppm { form, file } => rows.chunks_exact(row_bytes).try_for_each(|row| ppm::write_row(*form, self.bits, row, file)),
            }
            .map_err(|e| e.to_string())?;
            self.rows.drain(..complete * row_bytes);
            self.filled.drain(..complete);
            self.first += complete as u32;
        }
        Ok(())
    }
}

/// A complete image file under a temporary name beside its path; dropped
/// uncommitted, it is removed.
pub struct StagedImage {
    path: PathBuf,
    temp: TempPath,
}

impl StagedImage {
    /// Renames the file to its path, replacing any file there.
    pub fn commit(self) -> Result<(), ImageError> {
        self.temp.persist(&self.path).map_err(|e| ImageError::Output(format!("{}: {}", self.path.display(), e.error)))
    }
}

fn channel_count(channels: Channels) -> usize {
    match channels {
        Channels::Rgb => 3,
        Channels::Single(_) => 1,
    }
}

/// An EXR with one 32-bit float channel `name`.
fn write_exr_channel(
    values: Vec<f32>,
    name: &str,
    width: u32,
    height: u32,
    w: &mut (impl Write + std::io::Seek),
) -> exr::error::UnitResult {
    use exr::prelude as x;
    let channel = x::AnyChannel::new(name, x::FlatSamples::F32(values));
    let layer = x::Layer::new(
        (width as usize, height as usize),
        x::LayerAttributes::default(),
        x::Encoding::FAST_LOSSLESS,
        x::AnyChannels::sort(vec![channel].into()),
    );
    x::WritableImage::write(&x::Image::from_layer(layer)).to_buffered(w)
}

/// PFM: a text header (`PF` for colour, `Pf` for greyscale), then
/// little-endian floats, rows from the bottom up.
fn write_pfm(values: &[f32], channels: Channels, width: u32, height: u32, w: &mut impl Write) -> std::io::Result<()> {
    let magic = match channels {
        Channels::Rgb => "PF",
        Channels::Single(_) => "Pf",
    };
    write!(w, "{magic}\n{width} {height}\n-1.0\n")?;
    let row = width as usize * channel_count(channels);
    for values in values.chunks_exact(row.max(1)).rev() {
        for v in values {
            w.write_all(&v.to_le_bytes())?;
        }
    }
    Ok(())
}

/// Writes `image` to `path` in the format its extension names, atomically
/// (see [`ImageSink`]).
pub fn write_image(image: &Image, path: &Path, bits: Bits) -> Result<(), ImageError> {
    write_image_channels(image, path, bits.into(), Channels::Rgb)
}

/// [`write_image`], with display formats written with `samples` and float
/// formats with `channels`.
pub fn write_image_channels(image: &Image, path: &Path, samples: Samples, channels: Channels) -> Result<(), ImageError> {
    let mut sink = ImageSink::create(path, image.width, image.height, samples, channels)?;
    sink.paste(image, 0, 0)?;
    sink.finish()?.commit()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{read_pfm, read_pfm_channels, Region};

    /// An image whose pixel (x, y) has distinct display and linear values.
    fn image(width: u32, height: u32) -> Image {
        let value = |i: u32| (i % 251) as f32 / 250.0;
        let linear: Vec<[f32; 4]> = (0..width * height).map(|i| [value(i), value(i + 7) * 3.0, i as f32, 1.0]).collect();
        let display = linear.iter().map(|p| [p[1] / 3.0, p[0], 1.0 - p[0], 1.0]).collect();
        Image { width, height, display, linear }
    }

    /// Writes `image` to `path` in tiles of `tile_pixels`, in reading order or
    /// its `reverse`, and returns the most bytes the sink held meanwhile.
    fn write_in_tiles(image: &Image, path: &Path, samples: Samples, channels: Channels, tile_pixels: u64, reverse: bool) -> usize {
        let mut sink = ImageSink::create(path, image.width, image.height, samples, channels).unwrap();
        let mut tiles = Region::whole(image.width, image.height).tiles(tile_pixels);
        if reverse {
            tiles.reverse();
        }
        let mut held = 0;
        for tile in tiles {
            sink.paste(&image.crop(tile), tile.x0, tile.y0).unwrap();
            held = held.max(sink.retained_bytes());
        }
        sink.finish().unwrap().commit().unwrap();
        held
    }

    #[test]
    fn a_png_holds_at_most_the_rows_of_a_band_of_tiles() {
        let (width, height) = (300, 200);
        let img = image(width, height);
        let dir = tempfile::tempdir().unwrap();
        let whole = dir.path().join("whole.png");
        crate::write_image(&img, &whole, Bits::Eight).unwrap();
        for (bits, sample) in [(Bits::Eight, 3), (Bits::Sixteen, 6)] {
            // Bands of 16 whole rows, then tiles narrower than a row.
            for (tile_pixels, band_rows) in [(300 * 16, 16), (7, 1)] {
                let path = dir.path().join(format!("{sample}-{tile_pixels}.png"));
                let held = write_in_tiles(&img, &path, bits.into(), Channels::Rgb, tile_pixels, false);
                let band = width as usize * band_rows * sample;
                // A row's count of pixels pasted is 4 bytes, at least 4 of them.
                assert!(held <= band + band_rows.max(4) * 4, "{held} bytes held for bands of {band_rows} rows ({band} bytes)");
                assert!(held < width as usize * height as usize * sample / 10, "a PNG must not hold its whole image");
                if bits == Bits::Eight {
                    assert!(std::fs::read(&path).unwrap() == std::fs::read(&whole).unwrap(), "tiles change the file");
                }
                let back = image::open(&path).unwrap();
                assert_eq!(back.color(), if sample == 3 { image::ColorType::Rgb8 } else { image::ColorType::Rgb16 });
                assert_eq!(back.to_rgb8(), img.to_rgb8());
            }
        }
        // In reverse order every row waits for the top one: the whole image is
        // held, and the file is still the same.
        let path = dir.path().join("reverse.png");
        let held = write_in_tiles(&img, &path, Bits::Eight.into(), Channels::Rgb, 300 * 16, true);
        assert!(held <= (width * height * 3 + height * 4) as usize, "{held}");
        assert!(std::fs::read(&path).unwrap() == std::fs::read(&whole).unwrap());
    }

    #[test]
    fn a_ppm_holds_the_png_s_samples_after_its_header_in_tiles_of_any_order() {
        let (width, height) = (300, 200);
        let img = image(width, height);
        let dir = tempfile::tempdir().unwrap();
        let png = dir.path().join("whole.png");
        crate::write_image(&img, &png, Bits::Eight).unwrap();
        let png = image::open(&png).unwrap().to_rgb8().into_raw();
        for (bits, sample) in [(Bits::Eight, 3), (Bits::Sixteen, 6)] {
            let raw = Samples { bits, ppm: PpmForm::Raw };
            let whole = dir.path().join(format!("whole{sample}.ppm"));
            crate::write_image(&img, &whole, bits).unwrap();
            let bytes = std::fs::read(&whole).unwrap();
            let header = if bits == Bits::Eight { "P6\n300 200\n255\n" } else { "P6\n300 200\n65535\n" };
            assert!(bytes.starts_with(header.as_bytes()), "{:?}", &bytes[..16]);
            assert_eq!(bytes.len(), header.len() + (width * height) as usize * sample);
            let read = crate::read_ppm(&bytes).unwrap();
            let expected: Vec<u16> = img.display.iter().flat_map(|p| [p[0], p[1], p[2]]).map(|v| match bits {
                Bits::Eight => u16::from(crate::output::to_u8(v)),
                Bits::Sixteen => crate::output::to_u16(v),
            }).collect();
            assert_eq!(read.samples, expected);
            if bits == Bits::Eight {
                assert!(bytes[header.len()..] == png[..], "an 8-bit PPM's samples are the PNG's bytes");
            }
            for (tile_pixels, reverse, band_rows) in [(300 * 16, false, 16), (7, false, 1), (300 * 16, true, 200)] {
                let path = dir.path().join(format!("{sample}-{tile_pixels}-{reverse}.ppm"));
                let held = write_in_tiles(&img, &path, raw, Channels::Rgb, tile_pixels, reverse);
                assert!(held <= width as usize * band_rows * sample + band_rows.max(4) * 4, "{held} bytes held");
                assert!(std::fs::read(&path).unwrap() == bytes, "tiles change the file");
            }
            // Plain: the same samples as text, in short lines.
            let path = dir.path().join(format!("plain{sample}.ppm"));
            write_in_tiles(&img, &path, Samples { bits, ppm: PpmForm::Plain }, Channels::Rgb, 90, false);
            let text = std::fs::read(&path).unwrap();
            assert!(text.starts_with(header.replace("P6", "P3").as_bytes()));
            assert!(text.split(|&b| b == b'\n').all(|line| line.len() <= 70));
            let plain = crate::read_ppm(&text).unwrap();
            assert_eq!((plain.form, plain.samples, plain.maxval), (PpmForm::Plain, read.samples, read.maxval));
        }
    }

    #[test]
    fn float_files_hold_only_the_channels_written() {
        let img = image(40, 30);
        let dir = tempfile::tempdir().unwrap();
        let (rgb, z) = (Channels::Rgb, Channels::Single("Z"));
        for (name, channels, count) in [("rgb.pfm", rgb, 3), ("rgb.exr", rgb, 3), ("z.pfm", z, 1), ("z.exr", z, 1)] {
            let path = dir.path().join(name);
            let held = write_in_tiles(&img, &path, Bits::Eight.into(), channels, 90, false);
            assert_eq!(held, 40 * 30 * count * 4, "{name}");
        }
        let (w, h, rgb) = read_pfm(&std::fs::read(dir.path().join("rgb.pfm")).unwrap()).unwrap();
        assert_eq!((w, h), (40, 30));
        assert!(rgb.iter().zip(&img.linear).all(|(a, b)| a[..] == b[..3]));
        let (_, _, count, z) = read_pfm_channels(&std::fs::read(dir.path().join("z.pfm")).unwrap()).unwrap();
        assert_eq!(count, 1);
        assert!(z.iter().zip(&img.linear).all(|(a, b)| *a == b[0]));
    }

    #[test]
    fn single_channel_pfm_is_greyscale() {
        let mut bytes = Vec::new();
        write_pfm(&[1.0, 2.0, 3.0, 4.0, 5.0, f32::INFINITY], Channels::Single("Z"), 3, 2, &mut bytes).unwrap();
        assert!(bytes.starts_with(b"Pf\n3 2\n-1.0\n"));
        assert_eq!(bytes.len(), b"Pf\n3 2\n-1.0\n".len() + 6 * 4, "one float per pixel");
        let (w, h, channels, values) = read_pfm_channels(&bytes).unwrap();
        assert_eq!((w, h, channels), (3, 2, 1));
        assert_eq!(values, [1.0, 2.0, 3.0, 4.0, 5.0, f32::INFINITY], "top row first");
        let (_, _, rgb) = read_pfm(&bytes).unwrap();
        assert_eq!(rgb[4], [5.0; 3]);
    }

    #[test]
    fn single_channel_exr_has_one_named_channel() {
        let mut bytes = std::io::Cursor::new(Vec::new());
        write_exr_channel(vec![1.0, -1.0, 7.0, f32::INFINITY], "Z", 2, 2, &mut bytes).unwrap();
        let (_, _, channels) = crate::read_exr_channels(&bytes.into_inner()).unwrap();
        assert_eq!(channels.len(), 1);
        assert_eq!(channels[0].0, "Z");
        assert_eq!(channels[0].1, [1.0, -1.0, 7.0, f32::INFINITY]);
    }

    #[test]
    fn nothing_appears_before_commit_and_nothing_stays_after_a_failure() {
        let dir = tempfile::tempdir().unwrap();
        let img = image(20, 10);
        let listing = || std::fs::read_dir(dir.path()).unwrap().map(|e| e.unwrap().file_name()).collect::<Vec<_>>();
        for name in ["a.png", "a.ppm", "a.exr"] {
            let path = dir.path().join(name);
            // Abandoned halfway, as when a render fails: no file at all.
            let mut sink = ImageSink::create(&path, 20, 10, Bits::Eight.into(), Channels::Rgb).unwrap();
            sink.paste(&img.crop(Region { x0: 0, y0: 0, x1: 20, y1: 4 }), 0, 0).unwrap();
            drop(sink);
            assert!(listing().is_empty(), "{name}: {:?}", listing());
            // Finished but not committed: still nothing at the path.
            let mut sink = ImageSink::create(&path, 20, 10, Bits::Eight.into(), Channels::Rgb).unwrap();
            sink.paste(&img, 0, 0).unwrap();
            let staged = sink.finish().unwrap();
            assert!(!path.exists());
            staged.commit().unwrap();
            assert_eq!(listing(), [std::ffi::OsString::from(name)]);
            std::fs::remove_file(&path).unwrap();
        }
        let path = dir.path().join("b.png");
        let mut sink = ImageSink::create(&path, 20, 10, Bits::Eight.into(), Channels::Rgb).unwrap();
        let half = img.crop(Region { x0: 0, y0: 0, x1: 20, y1: 5 });
        sink.paste(&half, 0, 0).unwrap();
        let e = sink.paste(&half, 0, 2).unwrap_err().to_string();
        assert!(e.contains("b.png") && e.contains("overlaps"), "{e}");
        assert!(sink.paste(&half, 0, 6).unwrap_err().to_string().contains("outside the image"));
        let e = sink.finish().err().unwrap().to_string();
        assert!(e.contains("only 100 of the image's 200 pixels"), "{e}");
        assert!(listing().is_empty(), "{:?}", listing());
    }
}
