//! What "close enough" means: a threshold on one metric, and optionally a
//! limit on the share of pixels whose own error exceeds a tolerance.

use crate::metrics::{Measurement, Metric};

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Criteria {
    pub metric: Metric,
    /// The metric's limit: a maximum, or for PSNR a minimum.
    pub threshold: f64,
    /// A pixel whose own error exceeds this counts as "above tolerance".
    pub pixel_tolerance: f64,
    /// At most this fraction of pixels may be above tolerance; `None` sets no limit.
    pub max_bad_fraction: Option<f64>,
}

impl Criteria {
    /// The defaults, documented in docs/golden-ci.md. FLIP's are the ones
    /// Glint's own goldens use: a mean of 0.01 is invisible, and 0.5 % of
    /// pixels above 0.2 allows a few silhouette pixels that another GPU's
    /// rounding moves. The others allow about one 8-bit step of a bright value
    /// (0.01 in linear light) and 40 dB.
    pub fn for_metric(metric: Metric) -> Self {
        match metric {
            Metric::Flip => Self { metric, threshold: 0.01, pixel_tolerance: 0.2, max_bad_fraction: Some(0.005) },
            Metric::Psnr => Self { metric, threshold: 40.0, pixel_tolerance: 0.01, max_bad_fraction: None },
            Metric::Rmse | Metric::Max => Self { metric, threshold: 0.01, pixel_tolerance: 0.01, max_bad_fraction: None },
        }
    }
}

/// The pixel with the largest error (the first in row order among equals).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Worst {
    pub x: u32,
    pub y: u32,
    pub error: f32,
}

/// A measurement held against criteria.
#[derive(Debug, Clone, PartialEq)]
pub struct Verdict {
    pub criteria: Criteria,
    pub value: f64,
    pub pixels: usize,
    pub pixels_above: usize,
    pub worst: Worst,
}

pub fn judge(measurement: &Measurement, criteria: &Criteria) -> Verdict {
    let errors = measurement.pixel_errors(criteria.metric);
    let tolerance = criteria.pixel_tolerance;
    let pixels_above = errors.iter().filter(|&&e| f64::from(e) > tolerance).count();
    let mut worst = (0, 0.0f32);
    for (i, &e) in errors.iter().enumerate() {
        if e > worst.1 {
            worst = (i, e);
        }
    }
    let width = measurement.width as usize;
    Verdict {
        criteria: *criteria,
        value: measurement.value(criteria.metric),
        pixels: errors.len(),
        pixels_above,
        worst: Worst { x: (worst.0 % width) as u32, y: (worst.0 / width) as u32, error: worst.1 },
    }
}

impl Verdict {
    pub fn fraction_above(&self) -> f64 {
        self.pixels_above as f64 / self.pixels as f64
    }

    /// The metric is on the right side of its threshold (NaN never is).
    pub fn within_threshold(&self) -> bool {
        if self.criteria.metric.higher_is_better() {
            self.value >= self.criteria.threshold
        } else {
            self.value <= self.criteria.threshold
        }
    }

    pub fn within_bad_fraction(&self) -> bool {
        self.criteria.max_bad_fraction.is_none_or(|limit| self.fraction_above() <= limit)
    }

    pub fn passed(&self) -> bool {
        self.within_threshold() && self.within_bad_fraction()
    }

    /// One line: the metric against its threshold, the pixels above tolerance
    /// and the worst pixel (when any differs), e.g.
    /// `flip 0.031200 > 0.01, 1.20% of pixels above 0.2 (at most 0.5%), worst (83, 41)`.
    /// What failed comes first, so that a line that starts like a pass is one:
    /// `11.6% of pixels above 0.2, more than the 2% allowed (flip 0.045684 <= 0.05)`.
    pub fn summary(&self) -> String {
        let c = &self.criteria;
        let relation = match (c.metric.higher_is_better(), self.within_threshold()) {
            (false, true) => "<=",
            (false, false) => ">",
            (true, true) => ">=",
            (true, false) => "<",
        };
        let mean = format!("{} {} {relation} {}", c.metric.name(), number(self.value), c.threshold);
        let above = format!("{} of pixels above {}", percent(self.fraction_above()), c.pixel_tolerance);
        let mut line = match c.max_bad_fraction {
            Some(limit) if !self.within_bad_fraction() && self.within_threshold() => {
                format!("{above}, more than the {} allowed ({mean})", percent(limit))
            }
            Some(limit) if !self.within_bad_fraction() => format!("{mean}, {above} (more than the {} allowed)", percent(limit)),
            Some(limit) => format!("{mean}, {above} (at most {})", percent(limit)),
            None => format!("{mean}, {above}"),
        };
        if self.worst.error > 0.0 {
            line += &format!(", worst ({}, {})", self.worst.x, self.worst.y);
        }
        line
    }
}

