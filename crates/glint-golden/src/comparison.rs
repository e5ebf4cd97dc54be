//! One comparison as a test reports it: a tested image held against its
//! reference by a case's criteria, with a one-line detail and, when it fails
//! and a report wants them, the images that show why. The golden runner and
//! grading both judge images this way.

use crate::criteria::{judge, Criteria, Verdict};
use crate::diff_map::diff_map;
use crate::image_io::{encode_png, LinearImage};
use crate::metrics::measure;
use crate::region::{magnified, outline, worst_region, Region};

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

/// The role of the error map among a report's images.
pub const DIFF_ROLE: &str = "diff";

impl ReportImages {
    /// Only the tested image: there is no reference to set beside it.
    pub fn alone(role: &'static str, tested: &LinearImage) -> Self {
        ReportImages { whole: vec![(role, Png::of_linear(tested))], zoomed: Vec::new() }
    }

    /// Outlines `region` on the whole image of `role`, if there is one.
    pub fn outline(&mut self, role: &str, region: Region) {
        if let Some((_, png)) = self.whole.iter_mut().find(|(r, _)| *r == role) {
            let mut rgb = image::load_from_memory_with_format(&png.bytes, image::ImageFormat::Png).expect("a PNG this crate encoded").to_rgb8();
            outline(&mut rgb, region);
            *png = Png::of_rgb(&rgb);
        }
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
            (DIFF_ROLE, Png::of_rgb(&diff_map(&measurement, criteria.metric))),
        ],
        zoomed: vec![
            (roles.reference, Png::of_rgb(&magnified(reference, region))),
            (roles.tested, Png::of_rgb(&magnified(tested, region))),
        ],
    });
    Comparison { verdict: Some(verdict), detail, images }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::criteria::Criteria;
    use crate::metrics::Metric;
    use crate::region::OUTLINE_COLOUR;

    #[test]
    fn a_region_is_outlined_on_the_diff_map_alone() {
        let reference = LinearImage { width: 32, height: 24, pixels: vec![[0.2; 3]; 32 * 24] };
        let mut tested = reference.clone();
        for y in 9..12 {
            tested.pixels[y * 32 + 11..y * 32 + 14].fill([1.0, 0.0, 0.0]);
        }
        let roles = Roles { reference: "reference", tested: "submission" };
        let mut images = compare(&reference, &tested, &Criteria::for_metric(Metric::Flip), roles, true).images.unwrap();
        let before = images.clone();
        let region = Region { x: 8, y: 6, width: 8, height: 8 };
        images.outline(DIFF_ROLE, region);
        let decode = |png: &Png| image::load_from_memory(&png.bytes).unwrap().to_rgb8();
        let diff = decode(&images.whole[2].1);
        assert_eq!(images.whole[2].0, DIFF_ROLE);
        for (x, y) in [(8, 6), (15, 6), (9, 13), (15, 13), (12, 7)] {
            assert_eq!(diff.get_pixel(x, y).0, OUTLINE_COLOUR.0, "({x}, {y})");
        }
        // Inside and outside the box, the map is as it was.
        let old = decode(&before.whole[2].1);
        for (x, y) in [(12, 10), (0, 0), (7, 6), (16, 14)] {
            assert_eq!(diff.get_pixel(x, y), old.get_pixel(x, y), "({x}, {y})");
        }
        assert_eq!((&images.whole[..2], &images.zoomed), (&before.whole[..2], &before.zoomed));
    }
}
