//! Parts of one image rendered apart (`glint render --region` or `--shard`),
//! and putting them back together. Each part's placement — the full image's
//! size and the region the part holds — is recorded beside it in
//! `PART.json` (`shard0.png` → `shard0.png.json`), one format for PNG, PPM,
//! EXR and PFM alike (PPM and PFM have no room for metadata), with the shard `I/N` the
//! part is, if it is one, so that stitching can name the shards missing.
//! Stitching reads each part
//! back as the values it was written from and writes the whole with the same
//! encoder, so stitched parts give the bytes of a render done in one piece.

use std::path::{Path, PathBuf};

use crate::output::{write_atomically, Bits, Channels, Format, Image, Samples};
use crate::{read_pfm_channels, read_ppm, ImageError, ImageSink, PpmForm, Region};

/// Where a part belongs: in an image of `width` × `height`, at `region`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Placement {
    pub width: u32,
    pub height: u32,
    pub region: Region,
    /// `(I, N)` for the part `--shard I/N` renders; none for a `--region`,
    /// and for parts written before Glint recorded it.
    pub shard: Option<(u32, u32)>,
}

/// The file that records the placement of the part at `image`.
pub fn placement_path(image: &Path) -> PathBuf {
    let mut name = image.as_os_str().to_owned();
    name.push(".json");
    PathBuf::from(name)
}

/// Records, atomically, that the part at `image` holds `placement`.
pub fn write_placement(image: &Path, placement: &Placement) -> Result<(), ImageError> {
    let path = placement_path(image);
    let Region { x0, y0, x1, y1 } = placement.region;
    let shard = placement.shard.map_or(String::new(), |(index, count)| format!(", \"shard\": [{index}, {count}]"));
    let text = format!(
        "{{\"glint_part\": 1, \"image\": [{}, {}], \"region\": [{x0}, {y0}, {x1}, {y1}]{shard}}}\n",
        placement.width, placement.height
    );
    write_atomically(&path, text.as_bytes()).map_err(|e| ImageError::Output(format!("{}: {e}", path.display())))
}

/// The placement recorded beside the part at `image`.
pub fn read_placement(image: &Path) -> Result<Placement, String> {
    let path = placement_path(image);
    let shown = path.display();
    let text = std::fs::read_to_string(&path).map_err(|e| match e.kind() {
        std::io::ErrorKind::NotFound => format!(
            "{}: no placement file {shown} beside it: only parts rendered with --region or --shard can be stitched",
            image.display()
        ),
        _ => format!("{shown}: cannot read: {e}"),
    })?;
    let value: serde_json::Value = serde_json::from_str(&text).map_err(|e| format!("{shown}: not JSON: {e}"))?;
    let numbers = |key: &str, count: usize| -> Result<Vec<u32>, String> {
        let wrong = || format!("{shown}: `{key}` must be a list of {count} whole numbers");
        let list = value.get(key).and_then(|v| v.as_array()).ok_or_else(wrong)?;
        let numbers: Option<Vec<u32>> = list.iter().map(|n| n.as_u64().and_then(|n| u32::try_from(n).ok())).collect();
        numbers.filter(|n| n.len() == count).ok_or_else(wrong)
    };
    let (image_size, region) = (numbers("image", 2)?, numbers("region", 4)?);
    let shard = match value.get("shard") {
        Some(_) => Some(numbers("shard", 2).map(|n| (n[0], n[1]))?),
        None => None,
    };
    let placement = Placement {
        width: image_size[0],
        height: image_size[1],
        region: Region { x0: region[0], y0: region[1], x1: region[2], y1: region[3] },
        shard,
    };
    let whole = Region::whole(placement.width, placement.height);
    if placement.region.is_empty() || !whole.contains(&placement.region) {
        return Err(format!(
            "{shown}: the region {} is empty or not inside the {}x{} image",
            placement.region, placement.width, placement.height
        ));
    }
    if let Some((index, count)) = shard
        && (index >= count || whole.strip(index, count) != placement.region)
    {
        let (region, width, height) = (placement.region, placement.width, placement.height);
        return Err(format!("{shown}: the region {region} is not shard {index}/{count} of the {width}x{height} image"));
    }
    Ok(placement)
}

/// How a part's values are stored, which the whole must keep.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Encoding {
    /// PNG or PPM.
    Display(Format, Samples),
    Float(Format, Channels),
}

