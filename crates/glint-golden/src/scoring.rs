//! Points for a graded case: all of its `points` when the image passes, else
//! the points of the best partial-credit band that holds, else none. A
//! manifest writes a band as
//!
//! ```toml
//! [[case.partial]]
//! flip = 0.05              # the case's metric, and the loosest value that earns
//! max_bad_fraction = 0.08  # optional: and at most this share of pixels above
//!                          # the case's pixel_tolerance
//! points = 5
//! ```
//!
//! A mean alone cannot rank: a wrong highlight model spreads a small error
//! over many pixels, a half-pixel shift a large one over few edges, and both
//! can have the same mean. Bounding both ranks them.

use serde::Deserialize;
use toml::Spanned;

use crate::criteria::{percent, Criteria, Verdict};
use crate::metrics::Metric;
use crate::settings::{Checked, Finite, Fraction, NonNegative};

/// Points when no `points` is given.
pub const DEFAULT_POINTS: f64 = 1.0;

#[derive(Debug, Clone, PartialEq)]
pub struct Scoring {
    pub points: f64,
    /// Bands with their limits, in the manifest's order.
    pub partial: Vec<Band>,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Band {
    /// The loosest value of the case's metric that still earns `points`.
    pub limit: f64,
    /// The largest share of pixels above the case's pixel tolerance that
    /// still earns; `None` sets no limit.
    pub max_bad_fraction: Option<f64>,
    pub points: f64,
}

/// What a judged image earns, and the band that gave a failing image its
/// points.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Award {
    pub points: f64,
    pub band: Option<Band>,
}

/// `[[case.partial]]` as written: one metric's limit, perhaps a bad-pixel
/// limit, and the points.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BandDef {
    flip: Option<Checked<Finite>>,
    psnr: Option<Checked<Finite>>,
    rmse: Option<Checked<Finite>>,
    max: Option<Checked<Finite>>,
    max_bad_fraction: Option<Checked<Fraction>>,
    points: Checked<NonNegative>,
}

impl Band {
    fn holds(&self, verdict: &Verdict) -> bool {
        let mean = if verdict.criteria.metric.higher_is_better() { verdict.value >= self.limit } else { verdict.value <= self.limit };
        mean && self.max_bad_fraction.is_none_or(|limit| verdict.fraction_above() <= limit)
    }

    /// The band's conditions in words, e.g. `flip <= 0.1, at most 8% of pixels above 0.2`.
    pub fn conditions(&self, criteria: &Criteria) -> String {
        let relation = if criteria.metric.higher_is_better() { ">=" } else { "<=" };
        let mut text = format!("{} {relation} {}", criteria.metric.name(), self.limit);
        if let Some(limit) = self.max_bad_fraction {
            text += &format!(", at most {} of pixels above {}", percent(limit), criteria.pixel_tolerance);
        }
        text
    }
}

impl Scoring {
    /// Reads a case's `points` and `partial` bands, checked against the
    /// case's criteria. An error comes with the offset of the band it is
    /// about, if any.
    pub fn of(points: Option<f64>, bands: &[Spanned<BandDef>], criteria: &Criteria) -> Result<Scoring, (Option<usize>, String)> {
        let points = points.unwrap_or(DEFAULT_POINTS);
        let metric = criteria.metric;
        let mut partial = Vec::new();
        for def in bands {
            let at = |message: String| (Some(def.span().start), format!("partial: {message}"));
            let band = def.get_ref();
            let given: Vec<(Metric, f64)> = [(Metric::Flip, band.flip), (Metric::Psnr, band.psnr), (Metric::Rmse, band.rmse), (Metric::Max, band.max)]
                .into_iter()
                .filter_map(|(m, v)| Some((m, v?.value)))
                .collect();
            let limit = match given[..] {
                [(m, limit)] if m == metric => limit,
                [(m, _)] => return Err(at(format!("the case is judged by {}, so a band gives `{}`, not `{}`", metric.name(), metric.name(), m.name()))),
                _ => return Err(at(format!("give one limit, `{} = …`, and `points`", metric.name()))),
            };
            let max_bad_fraction = band.max_bad_fraction.map(|f| f.value);
            // A band that only a passing image meets never earns anything.
            let stricter_mean = if metric.higher_is_better() { limit >= criteria.threshold } else { limit <= criteria.threshold };
            // A band as strict in its mean as passing earns only by giving
            // more bad pixels than passing allows.
            let looser_pixels = matches!((max_bad_fraction, criteria.max_bad_fraction), (Some(band), Some(case)) if band > case);
            if stricter_mean && !looser_pixels {
                let passes = format!("{} {limit} passes the threshold {} already", metric.name(), criteria.threshold);
                return Err(at(match (max_bad_fraction, criteria.max_bad_fraction) {
                    (None, _) => format!("{passes}: a band's limit is looser"),
                    (Some(f), Some(case)) => {
                        format!("{passes}, and at most {} of pixels is within the case's {}: a band is looser in one of them", percent(f), percent(case))
                    }
                    (Some(_), None) => format!("{passes}, and the case sets no bad-pixel limit: a band's limit is looser"),
                }));
            }
            let earns = band.points.value;
            if earns >= points {
                return Err(at(format!("{earns} points is not less than the case's {points}")));
            }
            partial.push(Band { limit, max_bad_fraction, points: earns });
        }
        Ok(Scoring { points, partial })
    }

