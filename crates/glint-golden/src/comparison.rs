//! One comparison as a test reports it: a tested image held against its
//! reference by a case's criteria, with a one-line detail and, when it fails
//! and a report wants them, the images that show why. The golden runner and
//! grading both judge images this way.

use crate::criteria::{judge, Criteria, Verdict};
use crate::diff_map::diff_map;
use crate::image_io::{encode_png, LinearImage};
use crate::metrics::measure;
use crate::region::{magnified, worst_region};

/// An image encoded as PNG, with its size.
#[derive(Debug, Clone, PartialEq)]
pub struct Png {
    pub bytes: Vec<u8>,
    pub width: u32,
    pub height: u32,
}

impl Png {
    pub fn of_rgb(rgb: &image::RgbImage) -> Self {
        Png { bytes: encode_png(rgb), width: rgb.width(), height: rgb.height() }
    }

    pub fn of_linear(image: &LinearImage) -> Self {
        Png { bytes: image.to_png(), width: image.width, height: image.height }
    }
}

/// The images of a failing case for the HTML report, each with its role
/// (`reference`, `render`, `diff`…), which names its file and caption.
#[derive(Debug, Clone, PartialEq)]
pub struct ReportImages {
    /// Whole images side by side.
    pub whole: Vec<(&'static str, Png)>,
    /// The worst region of the reference and of the tested image, magnified.
    pub zoomed: Vec<(&'static str, Png)>,
}

impl ReportImages {
    /// Only the tested image: there is no reference to set beside it.
    pub fn alone(role: &'static str, tested: &LinearImage) -> Self {
        ReportImages { whole: vec![(role, Png::of_linear(tested))], zoomed: Vec::new() }
    }
}

/// How the tested image is named in details and reports.
#[derive(Debug, Clone, Copy)]
pub struct Roles {
    pub reference: &'static str,
    pub tested: &'static str,
}

pub struct Comparison {
    /// `None` when the sizes differ.
    pub verdict: Option<Verdict>,
    /// The verdict's summary and where the worst region is, or the sizes.
    pub detail: String,
    pub images: Option<ReportImages>,
}

impl Comparison {
    pub fn passed(&self) -> bool {
        self.verdict.as_ref().is_some_and(Verdict::passed)
    }
}

/// Holds `tested` against `reference`; `report_images` asks for the images
/// of a failure.
pub fn compare(reference: &LinearImage, tested: &LinearImage, criteria: &Criteria, roles: Roles, report_images: bool) -> Comparison {
    let measurement = match measure(reference, tested) {
        Ok(measurement) => measurement,
        Err(e) => {
            let detail = format!(
                "wrong size: the {} is {}x{}, the {} {}x{}",
                roles.tested, e.test.0, e.test.1, roles.reference, e.reference.0, e.reference.1
            );
            let images = report_images.then(|| ReportImages {
                whole: vec![(roles.reference, Png::of_linear(reference)), (roles.tested, Png::of_linear(tested))],
                zoomed: Vec::new(),
            });
            return Comparison { verdict: None, detail, images };
        }
    };
    let verdict = judge(&measurement, criteria);
    if verdict.passed() {
        return Comparison { detail: verdict.summary(), verdict: Some(verdict), images: None };
    }
    let region = worst_region(measurement.pixel_errors(criteria.metric), measurement.width, measurement.height);
    let detail = format!("{}, worst region {region}", verdict.summary());
    let images = report_images.then(|| ReportImages {
        whole: vec![
            (roles.reference, Png::of_linear(reference)),
            (roles.tested, Png::of_linear(tested)),
            ("diff", Png::of_rgb(&diff_map(&measurement, criteria.metric))),
        ],
        zoomed: vec![
            (roles.reference, Png::of_rgb(&magnified(reference, region))),
            (roles.tested, Png::of_rgb(&magnified(tested, region))),
        ],
    });
    Comparison { verdict: Some(verdict), detail, images }
}