impl std::fmt::Display for Encoding {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Encoding::Display(format, Samples { bits, ppm }) => {
                let bits = match bits {
                    Bits::Eight => "an 8-bit",
                    Bits::Sixteen => "a 16-bit",
                };
                match (format, ppm) {
                    (Format::Ppm, PpmForm::Raw) => write!(f, "{bits} raw PPM (P6)"),
                    (Format::Ppm, PpmForm::Plain) => write!(f, "{bits} plain PPM (P3)"),
                    _ => write!(f, "{bits} PNG"),
                }
            }
            Encoding::Float(format, Channels::Rgb) => write!(f, "an RGB {}", format!("{format:?}").to_ascii_uppercase()),
            Encoding::Float(format, Channels::Single(name)) => {
                write!(f, "a one-channel ({name}) {}", format!("{format:?}").to_ascii_uppercase())
            }
        }
    }
}

/// A part read back: its placement, its values and how they were stored.
struct Part {
    path: PathBuf,
    placement: Placement,
    image: Image,
    encoding: Encoding,
}

/// Assembles `parts` into the image they are parts of and writes it to
/// `output` (the parts' format), and returns its width and height. The parts
/// must be of one image, stored alike, and cover it exactly once; each
/// problem is one line naming a file.
pub fn stitch(parts: &[PathBuf], output: &Path) -> Result<(u32, u32), ImageError> {
    let parts: Vec<Part> = parts.iter().map(|p| read_part(p)).collect::<Result<_, _>>().map_err(ImageError::Stitch)?;
    let first = parts.first().ok_or_else(|| ImageError::Stitch("no parts to stitch".into()))?;
    let (width, height, encoding) = (first.placement.width, first.placement.height, first.encoding);
    let wanted = Format::from_path(output)?;
    let format_of = |e: Encoding| match e {
        Encoding::Display(format, _) | Encoding::Float(format, _) => format,
    };
    if format_of(encoding) != wanted {
        let extension = format!("{:?}", format_of(encoding)).to_ascii_lowercase();
        return Err(ImageError::Stitch(format!(
            "{}: the parts are .{extension} files and stitching keeps their format: name the output .{extension}",
            output.display()
        )));
    }
    for part in &parts {
        let shown = part.path.display();
        if (part.placement.width, part.placement.height) != (width, height) {
            return Err(ImageError::Stitch(format!(
                "{shown}: is a part of a {}x{} image, but {} is a part of a {width}x{height} one",
                part.placement.width,
                part.placement.height,
                first.path.display()
            )));
        }
        if part.encoding != encoding {
            return Err(ImageError::Stitch(format!(
                "{shown}: is {}, but {} is {encoding}",
                part.encoding,
                first.path.display()
            )));
        }
    }
    check_coverage(&parts, width, height)?;
    let (samples, channels) = match encoding {
        Encoding::Display(_, samples) => (samples, Channels::Rgb),
        Encoding::Float(_, channels) => (Samples::default(), channels),
    };
    let mut sink = ImageSink::create(output, width, height, samples, channels)?;
    // In reading order a PNG's or PPM's rows are written as each strip of parts completes them.
    let mut parts = parts;
    parts.sort_by_key(|p| (p.placement.region.y0, p.placement.region.x0));
    for part in &parts {
        sink.paste(&part.image, part.placement.region.x0, part.placement.region.y0)?;
    }
    sink.finish()?.commit()?;
    Ok((width, height))
}

/// Checks that the parts' regions cover the `width` × `height` image exactly
/// once: no two share a pixel and none is missing.
fn check_coverage(parts: &[Part], width: u32, height: u32) -> Result<(), ImageError> {
    for (i, a) in parts.iter().enumerate() {
        for b in &parts[i + 1..] {
            if a.placement.region.overlaps(&b.placement.region) {
                return Err(ImageError::Stitch(format!(
                    "{} (region {}) and {} (region {}) overlap",
                    a.path.display(),
                    a.placement.region,
                    b.path.display(),
                    b.placement.region
                )));
            }
        }
    }
    let regions: Vec<Region> = parts.iter().map(|p| p.placement.region).collect();
    if let Some((x, y)) = first_uncovered(&regions, width, height) {
        let covered: u64 = regions.iter().map(Region::pixels).sum();
        let missing = u64::from(width) * u64::from(height) - covered;
        return Err(ImageError::Stitch(format!(
            "the parts leave {missing} pixels of the {width}x{height} image uncovered, the first at ({x}, {y}): {}",
            missing_shards(parts).unwrap_or_else(|| "a part is missing".into())
        )));
    }
    Ok(())
}

