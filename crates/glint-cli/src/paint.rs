//! The observer's overlay painted into an image on the CPU: anti-aliased
//! lines and dots, each over a dark outline so it reads on any background.

use glam::DVec2;
use glint_observer::{clip_to_box, Ink, Observer, Overlay};
use image::RgbImage;

/// Dashes of shadow rays: this many pixels drawn, then a gap.
const DASH: f64 = 7.0;
const GAP: f64 = 5.0;
const DOT_RADIUS: f64 = 3.5;

/// Paints `overlay` as `observer` sees it into `image` (the observer's size):
/// the segments in their order, the dots on top.
pub fn paint_overlay(image: &mut RgbImage, overlay: &Overlay, observer: &Observer) {
    for segment in &overlay.segments {
        let Some((a, b)) = observer.project_segment(segment.a, segment.b) else { continue };
        let width = segment.ink.line_width();
        if segment.ink != Ink::Grid {
            line(image, a, b, width + 2.0, [0, 0, 0], 0.6, segment.ink.is_dashed());
        }
        line(image, a, b, width, segment.ink.rgb(), 1.0, segment.ink.is_dashed());
        if segment.ink == Ink::ShadowBlocked {
            // A cross where the blocker stops it.
            for d in [DVec2::new(5.0, 5.0), DVec2::new(5.0, -5.0)] {
                line(image, b - d, b + d, width + 1.0, segment.ink.rgb(), 1.0, false);
            }
        }
    }
    for dot in &overlay.dots {
        let Some(at) = observer.project(dot.at) else { continue };
        disc(image, at, DOT_RADIUS + 1.0, [0, 0, 0], 0.7);
        disc(image, at, DOT_RADIUS, dot.ink.rgb(), 1.0);
    }
}

/// A line `width` pixels wide from `a` to `b` (pixel coordinates, pixel
/// centres at +0.5), its edges anti-aliased by their distance to each pixel.
fn line(image: &mut RgbImage, a: DVec2, b: DVec2, width: f64, color: [u8; 3], alpha: f64, dashed: bool) {
    // With a margin, so the ends of a clipped line are cut off screen.
    let margin = DVec2::splat(width + 1.0);
    let size = DVec2::new(f64::from(image.width()), f64::from(image.height()));
    let Some((a, b)) = clip_to_box(a, b, -margin, size + margin) else { return };
    let along = b - a;
    let length = along.length();
    let half = width / 2.0;
    cover(image, a.min(b) - half - 1.0, a.max(b) + half + 1.0, color, alpha, |p| {
        let s = if length > 0.0 { ((p - a).dot(along) / length).clamp(0.0, length) } else { 0.0 };
        if dashed && s % (DASH + GAP) > DASH {
            return 0.0;
        }
        let nearest = if length > 0.0 { a + along * (s / length) } else { a };
        half + 0.5 - p.distance(nearest)
    });
}

fn disc(image: &mut RgbImage, at: DVec2, radius: f64, color: [u8; 3], alpha: f64) {
    cover(image, at - radius - 1.0, at + radius + 1.0, color, alpha, |p| radius + 0.5 - p.distance(at));
}

/// Blends `color` into the pixels from `lo` to `hi` by `coverage(pixel
/// centre)`, clamped to 0..1, times `alpha`.
fn cover(image: &mut RgbImage, lo: DVec2, hi: DVec2, color: [u8; 3], alpha: f64, coverage: impl Fn(DVec2) -> f64) {
    let (w, h) = (f64::from(image.width()), f64::from(image.height()));
    let (x0, y0) = (lo.x.floor().max(0.0) as u32, lo.y.floor().max(0.0) as u32);
    let (x1, y1) = (hi.x.ceil().min(w) as u32, hi.y.ceil().min(h) as u32);
    for y in y0..y1 {
        for x in x0..x1 {
            let c = coverage(DVec2::new(f64::from(x) + 0.5, f64::from(y) + 0.5)).clamp(0.0, 1.0) * alpha;
            if c > 0.0 {
                let pixel = image.get_pixel_mut(x, y);
                for (p, &ink) in pixel.0.iter_mut().zip(&color) {
                    *p = (f64::from(*p) * (1.0 - c) + f64::from(ink) * c).round() as u8;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_line_covers_the_pixels_along_it_and_fades_at_its_edges() {
        let mut image = RgbImage::new(20, 20);
        line(&mut image, DVec2::new(2.0, 10.25), DVec2::new(18.0, 10.25), 2.0, [255, 0, 0], 1.0, false);
        assert_eq!(image.get_pixel(10, 10).0, [255, 0, 0], "on the line");
        assert_eq!(image.get_pixel(10, 5).0, [0, 0, 0], "far from it");
        let edge = image.get_pixel(10, 11).0[0];
        assert!(edge > 0 && edge < 255, "the edge pixel is partly covered: {edge}");
    }

    #[test]
    fn a_dashed_line_has_gaps_and_a_far_off_segment_is_clipped() {
        let mut image = RgbImage::new(40, 4);
        line(&mut image, DVec2::new(0.0, 2.0), DVec2::new(40.0, 2.0), 2.0, [255, 255, 255], 1.0, true);
        assert_eq!(image.get_pixel(3, 1).0, [255; 3]);
        assert_eq!(image.get_pixel(10, 1).0, [0; 3], "in the first gap");
        let mut image = RgbImage::new(10, 10);
        line(&mut image, DVec2::new(5.0, 5.0), DVec2::new(5.0e12, 5.0), 2.0, [255, 255, 255], 1.0, false);
        assert_eq!(image.get_pixel(9, 4).0, [255; 3]);
    }
}
