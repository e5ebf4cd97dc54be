//! The options a manifest gives its cases: how to render (`render`, the
//! options of `glint render`) and how to compare (`compare`). Each field is
//! optional so that a case can override the manifest's defaults field by
//! field. Values are checked while the TOML is read, so a bad one is reported
//! at its line.

use std::fmt;
use std::marker::PhantomData;

use glint_scene::MAX_DEPTH_LIMIT;
use glint_scene::MAX_IMAGE_SIDE;
use serde::de::{self, Deserialize, Deserializer};

use crate::criteria::Criteria;
use crate::metrics::Metric;

#[derive(Debug, Clone, Default, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RenderSettings {
    /// Image width (default: the scene's).
    pub width: Option<Bounded<1, MAX_IMAGE_SIDE>>,
    /// Image height (default: the scene's).
    pub height: Option<Bounded<1, MAX_IMAGE_SIDE>>,
    /// Scale the image to fit inside [W, H], keeping the scene's aspect ratio.
    pub fit: Option<[Bounded<1, MAX_IMAGE_SIDE>; 2]>,
    pub spp: Option<Bounded<1, 4096>>,
    pub seed: Option<u32>,
    pub filter: Option<FilterName>,
    pub max_depth: Option<Bounded<1, MAX_DEPTH_LIMIT>>,
    pub no_cutoff: Option<bool>,
    pub view: Option<ViewName>,
    pub exposure: Option<Checked<PositiveFinite>>,
    pub tone_map: Option<ToneMapName>,
    pub nff_angle: Option<NffAngleName>,
    /// Trace shadow rays (default: the scene's setting).
    pub shadows: Option<bool>,
    /// Trace reflected rays (default: the scene's setting).
    pub reflection: Option<bool>,
    /// Trace refracted rays (default: the scene's setting).
    pub refraction: Option<bool>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum FilterName {
    Box,
    Tent,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ViewName {
    Shaded,
    Normals,
    Depth,
    Albedo,
    Diffuse,
    Id,
    Heatmap,
    #[serde(rename = "ray-depth")]
    RayDepth,
    #[serde(rename = "ray-count")]
    RayCount,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ToneMapName {
    Clamp,
    Reinhard,
    Aces,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum NffAngleName {
    Centers,
    Edges,
}

/// When Gradescope shows a graded case's test to the student, its
/// `visibility` in results.json.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Visibility {
    Visible,
    Hidden,
    AfterDueDate,
    AfterPublished,
}

impl Visibility {
    /// The name as a manifest and Gradescope write it.
    pub fn name(self) -> &'static str {
        match self {
            Visibility::Visible => "visible",
            Visibility::Hidden => "hidden",
            Visibility::AfterDueDate => "after_due_date",
            Visibility::AfterPublished => "after_published",
        }
    }
}

#[derive(Debug, Clone, Default, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CompareSettings {
    pub metric: Option<Metric>,
    pub threshold: Option<Checked<Finite>>,
    pub pixel_tolerance: Option<Checked<NonNegative>>,
    pub max_bad_fraction: Option<Checked<Fraction>>,
}

impl ViewName {
    /// The name as a manifest writes it.
    pub fn name(self) -> &'static str {
        match self {
            ViewName::Shaded => "shaded",
            ViewName::Normals => "normals",
            ViewName::Depth => "depth",
            ViewName::Albedo => "albedo",
            ViewName::Diffuse => "diffuse",
            ViewName::Id => "id",
            ViewName::Heatmap => "heatmap",
            ViewName::RayDepth => "ray-depth",
            ViewName::RayCount => "ray-count",
        }
    }
}

impl RenderSettings {
    /// `self` with every field that `over` sets replaced.
    pub fn overridden_by(&self, over: &RenderSettings) -> RenderSettings {
        RenderSettings {
            width: over.width.or(self.width),
            height: over.height.or(self.height),
            fit: over.fit.or(self.fit),
            spp: over.spp.or(self.spp),
            seed: over.seed.or(self.seed),
            filter: over.filter.or(self.filter),
            max_depth: over.max_depth.or(self.max_depth),
            no_cutoff: over.no_cutoff.or(self.no_cutoff),
            view: over.view.or(self.view),
            exposure: over.exposure.or(self.exposure),
            tone_map: over.tone_map.or(self.tone_map),
            nff_angle: over.nff_angle.or(self.nff_angle),
            shadows: over.shadows.or(self.shadows),
            reflection: over.reflection.or(self.reflection),
            refraction: over.refraction.or(self.refraction),
        }
    }
}