    /// What `verdict` earns; nothing without one (the sizes differ, the image
    /// is missing or unreadable).
    pub fn award(&self, verdict: Option<&Verdict>) -> Award {
        let nothing = Award { points: 0.0, band: None };
        let Some(verdict) = verdict else { return nothing };
        if verdict.passed() {
            return Award { points: self.points, band: None };
        }
        // The first of the best bands, so that ties name the manifest's first.
        self.partial.iter().filter(|band| band.holds(verdict)).fold(nothing, |best, band| {
            if band.points > best.points || best.band.is_none() { Award { points: band.points, band: Some(*band) } } else { best }
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::criteria::Worst;

    #[derive(Deserialize)]
    struct Bands {
        partial: Vec<Spanned<BandDef>>,
    }

    fn scoring(text: &str, criteria: Criteria) -> Result<Scoring, String> {
        let bands: Bands = toml::from_str(text).unwrap();
        Scoring::of(Some(10.0), &bands.partial, &criteria).map_err(|(_, m)| m)
    }

    /// A verdict with `above` of 100 pixels above the tolerance.
    fn verdict(criteria: Criteria, value: f64, above: usize) -> Verdict {
        Verdict { criteria, value, pixels: 100, pixels_above: above, worst: Worst { x: 0, y: 0, error: 0.5 } }
    }

    fn points(scoring: &Scoring, verdict: &Verdict) -> f64 {
        scoring.award(Some(verdict)).points
    }

    #[test]
    fn the_best_band_that_holds_earns() {
        let criteria = Criteria { max_bad_fraction: None, ..Criteria::for_metric(Metric::Flip) };
        let flip = scoring("[[partial]]\nflip = 0.1\npoints = 2\n[[partial]]\nflip = 0.05\npoints = 6\n", criteria).unwrap();
        assert_eq!(points(&flip, &verdict(criteria, 0.005, 0)), 10.0);
        assert_eq!(points(&flip, &verdict(criteria, 0.03, 1)), 6.0);
        assert_eq!(points(&flip, &verdict(criteria, 0.08, 1)), 2.0);
        assert_eq!(points(&flip, &verdict(criteria, 0.5, 1)), 0.0);
        assert_eq!(flip.award(None), Award { points: 0.0, band: None });
        let award = flip.award(Some(&verdict(criteria, 0.03, 1)));
        assert_eq!(award.band.map(|b| b.conditions(&criteria)), Some("flip <= 0.05".to_string()));
        assert_eq!(flip.award(Some(&verdict(criteria, 0.005, 0))).band, None, "a pass earns by no band");
        let psnr_criteria = Criteria::for_metric(Metric::Psnr);
        let psnr = scoring("[[partial]]\npsnr = 30\npoints = 5\n", psnr_criteria).unwrap();
        assert_eq!(points(&psnr, &verdict(psnr_criteria, 32.0, 0)), 5.0);
        assert_eq!(points(&psnr, &verdict(psnr_criteria, 28.0, 0)), 0.0);
        assert_eq!(psnr.partial[0].conditions(&psnr_criteria), "psnr >= 30");
    }

    #[test]
    fn bands_bound_the_bad_pixels_too() {
        // Passing: mean <= 0.05 and at most 2 % of pixels above 0.2.
        let criteria = Criteria { threshold: 0.05, max_bad_fraction: Some(0.02), ..Criteria::for_metric(Metric::Flip) };
        let bands = "[[partial]]\nflip = 0.08\nmax_bad_fraction = 0.06\npoints = 7\n[[partial]]\nflip = 0.2\npoints = 3\n";
        let ranked = scoring(bands, criteria).unwrap();
        // A small error on many pixels (a wrong highlight model) and a large
        // one on few (a shifted camera) have the same mean, and rank apart.
        let many = verdict(criteria, 0.045, 12);
        let few = verdict(criteria, 0.045, 4);
        assert!(!many.passed() && !few.passed());
        assert_eq!((points(&ranked, &many), points(&ranked, &few)), (3.0, 7.0));
        let award = ranked.award(Some(&few));
        assert_eq!(award.band.unwrap().conditions(&criteria), "flip <= 0.08, at most 6% of pixels above 0.2");
        // A band may be as strict in the mean as passing, if looser in its pixels.
        assert!(scoring("[[partial]]\nflip = 0.05\nmax_bad_fraction = 0.1\npoints = 5\n", criteria).is_ok());
    }

    #[test]
    fn bands_that_make_no_sense_are_refused() {
        let flip = Criteria::for_metric(Metric::Flip);
        for (text, needle) in [
            ("[[partial]]\nrmse = 0.1\npoints = 2\n", "the case is judged by flip, so a band gives `flip`, not `rmse`"),
            ("[[partial]]\npoints = 2\n", "give one limit, `flip = …`, and `points`"),
            ("[[partial]]\nflip = 0.005\npoints = 2\n", "flip 0.005 passes the threshold 0.01 already: a band's limit is looser"),
            (
                "[[partial]]\nflip = 0.005\nmax_bad_fraction = 0.001\npoints = 2\n",
                "flip 0.005 passes the threshold 0.01 already, and at most 0.1% of pixels is within the case's 0.5%: a band is looser in one of them",
            ),
            ("[[partial]]\nflip = 0.1\nmax_bad_fraction = 2\npoints = 2\n", "2 is not a fraction in [0, 1]"),
            ("[[partial]]\nflip = 0.1\npoints = 10\n", "10 points is not less than the case's 10"),
        ] {
            let bands: Result<Bands, _> = toml::from_str(text);
            let e = match bands {
                Ok(bands) => Scoring::of(Some(10.0), &bands.partial, &flip).map_err(|(_, m)| m).unwrap_err(),
                Err(e) => e.to_string(),
            };
            assert!(e.contains(needle), "{text}: {e}");
        }
    }
}