/// Which shards are missing and how to render just them, when every part is a
/// shard of one count. A Slurm array index is the shard index, so the missing
/// indices are also the `--array` that reruns them.
fn missing_shards(parts: &[Part]) -> Option<String> {
    let shards: Vec<(u32, u32)> = parts.iter().map(|p| p.placement.shard).collect::<Option<_>>()?;
    let count = shards.first()?.1;
    if shards.iter().any(|&(_, n)| n != count) {
        return None;
    }
    let missing: Vec<u32> = (0..count).filter(|i| !shards.contains(&(*i, count))).collect();
    let list = index_ranges(&missing);
    Some(match missing.len() {
        1 => format!("shard {list} of {count} is missing: render it again (in a Slurm job array, --array={list})"),
        _ => format!("shards {list} of {count} are missing: render them again (in a Slurm job array, --array={list})"),
    })
}

/// Ascending indices as runs, as Slurm's `--array` takes them: `1-3,5`.
fn index_ranges(indices: &[u32]) -> String {
    let mut runs: Vec<(u32, u32)> = Vec::new();
    for &i in indices {
        match runs.last_mut() {
            Some((_, last)) if *last + 1 == i => *last = i,
            _ => runs.push((i, i)),
        }
    }
    let run = |&(first, last): &(u32, u32)| if first == last { first.to_string() } else { format!("{first}-{last}") };
    runs.iter().map(run).collect::<Vec<_>>().join(",")
}

/// The first pixel, in reading order, of no region. The regions' edges cut
/// the image into cells each wholly inside or outside every region, so one
/// pixel per cell settles it, however large the image.
fn first_uncovered(regions: &[Region], width: u32, height: u32) -> Option<(u32, u32)> {
    let cuts = |edges: &mut dyn Iterator<Item = u32>, end: u32| {
        let mut cuts: Vec<u32> = edges.filter(|&e| e < end).chain([0]).collect();
        cuts.sort_unstable();
        cuts.dedup();
        cuts
    };
    let ys = cuts(&mut regions.iter().flat_map(|r| [r.y0, r.y1]), height);
    let xs = cuts(&mut regions.iter().flat_map(|r| [r.x0, r.x1]), width);
    ys.iter().flat_map(|&y| xs.iter().map(move |&x| (x, y))).find(|&(x, y)| {
        !regions.iter().any(|r| r.contains(&Region { x0: x, y0: y, x1: x + 1, y1: y + 1 }))
    })
}

fn read_part(path: &Path) -> Result<Part, String> {
    let shown = path.display();
    let format = Format::from_path(path).map_err(|e| e.to_string())?;
    if !path.exists() {
        return Err(format!("{shown}: no such file"));
    }
    let placement = read_placement(path)?;
    let bytes = std::fs::read(path).map_err(|e| format!("{shown}: cannot read: {e}"))?;
    let (image, encoding) = decode(&bytes, format).map_err(|e| format!("{shown}: {e}"))?;
    let region = placement.region;
    if (image.width, image.height) != (region.width(), region.height()) {
        return Err(format!(
            "{shown}: is {}x{}, but its placement {} says the region {region} ({}x{})",
            image.width,
            image.height,
            placement_path(path).display(),
            region.width(),
            region.height()
        ));
    }
    Ok(Part { path: path.to_path_buf(), placement, image, encoding })
}