impl CompareSettings {
    /// `self` with every field that `over` sets replaced. A different metric
    /// drops the limits set for the old one: a FLIP threshold means nothing
    /// as a PSNR.
    pub fn overridden_by(&self, over: &CompareSettings) -> CompareSettings {
        let base = match over.metric {
            Some(metric) if Some(metric) != self.metric => &CompareSettings::default(),
            _ => self,
        };
        CompareSettings {
            metric: over.metric.or(base.metric),
            threshold: over.threshold.or(base.threshold),
            pixel_tolerance: over.pixel_tolerance.or(base.pixel_tolerance),
            max_bad_fraction: over.max_bad_fraction.or(base.max_bad_fraction),
        }
    }

    /// The criteria: the metric's defaults where nothing is set.
    pub fn criteria(&self) -> Criteria {
        let defaults = Criteria::for_metric(self.metric.unwrap_or(Metric::Flip));
        Criteria {
            metric: defaults.metric,
            threshold: self.threshold.map_or(defaults.threshold, |v| v.value),
            pixel_tolerance: self.pixel_tolerance.map_or(defaults.pixel_tolerance, |v| v.value),
            max_bad_fraction: self.max_bad_fraction.map(|v| v.value).or(defaults.max_bad_fraction),
        }
    }
}

/// A whole number in `LO..=HI`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Bounded<const LO: u32, const HI: u32>(pub u32);

impl<'de, const LO: u32, const HI: u32> Deserialize<'de> for Bounded<LO, HI> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let v = i64::deserialize(d)?;
        u32::try_from(v)
            .ok()
            .filter(|v| (LO..=HI).contains(v))
            .map(Bounded)
            .ok_or_else(|| de::Error::custom(format!("{v} is not in {LO}..={HI}")))
    }
}

/// A condition a number must meet, named for the error message.
pub trait Condition {
    const WHAT: &'static str;
    fn holds(v: f64) -> bool;
}

/// A number that meets `C`.
pub struct Checked<C> {
    pub value: f64,
    condition: PhantomData<C>,
}

// Derives would demand the same of the marker type `C`.
impl<C> Clone for Checked<C> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<C> Copy for Checked<C> {}
impl<C> PartialEq for Checked<C> {
    fn eq(&self, other: &Self) -> bool {
        self.value == other.value
    }
}
impl<C> fmt::Debug for Checked<C> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.value.fmt(f)
    }
}

impl<'de, C: Condition> Deserialize<'de> for Checked<C> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        // TOML integers are numbers too: `threshold = 40`.
        let value = NumberOrInteger::deserialize(d)?.0;
        if C::holds(value) {
            Ok(Checked { value, condition: PhantomData })
        } else {
            Err(de::Error::custom(format!("{value} is not {}", C::WHAT)))
        }
    }
}

struct NumberOrInteger(f64);

impl<'de> Deserialize<'de> for NumberOrInteger {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Visitor;
        impl de::Visitor<'_> for Visitor {
            type Value = NumberOrInteger;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a number")
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<Self::Value, E> {
                Ok(NumberOrInteger(v))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Self::Value, E> {
                Ok(NumberOrInteger(v as f64))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Self::Value, E> {
                Ok(NumberOrInteger(v as f64))
            }
        }
        d.deserialize_any(Visitor)
    }
}

#[derive(Debug)]
pub struct Finite;
impl Condition for Finite {
    const WHAT: &'static str = "a finite number";
    fn holds(v: f64) -> bool {
        v.is_finite()
    }
}

#[derive(Debug)]
pub struct NonNegative;
impl Condition for NonNegative {
    const WHAT: &'static str = "a finite number >= 0";
    fn holds(v: f64) -> bool {
        v.is_finite() && v >= 0.0
    }
}

#[derive(Debug)]
pub struct PositiveFinite;
impl Condition for PositiveFinite {
    const WHAT: &'static str = "a positive finite number";
    fn holds(v: f64) -> bool {
        v.is_finite() && v > 0.0
    }
}

