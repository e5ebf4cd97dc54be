//! The HTML report: a table of every case with its settings, then for each
//! failing case its reference, tested image and error map side by side, and
//! the worst region of the first two magnified. A diagnosed case says what
//! the image most likely got wrong, and its error map outlines where. The page and its PNG images
//! go in one directory, linked by relative names, so the directory can be
//! kept as a CI artifact and opened anywhere.

use std::fmt::Write;
use std::path::{Path, PathBuf};

use crate::comparison::Png;
use crate::markup::escape;
use crate::runner::{sentence_and_advice, Outcome, Points, Status, Summary};

pub const STYLE: &str = "body { font-family: sans-serif; margin: 1.5em; color: #222; background: #fafafa }
table { border-collapse: collapse; margin-bottom: 2em }
th, td { text-align: left; padding: 0.25em 0.8em; border-bottom: 1px solid #ddd; vertical-align: top }
.failed { color: #a00 }
.diagnosis { font-size: 1.1em }
.images { display: flex; flex-wrap: wrap; gap: 1.5em; align-items: flex-start; margin-bottom: 1em }
figure { margin: 0 }
img { image-rendering: pixelated; border: 1px solid #bbb; background: #fff }
code { font-size: 0.9em }";

/// Images are shown at least this wide, in whole multiples of their size so
/// that pixels stay square and sharp.
const SHOWN_WIDTH: u32 = 320;

/// Writes `DIR/index.html` and the images of each failing case, atomically;
/// returns the page's path. The error names the file that failed.
pub fn write_report(dir: &Path, title: &str, outcomes: &[Outcome]) -> Result<PathBuf, String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: cannot create the report directory: {e}", dir.display()))?;
    for outcome in outcomes {
        let (whole, zoomed) = report_images(outcome);
        for (name, _, png) in whole.iter().chain(&zoomed) {
            write_file(&dir.join(name), &png.bytes)?;
        }
    }
    let index = dir.join("index.html");
    write_file(&index, page(title, outcomes).as_bytes())?;
    Ok(index)
}

/// Writes `path` atomically; the error names it.
pub fn write_file(path: &Path, bytes: &[u8]) -> Result<(), String> {
    glint_gpu::write_atomically(path, bytes).map_err(|e| format!("{}: cannot write: {e}", path.display()))
}

/// An image of the report: its file name, its role and the image.
type Figure<'a> = (String, &'static str, &'a Png);

/// The whole images of an outcome's report, and the magnified ones.
fn report_images(outcome: &Outcome) -> (Vec<Figure<'_>>, Vec<Figure<'_>>) {
    let Some(images) = &outcome.images else { return (Vec::new(), Vec::new()) };
    (named(&outcome.file_stem, &images.whole, ""), named(&outcome.file_stem, &images.zoomed, "-zoom"))
}

fn named<'a>(stem: &str, images: &'a [(&'static str, Png)], suffix: &str) -> Vec<Figure<'a>> {
    images.iter().map(|(role, png)| (format!("{stem}-{role}{suffix}.png"), *role, png)).collect()
}

/// `6/10`, in at most two decimals.
pub fn points_text(points: Points) -> String {
    let short = |v: f64| {
        let s = format!("{v:.2}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    };
    format!("{}/{}", short(points.earned), short(points.possible))
}

/// The page's HTML.
pub fn page(title: &str, outcomes: &[Outcome]) -> String {
    let title = escape(title);
    let graded = outcomes.iter().any(|o| o.points.is_some());
    let mut html = String::new();
    let _ = write!(
        html,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>glint test: {title}</title>\n<style>\n{STYLE}\n</style>\n</head>\n<body>\n<h1>glint test: {title}</h1>\n<p>{}</p>\n",
        Summary::of(outcomes)
    );
    let points_header = if graded { "<th>points</th>" } else { "" };
    let _ = writeln!(html, "<table>\n<tr><th>case</th><th>result</th>{points_header}<th>settings</th><th>detail</th></tr>");
    for outcome in outcomes {
        let name = escape(&outcome.name);
        let (class, result) = match outcome.status {
            Status::Passed => ("", "ok"),
            Status::Blessed => ("", "blessed"),
            Status::Mismatch => (" class=\"failed\"", "differs"),
            Status::NoGolden => (" class=\"failed\"", "no golden"),
            Status::NoImage => (" class=\"failed\"", "no image"),
            Status::Error => (" class=\"failed\"", "error"),
        };
        let linked = if outcome.status.failed() { format!("<a href=\"#{}\">{name}</a>", anchor(outcome)) } else { name };
        let points = outcome.points.map_or(String::new(), |p| format!("<td>{}</td>", points_text(p)));
        let settings = escape(outcome.settings.as_deref().unwrap_or(""));
        let _ = writeln!(html, "<tr{class}><td>{linked}</td><td>{result}</td>{points}<td>{settings}</td><td>{}</td></tr>", escape(&outcome.detail));
    }
    html.push_str("</table>\n");
    for outcome in outcomes.iter().filter(|o| o.status.failed()) {
        let _ = write!(html, "<section id=\"{}\">\n<h2>{}</h2>\n<p class=\"failed\">{}</p>\n", anchor(outcome), escape(&outcome.name), escape(outcome.verdict()));
        if let Some(diagnosis) = &outcome.diagnosis {
            let (lead, advice) = sentence_and_advice(diagnosis);
            let _ = writeln!(
                html,
                "<p class=\"diagnosis\">{}<strong>{}</strong>. The cyan box on the diff map marks {}.</p>",
                escape(&lead),
                escape(advice),
                diagnosis.region
            );
        }
        let files: Vec<String> =
            outcome.files.iter().map(|(role, path)| format!("{role} <code>{}</code>", escape(&path.display().to_string()))).collect();
        let _ = writeln!(html, "<p>{}</p>", files.join(", "));
        if let Some(settings) = &outcome.settings {
            let _ = writeln!(html, "<p>settings: {}</p>", escape(settings));
        }
        let (whole, zoomed) = report_images(outcome);
        figures(&mut html, &whole, "");
        figures(&mut html, &zoomed, ", worst region magnified");
        html.push_str("</section>\n");
    }
    html.push_str("</body>\n</html>\n");
    html
}

/// A row of images, each captioned with its role and `caption`.
fn figures(html: &mut String, figures: &[Figure<'_>], caption: &str) {
    if figures.is_empty() {
        return;
    }
    html.push_str("<div class=\"images\">\n");
    let scale = figures.iter().map(|(_, _, png)| png.width).min().map_or(1, |w| SHOWN_WIDTH.div_ceil(w).clamp(1, 8));
    for (name, role, png) in figures {
        let _ = writeln!(
            html,
            "<figure><img src=\"{}\" alt=\"{role}{caption}\" width=\"{}\" height=\"{}\"><figcaption>{role}{caption}</figcaption></figure>",
            escape(name),
            png.width * scale,
            png.height * scale
        );
    }
    html.push_str("</div>\n");
}

fn anchor(outcome: &Outcome) -> String {
    format!("case-{}", outcome.file_stem)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::comparison::ReportImages;

    fn png(width: u32, height: u32) -> Png {
        Png { bytes: vec![1, 2, 3], width, height }
    }

    fn outcome(name: &str, status: Status, images: Option<ReportImages>) -> Outcome {
        Outcome {
            name: name.into(),
            file_stem: name.replace(' ', "_"),
            files: vec![("scene", format!("{name}.toml").into()), ("golden", format!("{name}.png").into())],
            settings: Some("view shaded, max depth 2, 1 spp, 160x120".into()),
            status,
            detail: format!("detail of {name} <b>"),
            points: None,
            images,
            diagnosis: None,
        }
    }

    #[test]
    fn failing_cases_show_reference_render_and_diff_side_by_side() {
        let images = ReportImages {
            whole: vec![("reference", png(160, 120)), ("render", png(160, 120)), ("diff", png(200, 154))],
            zoomed: vec![("reference", png(192, 192)), ("render", png(192, 192))],
        };
        let outcomes = [
            outcome("fine", Status::Passed, None),
            outcome("bad one", Status::Mismatch, Some(images)),
            outcome("new", Status::NoGolden, Some(ReportImages { whole: vec![("render", png(40, 30))], zoomed: Vec::new() })),
        ];
        let html = page("suite & co", &outcomes);
        assert!(html.contains("<title>glint test: suite &amp; co</title>"), "{html}");
        assert!(html.contains("<p>1 passed, 2 failed</p>"));
        assert!(html.contains("detail of bad one &lt;b&gt;"));
        for role in ["reference", "render", "diff"] {
            assert!(html.contains(&format!("<img src=\"bad_one-{role}.png\" alt=\"{role}\"")), "{role}: {html}");
        }
        // Shown at twice their size: 160 px is under 320.
        assert!(html.contains("alt=\"diff\" width=\"400\" height=\"308\""), "{html}");
        assert!(html.contains("<img src=\"new-render.png\""));
        assert!(!html.contains("new-reference.png") && !html.contains("fine-render.png"));
        assert!(html.contains("<a href=\"#case-bad_one\">bad one</a>") && html.contains("<section id=\"case-bad_one\">"));
        // The worst region of reference and render, side by side, magnified.
        for role in ["reference", "render"] {
            let zoom = format!("<img src=\"bad_one-{role}-zoom.png\" alt=\"{role}, worst region magnified\" width=\"384\"");
            assert!(html.contains(&zoom), "{role}: {html}");
        }
        // What made the image: the settings, in the table and in the case's section.
        assert_eq!(html.matches("view shaded, max depth 2, 1 spp, 160x120").count(), 3 + 2, "{html}");
        assert!(html.contains("<p>scene <code>bad one.toml</code>, golden <code>bad one.png</code></p>"), "{html}");
    }

    #[test]
    fn a_diagnosed_case_says_what_is_likely_wrong_under_its_verdict() {
        let mut diagnosed = outcome("glass", Status::Mismatch, None);
        diagnosed.diagnose(crate::diagnosis::Diagnosis {
            effect: crate::diagnosis::Effect::NoRefraction,
            what: "without refracted rays".into(),
            advice: "check your refracted rays and Snell's law",
            flip: 0.004,
            full_flip: 0.2,
            region: crate::region::Region { x: 3, y: 5, width: 8, height: 8 },
        });
        let html = page("t", &[diagnosed]);
        let verdict = "<p class=\"failed\">detail of glass &lt;b&gt;</p>\n";
        let diagnosis = "<p class=\"diagnosis\">closest to Glint&#39;s render without refracted rays (flip 0.004, against 0.200 for the full render; the two differ most in 8x8 at (3, 5)): <strong>check your refracted rays and Snell&#39;s law</strong>. The cyan box on the diff map marks 8x8 at (3, 5).</p>\n";
        assert!(html.contains(&format!("{verdict}{diagnosis}")), "{html}");
        // The table keeps the whole detail, the sentence with it.
        assert!(html.contains("<td>detail of glass &lt;b&gt;; closest to Glint&#39;s render without refracted rays"), "{html}");
    }

    #[test]
    fn the_report_directory_holds_the_page_and_its_images() {
        let dir = tempfile::tempdir().unwrap();
        let report = dir.path().join("report");
        let images = ReportImages { whole: vec![("reference", png(4, 4)), ("render", png(4, 4))], zoomed: Vec::new() };
        let outcomes = [outcome("size", Status::Mismatch, Some(images))];
        let index = write_report(&report, "t", &outcomes).unwrap();
        assert_eq!(index, report.join("index.html"));
        let mut names: Vec<String> = std::fs::read_dir(&report).unwrap().map(|e| e.unwrap().file_name().into_string().unwrap()).collect();
        names.sort();
        assert_eq!(names, ["index.html", "size-reference.png", "size-render.png"]);
        let blocked = dir.path().join("file");
        std::fs::write(&blocked, "").unwrap();
        let e = write_report(&blocked.join("sub"), "t", &outcomes).unwrap_err();
        assert!(e.starts_with(&format!("{}: cannot create the report directory", blocked.join("sub").display())), "{e}");
    }
}
