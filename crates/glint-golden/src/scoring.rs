//! Points for a graded case: all of its `points` when the image passes, else
//! the points of the best partial-credit band its metric value falls in,
//! else none. A manifest writes a band as
//!
//! ```toml
//! [[case.partial]]
//! flip = 0.05     # the case's metric, and the loosest value that earns
//! points = 5
//! ```

use serde::Deserialize;
use toml::Spanned;

use crate::criteria::{Criteria, Verdict};
use crate::metrics::Metric;
use crate::settings::{Checked, Finite, NonNegative};

/// Points when no `points` is given.
pub const DEFAULT_POINTS: f64 = 1.0;

#[derive(Debug, Clone, PartialEq)]
pub struct Scoring {
    pub points: f64,
    /// Bands with their metric limit, in the manifest's order.
    pub partial: Vec<Band>,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Band {
    /// The loosest value of the case's metric that still earns `points`.
    pub limit: f64,
    pub points: f64,
}

/// `[[case.partial]]` as written: one metric's limit and the points.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BandDef {
    flip: Option<Checked<Finite>>,
    psnr: Option<Checked<Finite>>,
    rmse: Option<Checked<Finite>>,
    max: Option<Checked<Finite>>,
    points: Checked<NonNegative>,
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
            let stricter = if metric.higher_is_better() { limit >= criteria.threshold } else { limit <= criteria.threshold };
            if stricter {
                return Err(at(format!("{} {limit} passes the threshold {} already: a band's limit is looser", metric.name(), criteria.threshold)));
            }
            let earns = band.points.value;
            if earns >= points {
                return Err(at(format!("{earns} points is not less than the case's {points}")));
            }
            partial.push(Band { limit, points: earns });
        }
        Ok(Scoring { points, partial })
    }

    /// The points `verdict` earns; none without one (the sizes differ, the
    /// image is missing or unreadable).
    pub fn earned(&self, verdict: Option<&Verdict>) -> f64 {
        let Some(verdict) = verdict else { return 0.0 };
        if verdict.passed() {
            return self.points;
        }
        let higher = verdict.criteria.metric.higher_is_better();
        self.partial
            .iter()
            .filter(|band| if higher { verdict.value >= band.limit } else { verdict.value <= band.limit })
            .map(|band| band.points)
            .fold(0.0, f64::max)
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

    fn scoring(text: &str, metric: Metric) -> Result<Scoring, String> {
        let bands: Bands = toml::from_str(text).unwrap();
        Scoring::of(Some(10.0), &bands.partial, &Criteria::for_metric(metric)).map_err(|(_, m)| m)
    }

    fn verdict(metric: Metric, value: f64, passed: bool) -> Verdict {
        let criteria = Criteria { max_bad_fraction: None, ..Criteria::for_metric(metric) };
        let pixels_above = usize::from(!passed);
        Verdict { criteria, value, pixels: 100, pixels_above, worst: Worst { x: 0, y: 0, error: 0.5 } }
    }

    #[test]
    fn the_best_band_that_holds_earns() {
        let flip = scoring("[[partial]]\nflip = 0.1\npoints = 2\n[[partial]]\nflip = 0.05\npoints = 6\n", Metric::Flip).unwrap();
        assert_eq!(flip.earned(Some(&verdict(Metric::Flip, 0.005, true))), 10.0);
        assert_eq!(flip.earned(Some(&verdict(Metric::Flip, 0.03, false))), 6.0);
        assert_eq!(flip.earned(Some(&verdict(Metric::Flip, 0.08, false))), 2.0);
        assert_eq!(flip.earned(Some(&verdict(Metric::Flip, 0.5, false))), 0.0);
        assert_eq!(flip.earned(None), 0.0);
        let psnr = scoring("[[partial]]\npsnr = 30\npoints = 5\n", Metric::Psnr).unwrap();
        assert_eq!(psnr.earned(Some(&verdict(Metric::Psnr, 32.0, false))), 5.0);
        assert_eq!(psnr.earned(Some(&verdict(Metric::Psnr, 28.0, false))), 0.0);
    }

    #[test]
    fn bands_that_make_no_sense_are_refused() {
        for (text, needle) in [
            ("[[partial]]\nrmse = 0.1\npoints = 2\n", "the case is judged by flip, so a band gives `flip`, not `rmse`"),
            ("[[partial]]\npoints = 2\n", "give one limit, `flip = …`, and `points`"),
            ("[[partial]]\nflip = 0.005\npoints = 2\n", "flip 0.005 passes the threshold 0.01 already"),
            ("[[partial]]\nflip = 0.1\npoints = 10\n", "10 points is not less than the case's 10"),
        ] {
            let e = scoring(text, Metric::Flip).unwrap_err();
            assert!(e.starts_with("partial: ") && e.contains(needle), "{text}: {e}");
        }
    }
}