#[derive(Debug)]
pub struct Fraction;
impl Condition for Fraction {
    const WHAT: &'static str = "a fraction in [0, 1]";
    fn holds(v: f64) -> bool {
        (0.0..=1.0).contains(&v)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn compare(text: &str) -> CompareSettings {
        toml::from_str(text).unwrap()
    }

    #[test]
    fn a_case_overrides_field_by_field() {
        let defaults: RenderSettings = toml::from_str("spp = 4\nseed = 1\nfilter = \"tent\"").unwrap();
        let case: RenderSettings = toml::from_str("spp = 16\nview = \"normals\"").unwrap();
        let merged = defaults.overridden_by(&case);
        assert_eq!(merged.spp, Some(Bounded(16)));
        assert_eq!(merged.seed, Some(1));
        assert_eq!(merged.filter, Some(FilterName::Tent));
        assert_eq!(merged.view, Some(ViewName::Normals));
    }

    #[test]
    fn changing_the_metric_drops_the_old_metrics_limits() {
        let defaults = compare("metric = \"flip\"\nthreshold = 0.02\nmax_bad_fraction = 0.1");
        let same = defaults.overridden_by(&compare("pixel_tolerance = 0.3")).criteria();
        assert_eq!((same.metric, same.threshold, same.pixel_tolerance, same.max_bad_fraction), (Metric::Flip, 0.02, 0.3, Some(0.1)));
        let psnr = defaults.overridden_by(&compare("metric = \"psnr\"")).criteria();
        assert_eq!(psnr, Criteria::for_metric(Metric::Psnr));
        let psnr = defaults.overridden_by(&compare("metric = \"psnr\"\nthreshold = 35")).criteria();
        assert_eq!(psnr.threshold, 35.0);
    }

    #[test]
    fn view_names_read_back_as_their_view() {
        for view in [
            ViewName::Shaded,
            ViewName::Normals,
            ViewName::Depth,
            ViewName::Albedo,
            ViewName::Diffuse,
            ViewName::Id,
            ViewName::Heatmap,
            ViewName::RayDepth,
            ViewName::RayCount,
        ] {
            let read: RenderSettings = toml::from_str(&format!("view = \"{}\"", view.name())).unwrap();
            assert_eq!(read.view, Some(view));
        }
    }

    #[test]
    fn bad_values_are_refused_with_the_reason() {
        for (text, needle) in [
            ("spp = 0", "0 is not in 1..=4096"),
            ("max_depth = 17", "17 is not in 1..=16"),
            ("fit = [160, -1]", "-1 is not in 1..="),
            ("exposure = 0.0", "0 is not a positive finite number"),
            ("filter = \"gauss\"", "unknown variant `gauss`"),
            ("sp = 4", "unknown field `sp`"),
        ] {
            let e = toml::from_str::<RenderSettings>(text).unwrap_err().to_string();
            assert!(e.contains(needle), "{text}: {e}");
        }
        for (text, needle) in [
            ("max_bad_fraction = 1.5", "1.5 is not a fraction in [0, 1]"),
            ("pixel_tolerance = -0.1", "-0.1 is not a finite number >= 0"),
            ("threshold = nan", "NaN is not a finite number"),
            ("metric = \"ssim\"", "unknown variant `ssim`"),
        ] {
            let e = toml::from_str::<CompareSettings>(text).unwrap_err().to_string();
            assert!(e.contains(needle), "{text}: {e}");
        }
    }

    #[test]
    fn visibilities_read_back_as_gradescope_names_them() {
        #[derive(Debug, serde::Deserialize)]
        struct Case {
            visibility: Visibility,
        }
        for visibility in [Visibility::Visible, Visibility::Hidden, Visibility::AfterDueDate, Visibility::AfterPublished] {
            let read: Case = toml::from_str(&format!("visibility = \"{}\"", visibility.name())).unwrap();
            assert_eq!(read.visibility, visibility);
        }
        let e = toml::from_str::<Case>("visibility = \"secret\"").unwrap_err().to_string();
        assert!(e.contains("unknown variant `secret`"), "{e}");
    }
}
