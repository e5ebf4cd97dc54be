//! Gradescope's autograder results, the `results.json` its harness reads
//! from `/autograder/results/` after each submission: the total `score`, an
//! `output` for the whole submission, and one entry in `tests` per case with
//! its `name`, `score`, `max_score`, `status` and `output`, and the case's
//! `visibility` where the manifest sets one
//! (<https://gradescope-autograders.readthedocs.io/en/latest/specs/>).
//!
//! A failed test's `output` is Markdown (`"output_format": "md"`): the
//! verdict, the diagnosis with its advice in bold, the settings and files,
//! then the reference, the submission and the diff map, small, inline as
//! data URIs, since results.json is all Gradescope keeps. A passed test's
//! stays plain text (docs/decisions/056-gradescope-output-with-images.md).

use base64::engine::general_purpose::STANDARD;
use base64::Engine;
use serde_json::json;

use crate::comparison::Png;
use crate::grading::Grades;
use crate::manifest::GradedCase;
use crate::html::points_text;
use crate::image_io::encode_png;
use crate::markup::escape_markdown;
use crate::runner::{sentence_and_advice, Outcome, Summary};

/// Images in a test's output are at most this wide: three side by side fit
/// Gradescope's page.
const IMAGE_WIDTH: u32 = 256;

/// The images of one results.json take at most this many bytes of base64;
/// a failed test whose images would pass that shows none. Gradescope
/// documents no size limit; this keeps results.json small however many
/// cases fail.
const IMAGE_BUDGET: usize = 1536 * 1024;

/// `grades` are one student's outcomes of `cases`, in the same order.
pub fn results_json(suite_name: &str, cases: &[&GradedCase], grades: &Grades) -> String {
    let total = grades.total();
    let mut budget = IMAGE_BUDGET;
    let tests: Vec<serde_json::Value> = grades
        .outcomes
        .iter()
        .zip(cases)
        .map(|(outcome, case)| {
            let points = outcome.points.expect("a graded outcome has points");
            let failed = outcome.status.failed();
            let mut test = json!({
                "name": outcome.name,
                "score": points.earned,
                "max_score": points.possible,
                "status": if failed { "failed" } else { "passed" },
                "output": outcome.explanation(),
            });
            if failed {
                test["output"] = failed_output(outcome, &mut budget).into();
                test["output_format"] = "md".into();
            }
            if let Some(visibility) = case.visibility {
                test["visibility"] = visibility.name().into();
            }
            test
        })
        .collect();
    let output = format!("{suite_name}: {}; {} points", Summary::of(&grades.outcomes), points_text(total));
    let results = json!({ "score": total.earned, "output": output, "tests": tests });
    serde_json::to_string_pretty(&results).expect("JSON values always serialise") + "\n"
}

/// A failed test's output in Markdown; its images are taken from `budget`.
fn failed_output(outcome: &Outcome, budget: &mut usize) -> String {
    let mut md = escape_markdown(outcome.verdict());
    if let Some(diagnosis) = &outcome.diagnosis {
        let (lead, advice) = sentence_and_advice(diagnosis);
        md += &format!("\n\n{}**{}**", escape_markdown(&lead), escape_markdown(advice));
    }
    md += "\n\n";
    if let Some(settings) = &outcome.settings {
        md += &format!("- settings: {}\n", escape_markdown(settings));
    }
    for (role, path) in &outcome.files {
        md += &format!("- {role}: {}\n", escape_markdown(&path.display().to_string()));
    }
    let Some(images) = outcome.images.as_ref().filter(|i| !i.whole.is_empty()) else { return md };
    let shown: Vec<(&str, String)> = images.whole.iter().map(|(role, png)| (*role, STANDARD.encode(smaller(png)))).collect();
    let size: usize = shown.iter().map(|(_, data)| data.len()).sum();
    if size > *budget {
        return md + "\nImages left out: this page holds as many as it can.\n";
    }
    *budget -= size;
    md += "\n";
    let inline: Vec<String> = shown.iter().map(|(role, data)| format!("![{role}](data:image/png;base64,{data})")).collect();
    md += &inline.join(" ");
    let roles: Vec<&str> = shown.iter().map(|(role, _)| *role).collect();
    md += &format!("\n\n{}", roles.join(", "));
    if let Some(diagnosis) = &outcome.diagnosis {
        md += &format!("; the cyan box on the diff marks {}", diagnosis.region);
    }
    md + "\n"
}

