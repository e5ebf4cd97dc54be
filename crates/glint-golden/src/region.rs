//! Where two images differ most: the square window with the largest summed
//! per-pixel error, and that window of each image magnified, so a report can
//! show the reference and the tested image side by side where they differ.

use std::fmt;

use crate::image_io::LinearImage;

/// A rectangle of pixels: its top-left corner and its size.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Region {
    pub x: u32,
    pub y: u32,
    pub width: u32,
    pub height: u32,
}

impl fmt::Display for Region {
    /// `8x8 at (16, 4)`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}x{} at ({}, {})", self.width, self.height, self.x, self.y)
    }
}

/// A window an eighth of the image's shorter side, at least 4 pixels (or the
/// whole side) and at most 64: big enough to show what is around a
/// difference, small enough to point at one object.
fn window_side(width: u32, height: u32) -> u32 {
    let short = width.min(height);
    (short / 8).clamp(4, 64).min(short)
}

/// The window whose pixels' `errors` (row by row, `width` per row) add up to
/// the most; the first in row order among equals.
pub fn worst_region(errors: &[f32], width: u32, height: u32) -> Region {
    let side = window_side(width, height);
    let (w, h) = (width as usize, height as usize);
    // A summed-area table with a zero row and column in front.
    let mut sums = vec![0.0f64; (w + 1) * (h + 1)];
    for y in 0..h {
        for x in 0..w {
            let e = f64::from(errors[y * w + x]);
            let e = if e.is_finite() { e } else { 1.0 };
            sums[(y + 1) * (w + 1) + x + 1] = e + sums[y * (w + 1) + x + 1] + sums[(y + 1) * (w + 1) + x] - sums[y * (w + 1) + x];
        }
    }
    let s = side as usize;
    let mut best = (0, 0, -1.0f64);
    for y in 0..=h - s {
        for x in 0..=w - s {
            let total = sums[(y + s) * (w + 1) + x + s] - sums[y * (w + 1) + x + s] - sums[(y + s) * (w + 1) + x] + sums[y * (w + 1) + x];
            if total > best.2 {
                best = (x, y, total);
            }
        }
    }
    Region { x: best.0 as u32, y: best.1 as u32, width: side, height: side }
}

/// Magnified crops are about this wide.
const ZOOM_WIDTH: u32 = 192;

/// `region` of `image`, each pixel drawn as a square block (nearest
/// neighbour, so that the pixels themselves are seen), in 8-bit sRGB.
pub fn magnified(image: &LinearImage, region: Region) -> image::RgbImage {
    let scale = (ZOOM_WIDTH / region.width).max(1);
    let srgb = image.to_srgb8();
    image::RgbImage::from_fn(region.width * scale, region.height * scale, |x, y| {
        let (sx, sy) = (region.x + x / scale, region.y + y / scale);
        let i = (sy * image.width + sx) as usize * 3;
        image::Rgb([srgb[i], srgb[i + 1], srgb[i + 2]])
    })
}

/// Outlines are this many pixels wide, drawn inside the region.
const OUTLINE_WIDTH: u32 = 2;

/// Cyan: on FLIP's magma map (black, purple, orange, pale yellow) and on the
/// black–red–yellow–white ramp alike, no error has this colour.
pub const OUTLINE_COLOUR: image::Rgb<u8> = image::Rgb([0, 255, 255]);

/// Draws `region`'s border on `image`, inside the region and the image.
pub fn outline(image: &mut image::RgbImage, region: Region) {
    let (right, bottom) = (region.x + region.width, region.y + region.height);
    for y in region.y..bottom.min(image.height()) {
        for x in region.x..right.min(image.width()) {
            let border = x < region.x + OUTLINE_WIDTH || x + OUTLINE_WIDTH >= right || y < region.y + OUTLINE_WIDTH || y + OUTLINE_WIDTH >= bottom;
            if border {
                image.put_pixel(x, y, OUTLINE_COLOUR);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_window_covers_the_cluster_not_a_lone_pixel() {
        let (width, height) = (64, 48);
        let mut errors = vec![0.0f32; 64 * 48];
        // One bright outlier, and a cluster of smaller errors that add up to more.
        errors[2 * 64 + 60] = 1.0;
        for y in 30..34 {
            for x in 10..14 {
                errors[y * 64 + x] = 0.3;
            }
        }
        let region = worst_region(&errors, width, height);
        // The first 6 × 6 window, in row order, that holds the whole 4 × 4 cluster.
        assert_eq!(region, Region { x: 8, y: 28, width: 6, height: 6 });
        assert_eq!(region.to_string(), "6x6 at (8, 28)");
    }

    #[test]
    fn a_tiny_image_is_one_window() {
        assert_eq!(worst_region(&[0.0; 6], 3, 2), Region { x: 0, y: 0, width: 2, height: 2 });
        assert_eq!(window_side(1000, 800), 64);
    }

    #[test]
    fn an_outline_is_two_pixels_inside_the_region() {
        let mut image = image::RgbImage::new(12, 10);
        outline(&mut image, Region { x: 2, y: 1, width: 6, height: 6 });
        let drawn: Vec<(u32, u32)> = image.enumerate_pixels().filter(|p| *p.2 == OUTLINE_COLOUR).map(|p| (p.0, p.1)).collect();
        // A 6 × 6 square less its 2 × 2 middle.
        assert_eq!(drawn.len(), 36 - 4);
        assert!(drawn.iter().all(|&(x, y)| (2..8).contains(&x) && (1..7).contains(&y)));
        assert!(![(4, 3), (5, 3), (4, 4), (5, 4)].iter().any(|p| drawn.contains(p)));
        // Clipped where the region runs past the image.
        let mut corner = image::RgbImage::new(4, 4);
        outline(&mut corner, Region { x: 2, y: 2, width: 4, height: 4 });
        assert_eq!(corner.enumerate_pixels().filter(|p| *p.2 == OUTLINE_COLOUR).count(), 4);
    }

    #[test]
    fn the_crop_is_magnified_by_whole_pixels() {
        let mut image = LinearImage { width: 16, height: 16, pixels: vec![[0.0; 3]; 256] };
        image.pixels[5 * 16 + 6] = [1.0, 0.0, 0.0];
        let zoom = magnified(&image, Region { x: 4, y: 4, width: 4, height: 4 });
        assert_eq!(zoom.dimensions(), (192, 192));
        // Pixel (6, 5) is block (2, 1): 48 screen pixels a side.
        assert_eq!(zoom.get_pixel(2 * 48, 48).0, [255, 0, 0]);
        assert_eq!(zoom.get_pixel(3 * 48 - 1, 2 * 48 - 1).0, [255, 0, 0]);
        assert_eq!(zoom.get_pixel(3 * 48, 48).0, [0, 0, 0]);
    }
}
