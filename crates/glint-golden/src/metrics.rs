//! The image metrics: FLIP (NVIDIA's perceptual difference, through nv-flip),
//! PSNR, RMSE and the largest channel difference, with each pixel's error.

use crate::image_io::LinearImage;

/// Which number judges a comparison.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Metric {
    /// Mean FLIP error, in [0, 1]; lower is better.
    Flip,
    /// Peak signal-to-noise ratio in dB, peak 1.0 in linear light; higher is better.
    Psnr,
    /// Root mean square channel difference in linear light; lower is better.
    Rmse,
    /// Largest absolute channel difference in linear light; lower is better.
    Max,
}

impl Metric {
    pub const ALL: [Metric; 4] = [Metric::Flip, Metric::Psnr, Metric::Rmse, Metric::Max];

    pub fn name(self) -> &'static str {
        match self {
            Metric::Flip => "flip",
            Metric::Psnr => "psnr",
            Metric::Rmse => "rmse",
            Metric::Max => "max",
        }
    }

    /// PSNR grows as images get closer; the others shrink.
    pub fn higher_is_better(self) -> bool {
        self == Metric::Psnr
    }
}

/// Two images of one size compared by every metric.
#[derive(Debug, Clone)]
pub struct Measurement {
    pub width: u32,
    pub height: u32,
    /// Mean FLIP error.
    pub flip: f64,
    /// +∞ for identical images.
    pub psnr: f64,
    pub rmse: f64,
    pub max: f64,
    /// Each pixel's FLIP error, in [0, 1].
    pub flip_map: Vec<f32>,
    /// Each pixel's largest absolute channel difference: the per-pixel error
    /// of PSNR, RMSE and max.
    pub difference_map: Vec<f32>,
}

impl Measurement {
    pub fn value(&self, metric: Metric) -> f64 {
        match metric {
            Metric::Flip => self.flip,
            Metric::Psnr => self.psnr,
            Metric::Rmse => self.rmse,
            Metric::Max => self.max,
        }
    }