/// The values a part was written from, and how they were stored.
fn decode(bytes: &[u8], format: Format) -> Result<(Image, Encoding), String> {
    let image_of = |width: u32, height: u32, values: Vec<[f32; 4]>| Image { width, height, display: values.clone(), linear: values };
    match format {
        Format::Png => {
            let decoded = image::load_from_memory_with_format(bytes, image::ImageFormat::Png)
                .map_err(|e| format!("not a readable PNG: {e}"))?;
            let (width, height) = (decoded.width(), decoded.height());
            // Dividing by the largest value is what writing multiplies back.
            let scaled = |rgb: [f32; 3], max: f32| [rgb[0] / max, rgb[1] / max, rgb[2] / max, 1.0];
            let (values, bits): (Vec<[f32; 4]>, Bits) = match decoded {
                image::DynamicImage::ImageRgb8(rgb) => (rgb.pixels().map(|p| scaled(p.0.map(f32::from), 255.0)).collect(), Bits::Eight),
                image::DynamicImage::ImageRgb16(rgb) => {
                    (rgb.pixels().map(|p| scaled(p.0.map(f32::from), 65535.0)).collect(), Bits::Sixteen)
                }
                _ => return Err("not an RGB PNG as `glint render` writes".into()),
            };
            Ok((image_of(width, height, values), Encoding::Display(Format::Png, bits.into())))
        }
        Format::Ppm => {
            let ppm = read_ppm(bytes)?;
            let bits = match ppm.maxval {
                255 => Bits::Eight,
                65535 => Bits::Sixteen,
                other => return Err(format!("not a PPM as `glint render` writes: its maxval is {other}, not 255 or 65535")),
            };
            let values = ppm.display_values().collect::<Vec<_>>().chunks_exact(3).map(|c| [c[0], c[1], c[2], 1.0]).collect();
            Ok((image_of(ppm.width, ppm.height, values), Encoding::Display(Format::Ppm, Samples { bits, ppm: ppm.form })))
        }
        Format::Pfm => {
            let (width, height, channels, values) = read_pfm_channels(bytes)?;
            let (values, channels) = match channels {
                1 => (values.iter().map(|&v| [v, 0.0, 0.0, 1.0]).collect(), Channels::Single("Z")),
                _ => (values.chunks_exact(3).map(|c| [c[0], c[1], c[2], 1.0]).collect(), Channels::Rgb),
            };
            Ok((image_of(width, height, values), Encoding::Float(Format::Pfm, channels)))
        }
        Format::Exr => decode_exr(bytes).map(|(image, channels)| (image, Encoding::Float(Format::Exr, channels))),
    }
}

/// An EXR as `glint render` writes them: R, G and B, or one named channel.
fn decode_exr(bytes: &[u8]) -> Result<(Image, Channels), String> {
    let (width, height, mut channels) = crate::read_exr_channels(bytes)?;
    let image = |values: Vec<[f32; 4]>| Image { width, height, display: values.clone(), linear: values };
    if let [(name, values)] = &channels[..] {
        let values = values.iter().map(|&v| [v, 0.0, 0.0, 1.0]).collect();
        // The stitched file names its one channel as the parts do. `Channels`
        // holds the names Glint writes, which live for the whole program, so
        // a name read from a file is kept as long: a few bytes per part.
        let name: &'static str = Box::leak(name.clone().into_boxed_str());
        return Ok((image(values), Channels::Single(name)));
    }
    let mut take = |name: &str| channels.iter().position(|(n, _)| n == name).map(|i| channels.swap_remove(i).1);
    match (take("R"), take("G"), take("B")) {
        (Some(r), Some(g), Some(b)) if channels.is_empty() => {
            let values = r.iter().zip(&g).zip(&b).map(|((&r, &g), &b)| [r, g, b, 1.0]).collect();
            Ok((image(values), Channels::Rgb))
        }
        _ => Err("not an EXR as `glint render` writes (R, G and B, or one channel)".into()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_hole_between_parts_is_found_wherever_it_is() {
        let r = |x0, y0, x1, y1| Region { x0, y0, x1, y1 };
        // A frame around the pixels [4, 6) × [3, 5) of a 10 × 8 image.
        let frame = [r(0, 0, 10, 3), r(0, 3, 4, 5), r(6, 3, 10, 5), r(0, 5, 10, 8)];
        assert_eq!(first_uncovered(&frame, 10, 8), Some((4, 3)));
        let filled: Vec<Region> = frame.iter().copied().chain([r(4, 3, 6, 5)]).collect();
        assert_eq!(first_uncovered(&filled, 10, 8), None);
        assert_eq!(first_uncovered(&[], 3, 3), Some((0, 0)));
    }

    #[test]
    fn missing_indices_are_runs_as_slurm_arrays_take_them() {
        assert_eq!(index_ranges(&[1]), "1");
        assert_eq!(index_ranges(&[0, 1, 2, 5, 7, 8]), "0-2,5,7-8");
        assert_eq!(index_ranges(&[]), "");
    }
}