/// A value as printed: six decimals, or three significant digits in
/// scientific notation when tiny, so a small error never prints as 0.
pub fn number(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        format!("{v}")
    } else if v.abs() >= 1e-3 {
        format!("{v:.6}")
    } else {
        format!("{v:.2e}")
    }
}

/// A fraction as a percentage: `0.0125` → `1.25%`, with more digits when small.
pub fn percent(fraction: f64) -> String {
    let p = fraction * 100.0;
    if p == 0.0 || p >= 0.01 { format!("{}%", trim_zeros(&format!("{p:.2}"))) } else { format!("{p:.1e}%") }
}

fn trim_zeros(text: &str) -> String {
    if text.contains('.') { text.trim_end_matches('0').trim_end_matches('.').to_string() } else { text.to_string() }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::image_io::LinearImage;
    use crate::metrics::measure;

    fn grey(width: u32, height: u32) -> LinearImage {
        LinearImage { width, height, pixels: vec![[0.5; 3]; (width * height) as usize] }
    }

    #[test]
    fn identical_images_pass_every_metric() {
        let a = grey(6, 3);
        let m = measure(&a, &a).unwrap();
        for metric in Metric::ALL {
            let v = judge(&m, &Criteria::for_metric(metric));
            assert!(v.passed(), "{}", v.summary());
            assert_eq!(v.pixels_above, 0);
            assert!(!v.summary().contains("worst"), "{}", v.summary());
        }
    }

    #[test]
    fn a_one_pixel_change_is_found_at_its_position() {
        let a = grey(10, 8);
        let mut b = a.clone();
        b.pixels[5 * 10 + 7] = [1.0, 0.0, 0.0];
        let m = measure(&a, &b).unwrap();
        for metric in Metric::ALL {
            let v = judge(&m, &Criteria::for_metric(metric));
            assert_eq!((v.worst.x, v.worst.y), (7, 5), "{}", metric.name());
            assert!(v.summary().ends_with("worst (7, 5)"), "{}", v.summary());
        }
        let max = judge(&m, &Criteria::for_metric(Metric::Max));
        assert_eq!(max.pixels_above, 1);
        assert!(!max.passed());
        assert_eq!(max.summary(), "max 0.500000 > 0.01, 1.25% of pixels above 0.01, worst (7, 5)");
        // FLIP's spatial filters spread the change to its neighbours, but not far;
        // even one pixel in 80 is over FLIP's 0.5 % allowance, though the mean passes.
        let flip = judge(&m, &Criteria { threshold: 1.0, ..Criteria::for_metric(Metric::Flip) });
        assert!((1..=9).contains(&flip.pixels_above), "{}", flip.pixels_above);
        assert!(flip.within_threshold() && !flip.within_bad_fraction() && !flip.passed());
        // Failing on its bad pixels alone, the line says so first.
        let line = flip.summary();
        assert!(line.starts_with(&format!("{} of pixels above 0.2, more than the 0.5% allowed (flip ", percent(flip.fraction_above()))), "{line}");
        assert!(line.contains(" <= 1), worst (7, 5)"), "{line}");
        let both = judge(&m, &Criteria { threshold: 1e-4, ..Criteria::for_metric(Metric::Flip) });
        assert!(both.summary().starts_with("flip ") && both.summary().contains(" > 0.0001, ") && both.summary().contains("(more than the 0.5% allowed)"), "{}", both.summary());
    }

    #[test]
    fn psnr_is_a_minimum() {
        let a = grey(4, 4);
        let mut b = a.clone();
        b.pixels[0] = [0.6, 0.5, 0.5];
        let m = measure(&a, &b).unwrap();
        // MSE = 0.01 / 48, so PSNR = 10 log10(4800) = 36.81 dB.
        assert!((m.psnr - 36.812).abs() < 1e-3, "{}", m.psnr);
        let strict = judge(&m, &Criteria::for_metric(Metric::Psnr));
        assert!(!strict.passed());
        assert!(strict.summary().starts_with("psnr 36.812"), "{}", strict.summary());
        assert!(strict.summary().contains(" < 40,"), "{}", strict.summary());
        let lenient = judge(&m, &Criteria { threshold: 30.0, ..Criteria::for_metric(Metric::Psnr) });
        assert!(lenient.passed());
        assert!(lenient.summary().contains(" >= 30,"), "{}", lenient.summary());
    }

    #[test]
    fn numbers_never_round_to_zero() {
        assert_eq!(number(0.0), "0");
        assert_eq!(number(0.0123), "0.012300");
        assert_eq!(number(0.000_012_34), "1.23e-5");
        assert_eq!(number(f64::INFINITY), "inf");
        assert_eq!(percent(0.0125), "1.25%");
        assert_eq!(percent(0.005), "0.5%");
        assert_eq!(percent(0.0), "0%");
        assert_eq!(percent(1.0 / 19200.0), "5.2e-3%");
    }
}