    /// The per-pixel errors that `metric` is judged by, row by row.
    pub fn pixel_errors(&self, metric: Metric) -> &[f32] {
        match metric {
            Metric::Flip => &self.flip_map,
            Metric::Psnr | Metric::Rmse | Metric::Max => &self.difference_map,
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[error("the sizes differ: {}x{} against {}x{}", .reference.0, .reference.1, .test.0, .test.1)]
pub struct SizeMismatch {
    pub reference: (u32, u32),
    pub test: (u32, u32),
}

/// Compares `test` with `reference` by every metric.
pub fn measure(reference: &LinearImage, test: &LinearImage) -> Result<Measurement, SizeMismatch> {
    let (width, height) = (reference.width, reference.height);
    if (test.width, test.height) != (width, height) {
        return Err(SizeMismatch { reference: (width, height), test: (test.width, test.height) });
    }
    let mut squares = 0.0f64;
    let difference_map: Vec<f32> = reference
        .pixels
        .iter()
        .zip(&test.pixels)
        .map(|(a, b)| {
            let d = [0, 1, 2].map(|c| channel_difference(a[c], b[c]));
            squares += d.iter().map(|&d| f64::from(d) * f64::from(d)).sum::<f64>();
            d.into_iter().fold(0.0, f32::max)
        })
        .collect();
    let mse = squares / (3 * difference_map.len()) as f64;
    let (flip, flip_map) = flip(reference, test);
    Ok(Measurement {
        width,
        height,
        flip,
        psnr: -10.0 * mse.log10(),
        rmse: mse.sqrt(),
        max: difference_map.iter().copied().fold(0.0f32, f32::max).into(),
        flip_map,
        difference_map,
    })
}

/// |a − b|, where equal values (∞ included) differ by 0 and any other pair
/// involving a NaN or an infinity differs by +∞, so it can never pass.
fn channel_difference(a: f32, b: f32) -> f32 {
    if a == b {
        return 0.0;
    }
    let d = (a - b).abs();
    if d.is_nan() { f32::INFINITY } else { d }
}

/// Mean and per-pixel FLIP. nv-flip implements LDR-FLIP on 8-bit sRGB, so
/// float images are clamped to [0, 1] and encoded first; an 8-bit PNG goes in
/// exactly as it was stored.
fn flip(reference: &LinearImage, test: &LinearImage) -> (f64, Vec<f32>) {
    let (w, h) = (reference.width, reference.height);
    let error = nv_flip::flip(
        nv_flip::FlipImageRgb8::with_data(w, h, &reference.to_srgb8()),
        nv_flip::FlipImageRgb8::with_data(w, h, &test.to_srgb8()),
        nv_flip::DEFAULT_PIXELS_PER_DEGREE,
    );
    let mean = nv_flip::FlipPool::from_image(&error).mean();
    (f64::from(mean), error.to_vec())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image(width: u32, height: u32, pixels: Vec<[f32; 3]>) -> LinearImage {
        LinearImage { width, height, pixels }
    }

    fn uniform(value: [f32; 3]) -> LinearImage {
        image(8, 8, vec![value; 64])
    }

    #[test]
    fn identical_images_have_no_error() {
        let a = image(2, 2, vec![[0.1, 0.5, 0.9], [1.0, 0.0, 0.3], [0.7, 0.7, 0.7], [0.02, 0.4, 0.6]]);
        let m = measure(&a, &a).unwrap();
        assert_eq!((m.flip, m.rmse, m.max), (0.0, 0.0, 0.0));
        assert_eq!(m.psnr, f64::INFINITY);
        assert!(m.flip_map.iter().chain(&m.difference_map).all(|&e| e == 0.0));
    }

    #[test]
    fn psnr_rmse_and_max_match_hand_computed_values() {
        // Channel differences 0.1, 0, 0 | 0, 0.2, 0 | 0, 0, 0 | 0.4, 0, 0.
        let a = image(2, 2, vec![[0.5, 0.5, 0.5], [0.1, 0.2, 0.3], [0.0, 0.0, 0.0], [1.0, 1.0, 1.0]]);
        let b = image(2, 2, vec![[0.6, 0.5, 0.5], [0.1, 0.4, 0.3], [0.0, 0.0, 0.0], [0.6, 1.0, 1.0]]);
        let m = measure(&a, &b).unwrap();
        // MSE = (0.01 + 0.04 + 0.16) / 12 = 0.0175.
        let mse = 0.0175;
        assert!((m.rmse - 0.132_287_6).abs() < 1e-6, "rmse {}", m.rmse);
        assert!((m.rmse - f64::sqrt(mse)).abs() < 1e-6);
        // PSNR = 10 log10(1 / 0.0175) = 17.5696 dB.
        assert!((m.psnr - 17.569_6).abs() < 1e-3, "psnr {}", m.psnr);
        assert!((m.max - 0.4).abs() < 1e-6, "max {}", m.max);
        let expected = [0.1, 0.2, 0.0, 0.4];
        for (got, want) in m.difference_map.iter().zip(expected) {
            assert!((got - want).abs() < 1e-6, "{:?}", m.difference_map);
        }
    }

    /// CIELAB L* of a grey of linear luminance `y` (white Y = 1).
    fn lightness(y: f64) -> f64 {
        let f = if y > 216.0 / 24389.0 { y.cbrt() } else { (24389.0 / 27.0 * y + 16.0) / 116.0 };
        116.0 * f - 16.0
    }

    /// FLIP's colour error for two uniform images (no edges or points, so the
    /// feature term is 0 and the spatial filters leave a constant unchanged),
    /// following Andersson et al. 2020, eqs. 2–4: HyAB distance of the
    /// Hunt-adjusted L*a*b* colours, raised to q_c = 0.7, and remapped so that
    /// p_c·c_max goes to p_t, with c_max the distance from green to blue.
    fn flip_of_uniform_greys(y_a: f64, y_b: f64) -> f64 {
        let hunt = |[l, a, b]: [f64; 3]| [l, 0.01 * l * a, 0.01 * l * b];
        let hyab = |p: [f64; 3], q: [f64; 3]| (p[0] - q[0]).abs() + ((p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt();
        // L*a*b* of linear sRGB green and blue under D65.
        let green = hunt([87.737, -86.185, 83.181]);
        let blue = hunt([32.303, 79.197, -107.864]);
        let c_max = hyab(green, blue).powf(0.7);
        let (p_c, p_t) = (0.4, 0.95);
        let d = (lightness(y_a) - lightness(y_b)).abs().powf(0.7);
        if d < p_c * c_max { p_t / (p_c * c_max) * d } else { p_t + (d - p_c * c_max) / (c_max - p_c * c_max) * (1.0 - p_t) }
    }

    #[test]
    fn flip_matches_hand_computed_values_on_uniform_images() {
        let black = uniform([0.0; 3]);
        let white = uniform([1.0; 3]);
        // sRGB 128 decodes to linear 0.21586.
        let grey = uniform([crate::image_io::srgb_to_linear(128.0 / 255.0); 3]);
        for (a, b, y_a, y_b) in [(&black, &white, 0.0, 1.0), (&black, &grey, 0.0, 0.215_861), (&grey, &white, 0.215_861, 1.0)] {
            let m = measure(a, b).unwrap();
            let expected = flip_of_uniform_greys(y_a, y_b);
            assert!((m.flip - expected).abs() < 2e-3, "FLIP {} vs {expected} by hand", m.flip);
            assert!(m.flip_map.iter().all(|e| (f64::from(*e) - expected).abs() < 2e-3), "{:?}", m.flip_map);
        }
        // Black against white is close to FLIP's largest error.
        assert!((flip_of_uniform_greys(0.0, 1.0) - 0.967).abs() < 1e-3);
    }

    #[test]
    fn a_one_pixel_change_shows_at_that_pixel() {
        let a = image(5, 4, vec![[0.2, 0.3, 0.4]; 20]);
        let mut b = a.clone();
        b.pixels[2 * 5 + 3] = [0.9, 0.3, 0.4];
        let m = measure(&a, &b).unwrap();
        let worst = |errors: &[f32]| errors.iter().enumerate().max_by(|x, y| x.1.total_cmp(y.1)).unwrap().0;
        assert_eq!(worst(&m.flip_map), 13);
        assert_eq!(worst(&m.difference_map), 13);
        assert_eq!(m.difference_map.iter().filter(|&&e| e > 0.0).count(), 1);
        assert!((m.max - 0.7).abs() < 1e-6);
    }

    #[test]
    fn non_finite_values_never_pass() {
        let a = image(2, 1, vec![[f32::INFINITY, 0.0, 0.0], [f32::NAN, 0.0, 0.0]]);
        let b = image(2, 1, vec![[f32::INFINITY, 0.0, 0.0], [0.5, 0.0, 0.0]]);
        let m = measure(&a, &b).unwrap();
        assert_eq!(m.difference_map, vec![0.0, f32::INFINITY]);
        assert_eq!(m.rmse, f64::INFINITY);
        assert_eq!(m.psnr, f64::NEG_INFINITY);
    }

    #[test]
    fn different_sizes_are_refused() {
        let e = measure(&uniform([0.0; 3]), &image(2, 1, vec![[0.0; 3]; 2])).unwrap_err();
        assert_eq!(e.to_string(), "the sizes differ: 8x8 against 2x1");
    }
}