/// `png` at most `IMAGE_WIDTH` wide, scaled down with its aspect ratio kept.
fn smaller(png: &Png) -> Vec<u8> {
    if png.width <= IMAGE_WIDTH {
        return png.bytes.clone();
    }
    let rgb = image::load_from_memory_with_format(&png.bytes, image::ImageFormat::Png).expect("a PNG this crate encoded").to_rgb8();
    let height = (u64::from(png.height) * u64::from(IMAGE_WIDTH)).div_ceil(u64::from(png.width)) as u32;
    encode_png(&image::imageops::resize(&rgb, IMAGE_WIDTH, height.max(1), image::imageops::FilterType::Triangle))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::comparison::ReportImages;
    use crate::criteria::Criteria;
    use crate::diagnosis::{Diagnosis, Effect};
    use crate::grading::Student;
    use crate::manifest::Reference;
    use crate::metrics::Metric;
    use crate::region::Region;
    use crate::runner::{Points, Status};
    use crate::scoring::Scoring;
    use crate::settings::Visibility;

    fn outcome(name: &str, status: Status, earned: f64, possible: f64) -> Outcome {
        Outcome {
            name: name.into(),
            file_stem: name.into(),
            files: vec![("submission", format!("ann/{name}.png").into()), ("reference scene", format!("{name}.toml").into())],
            settings: Some("view shaded, max depth 5, 1 spp, 48x36".into()),
            status,
            detail: format!("detail of {name}"),
            points: Some(Points { earned, possible }),
            images: None,
            diagnosis: None,
        }
    }

    fn case(name: &str, visibility: Option<Visibility>) -> GradedCase {
        GradedCase {
            name: name.into(),
            image: format!("{name}.png"),
            reference: Reference::Scene(format!("{name}.toml").into()),
            render: Default::default(),
            criteria: Criteria::for_metric(Metric::Flip),
            scoring: Scoring { points: 10.0, partial: Vec::new() },
            visibility,
        }
    }

    fn grades(outcomes: Vec<Outcome>) -> Grades {
        Grades { student: Student { name: "ann".into(), dir: "ann".into(), report_folder: "ann".into() }, outcomes }
    }

    fn results(cases: &[&GradedCase], grades: &Grades) -> serde_json::Value {
        serde_json::from_str(&results_json("course", cases, grades)).unwrap()
    }

    /// A PNG of `width` × `height` pixels, each a colour of its own, so that
    /// it compresses little.
    fn png(width: u32, height: u32) -> Png {
        Png::of_rgb(&image::RgbImage::from_fn(width, height, |x, y| image::Rgb([(x * 7 + y) as u8, (y * 13 + x * x) as u8, (x * y) as u8])))
    }

    fn no_shadows() -> Diagnosis {
        Diagnosis {
            effect: Effect::NoShadows,
            what: "without shadow rays".into(),
            advice: "check your shadow rays",
            flip: 0.002,
            full_flip: 0.155,
            region: Region { x: 8, y: 4, width: 16, height: 16 },
        }
    }

    /// Each image of a test's Markdown output, decoded: its alt text and image.
    fn inline_images(output: &str) -> Vec<(String, image::RgbImage)> {
        output
            .split("![")
            .skip(1)
            .map(|part| {
                let (alt, rest) = part.split_once("](data:image/png;base64,").unwrap();
                let data = rest.split(')').next().unwrap();
                (alt.to_string(), image::load_from_memory(&STANDARD.decode(data).unwrap()).unwrap().to_rgb8())
            })
            .collect()
    }

    #[test]
    fn the_documented_fields_are_there() {
        let grades = grades(vec![outcome("balls", Status::Passed, 10.0, 10.0), outcome("room", Status::Mismatch, 2.5, 5.0)]);
        let (balls, room) = (case("balls", None), case("room", Some(Visibility::AfterDueDate)));
        let results = results(&[&balls, &room], &grades);
        assert_eq!(results["score"], 12.5);
        assert_eq!(results["output"], "course: 1 passed, 1 failed; 12.5/15 points");
        let tests = results["tests"].as_array().unwrap();
        assert_eq!(tests.len(), 2);
        assert_eq!((&tests[1]["name"], &tests[1]["score"], &tests[1]["max_score"], &tests[1]["status"]), (&json!("room"), &json!(2.5), &json!(5.0), &json!("failed")));
        assert_eq!(tests[0]["status"], "passed");
        // Gradescope's default unless the case sets its own.
        assert_eq!((tests[0].get("visibility"), &tests[1]["visibility"]), (None, &json!("after_due_date")));
        // A pass is plain text, Gradescope's default; a failure Markdown.
        assert_eq!((tests[0].get("output_format"), &tests[1]["output_format"]), (None, &json!("md")));
        assert_eq!(tests[0]["output"], "detail of balls\nsettings: view shaded, max depth 5, 1 spp, 48x36\nsubmission: ann/balls.png\nreference scene: balls.toml");
        assert_eq!(tests[1]["output"], "detail of room\n\n- settings: view shaded, max depth 5, 1 spp, 48x36\n- submission: ann/room.png\n- reference scene: room.toml\n");
    }

    #[test]
    fn a_failed_test_shows_its_diagnosis_and_images() {
        let mut failed = outcome("shadow_s1", Status::Mismatch, 2.0, 10.0);
        failed.detail = "flip 0.154708 > 0.01, worst region 16x16 at (8, 4); partial credit: flip <= 0.2".into();
        failed.images = Some(ReportImages { whole: vec![("reference", png(48, 36)), ("submission", png(48, 36)), ("diff", png(200, 70))], zoomed: vec![("reference", png(192, 192))] });
        failed.diagnose(no_shadows());
        let case = case("shadow_s1", None);
        let results = results(&[&case], &grades(vec![failed]));
        let output = results["tests"][0]["output"].as_str().unwrap();
        let paragraphs: Vec<&str> = output.split("\n\n").collect();
        // The verdict, then the diagnosis with its advice in bold, as paragraphs of their own.
        assert_eq!(paragraphs[0], "flip 0.154708 &gt; 0.01, worst region 16x16 at (8, 4); partial credit: flip &lt;= 0.2");
        assert_eq!(
            paragraphs[1],
            "closest to Glint's render without shadow rays (flip 0.002, against 0.155 for the full render; the two differ most in 16x16 at (8, 4)): **check your shadow rays**"
        );
        assert!(paragraphs[2].starts_with("- settings: view shaded, max depth 5, 1 spp, 48x36\n- submission: ann/shadow\\_s1.png\n"), "{output}");
        // The whole images, not the magnified ones, each as its report holds it.
        let images = inline_images(output);
        let roles: Vec<&str> = images.iter().map(|(role, _)| role.as_str()).collect();
        assert_eq!(roles, ["reference", "submission", "diff"]);
        assert_eq!(images[0].1, image::load_from_memory(&png(48, 36).bytes).unwrap().to_rgb8());
        assert_eq!(images[2].1.dimensions(), (200, 70));
        assert!(output.ends_with("\n\nreference, submission, diff; the cyan box on the diff marks 16x16 at (8, 4)\n"), "{output}");
    }

    #[test]
    fn images_are_small_and_a_class_of_failures_stays_within_the_budget() {
        let wide = || {
            let mut o = outcome("wide", Status::Mismatch, 0.0, 10.0);
            o.images = Some(ReportImages { whole: vec![("reference", png(640, 480)), ("submission", png(640, 480)), ("diff", png(640, 514))], zoomed: Vec::new() });
            o
        };
        let cases: Vec<GradedCase> = (0..20).map(|_| case("wide", None)).collect();
        let cases: Vec<&GradedCase> = cases.iter().collect();
        let text = results_json("course", &cases, &grades((0..20).map(|_| wide()).collect()));
        let results: serde_json::Value = serde_json::from_str(&text).unwrap();
        let outputs: Vec<&str> = results["tests"].as_array().unwrap().iter().map(|t| t["output"].as_str().unwrap()).collect();
        let first = inline_images(outputs[0]);
        assert_eq!(first.iter().map(|(_, i)| i.dimensions()).collect::<Vec<_>>(), [(256, 192), (256, 192), (256, 206)]);
        // Every failure says why it fails; the images stop at the budget.
        assert!(outputs.iter().all(|o| o.contains("\n- submission: ann/wide.png\n")));
        let with_images = outputs.iter().filter(|o| o.contains("![")).count();
        assert!((1..20).contains(&with_images), "{with_images}");
        assert!(outputs[with_images..].iter().all(|o| o.ends_with("\nImages left out: this page holds as many as it can.\n")));
        assert!(text.len() < IMAGE_BUDGET + 64 * 1024, "{} bytes", text.len());
    }
}
