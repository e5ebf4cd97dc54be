//! The false-colour error map: each pixel's error at its own position (pixel
//! (x, y) of the map is pixel (x, y) of the images), with a legend strip
//! underneath. FLIP errors use FLIP's own magma colour map over [0, 1]; the
//! channel differences of the other metrics use a black–red–yellow–white ramp
//! over [0, largest difference].

use image::{Rgb, RgbImage};

use crate::font;
use crate::metrics::{Measurement, Metric};

/// The legend needs this much width to stay readable however small the image.
const MIN_WIDTH: u32 = 200;
const LEGEND_HEIGHT: u32 = 34;
const MARGIN: u32 = 4;
const BACKGROUND: Rgb<u8> = Rgb([32, 32, 32]);
const INK: Rgb<u8> = Rgb([235, 235, 235]);

/// The colour scale of a map: how an error becomes a colour and what the
/// legend says about it.
struct Scale {
    title: &'static str,
    /// The error shown at the right end of the bar.
    top: f64,
    colour: Box<dyn Fn(f64) -> Rgb<u8>>,
}

impl Scale {
    fn for_metric(measurement: &Measurement, metric: Metric) -> Self {
        match metric {
            Metric::Flip => {
                let lut = nv_flip::magma_lut().to_vec();
                Scale {
                    title: "FLIP",
                    top: 1.0,
                    // As FLIP's own tool indexes its map: round(255 e).
                    colour: Box::new(move |e| {
                        let i = (e.clamp(0.0, 1.0) * 255.0).round() as usize * 3;
                        Rgb([lut[i], lut[i + 1], lut[i + 2]])
                    }),
                }
            }
            Metric::Psnr | Metric::Rmse | Metric::Max => {
                let largest = measurement.difference_map.iter().copied().filter(|e| e.is_finite()).fold(0.0f32, f32::max);
                let top = if largest > 0.0 { f64::from(largest) } else { 1.0 };
                Scale { title: "ABS DIFF", top, colour: Box::new(move |e| heat(e / top)) }
            }
        }
    }
}

/// Black → red → yellow → white as `t` goes 0 → 1 (beyond 1, and +∞, white).
fn heat(t: f64) -> Rgb<u8> {
    let t = if t.is_nan() { 1.0 } else { t.clamp(0.0, 1.0) } * 3.0;
    let channel = |start: f64| ((t - start).clamp(0.0, 1.0) * 255.0).round() as u8;
    Rgb([channel(0.0), channel(1.0), channel(2.0)])
}

/// The error map of `metric`'s per-pixel errors, with its legend.
pub fn diff_map(measurement: &Measurement, metric: Metric) -> RgbImage {
    let (w, h) = (measurement.width, measurement.height);
    let scale = Scale::for_metric(measurement, metric);
    let width = w.max(MIN_WIDTH);
    let mut map = RgbImage::from_pixel(width, h + LEGEND_HEIGHT, BACKGROUND);
    for (i, &e) in measurement.pixel_errors(metric).iter().enumerate() {
        map.put_pixel(i as u32 % w, i as u32 / w, (scale.colour)(f64::from(e)));
    }
    draw_legend(&mut map, h, &scale);
    map
}

fn draw_legend(map: &mut RgbImage, top: u32, scale: &Scale) {
    let width = map.width();
    font::draw_text(map, MARGIN, top + MARGIN, scale.title, INK);
    let bar_top = top + MARGIN + font::GLYPH_HEIGHT + 3;
    let bar_width = width - 2 * MARGIN;
    for dx in 0..bar_width {
        let colour = (scale.colour)(f64::from(dx) / f64::from(bar_width - 1) * scale.top);
        for y in bar_top..bar_top + 8 {
            map.put_pixel(MARGIN + dx, y, colour);
        }
    }
    let labels_top = bar_top + 11;
    let [low, middle, high] = [0.0, scale.top / 2.0, scale.top].map(label);
    font::draw_text(map, MARGIN, labels_top, &low, INK);
    font::draw_text(map, (width - font::text_width(&middle)) / 2, labels_top, &middle, INK);
    font::draw_text(map, width - MARGIN - font::text_width(&high), labels_top, &high, INK);
}

/// A tick label: `0`, `0.5`, `0.125`, or `3.5e-3` when small.
fn label(v: f64) -> String {
    if v == 0.0 {
        "0".into()
    } else if v >= 0.01 {
        let text = format!("{v:.3}");
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        format!("{v:.1e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::image_io::LinearImage;
    use crate::metrics::measure;

    fn one_pixel_apart() -> Measurement {
        let a = LinearImage { width: 8, height: 4, pixels: vec![[0.1; 3]; 32] };
        let mut b = a.clone();
        b.pixels[8 + 5] = [0.9, 0.9, 0.9];
        measure(&a, &b).unwrap()
    }

    #[test]
    fn the_changed_pixel_is_brightest_at_its_position() {
        let m = one_pixel_apart();
        for metric in [Metric::Flip, Metric::Max] {
            let map = diff_map(&m, metric);
            assert_eq!(map.dimensions(), (MIN_WIDTH, 4 + LEGEND_HEIGHT));
            let brightness = |x, y| map.get_pixel(x, y).0.iter().map(|&c| u32::from(c)).sum::<u32>();
            let brightest = (0..4).flat_map(|y| (0..8).map(move |x| (x, y))).max_by_key(|&(x, y)| brightness(x, y)).unwrap();
            assert_eq!(brightest, (5, 1), "{}", metric.name());
        }
    }

    #[test]
    fn flip_uses_flips_own_colour_map() {
        let m = one_pixel_apart();
        let map = diff_map(&m, Metric::Flip);
        let lut = nv_flip::magma_lut().to_vec();
        // An unchanged pixel far from the change has an error that rounds to
        // 0 in FLIP's 256-entry map: magma's first entry.
        assert!(m.flip_map[3 * 8] < 0.5 / 255.0, "{}", m.flip_map[3 * 8]);
        assert_eq!(map.get_pixel(0, 3).0, [lut[0], lut[1], lut[2]]);
        // The legend's bar ends at magma's last entry.
        let end = map.get_pixel(MIN_WIDTH - MARGIN - 1, 4 + MARGIN + font::GLYPH_HEIGHT + 4).0;
        assert_eq!(end, [lut[765], lut[766], lut[767]]);
    }

    #[test]
    fn the_legend_has_a_title_and_ticks() {
        let m = one_pixel_apart();
        let map = diff_map(&m, Metric::Rmse);
        let ink_rows: std::collections::BTreeSet<u32> = map.enumerate_pixels().filter(|p| *p.2 == INK).map(|p| p.1).collect();
        let title_rows = 4 + MARGIN..4 + MARGIN + font::GLYPH_HEIGHT;
        assert!(title_rows.clone().all(|y| ink_rows.contains(&y)), "{ink_rows:?}");
        assert!(ink_rows.iter().any(|&y| y > title_rows.end + 10), "no tick labels: {ink_rows:?}");
        for text in ["0", "0.4", "0.8", "3.5e-3"] {
            assert!(font::can_draw(text));
        }
        assert_eq!([0.0, 0.4, 0.8, 0.0035, 0.125].map(label), ["0", "0.4", "0.8", "3.5e-3", "0.125"]);
    }

    #[test]
    fn heat_runs_black_to_white() {
        assert_eq!(heat(0.0).0, [0, 0, 0]);
        assert_eq!(heat(1.0 / 3.0).0, [255, 0, 0]);
        assert_eq!(heat(2.0 / 3.0).0, [255, 255, 0]);
        assert_eq!(heat(f64::INFINITY).0, [255, 255, 255]);
    }
}
