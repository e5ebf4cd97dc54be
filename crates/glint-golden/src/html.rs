//! The HTML report: a table of every case, then for each failing case its
//! reference, render and error map side by side. The page and its PNG images
//! go in one directory, linked by relative names, so the directory can be
//! kept as a CI artifact and opened anywhere.

use std::fmt::Write;
use std::path::{Path, PathBuf};

use crate::markup::escape;
use crate::runner::{Outcome, Png, Status, Summary};

const STYLE: &str = "body { font-family: sans-serif; margin: 1.5em; color: #222; background: #fafafa }
table { border-collapse: collapse; margin-bottom: 2em }
th, td { text-align: left; padding: 0.25em 0.8em; border-bottom: 1px solid #ddd; vertical-align: top }
.failed { color: #a00 }
.images { display: flex; flex-wrap: wrap; gap: 1.5em; align-items: flex-start }
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
    let write = |name: &str, bytes: &[u8]| {
        let path = dir.join(name);
        glint_gpu::write_atomically(&path, bytes).map_err(|e| format!("{}: cannot write: {e}", path.display()))
    };
    for outcome in outcomes {
        for (role, png) in report_images(outcome) {
            write(&image_name(outcome, role), &png.bytes)?;
        }
    }
    write("index.html", page(title, outcomes).as_bytes())?;
    Ok(dir.join("index.html"))
}

fn report_images(outcome: &Outcome) -> Vec<(&'static str, &Png)> {
    let Some(images) = &outcome.images else { return Vec::new() };
    let mut shown = Vec::new();
    if let Some(reference) = &images.reference {
        shown.push(("reference", reference));
    }
    shown.push(("render", &images.render));
    if let Some(diff) = &images.diff {
        shown.push(("diff", diff));
    }
    shown
}

fn image_name(outcome: &Outcome, role: &str) -> String {
    format!("{}-{role}.png", outcome.file_stem)
}

/// The page's HTML.
pub fn page(title: &str, outcomes: &[Outcome]) -> String {
    let title = escape(title);
    let mut html = String::new();
    let _ = write!(
        html,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>glint test: {title}</title>\n<style>\n{STYLE}\n</style>\n</head>\n<body>\n<h1>glint test: {title}</h1>\n<p>{}</p>\n",
        Summary::of(outcomes)
    );
    html.push_str("<table>\n<tr><th>case</th><th>result</th><th>detail</th></tr>\n");
    for outcome in outcomes {
        let name = escape(&outcome.name);
        let (class, result) = match outcome.status {
            Status::Passed => ("", "ok"),
            Status::Blessed => ("", "blessed"),
            Status::Mismatch => (" class=\"failed\"", "differs"),
            Status::NoGolden => (" class=\"failed\"", "no golden"),
            Status::Error => (" class=\"failed\"", "error"),
        };
        let linked = if outcome.status.failed() { format!("<a href=\"#{}\">{name}</a>", anchor(outcome)) } else { name };
        let _ = writeln!(html, "<tr{class}><td>{linked}</td><td>{result}</td><td>{}</td></tr>", escape(&outcome.detail));
    }
    html.push_str("</table>\n");
    for outcome in outcomes.iter().filter(|o| o.status.failed()) {
        let _ = write!(
            html,
            "<section id=\"{}\">\n<h2>{}</h2>\n<p class=\"failed\">{}</p>\n<p>scene <code>{}</code>, golden <code>{}</code></p>\n",
            anchor(outcome),
            escape(&outcome.name),
            escape(&outcome.detail),
            escape(&outcome.scene.display().to_string()),
            escape(&outcome.golden.display().to_string())
        );
        let images = report_images(outcome);
        if !images.is_empty() {
            html.push_str("<div class=\"images\">\n");
            let scale = images.iter().map(|(_, png)| png.width).min().map_or(1, |w| SHOWN_WIDTH.div_ceil(w).clamp(1, 8));
            for (role, png) in images {
                let _ = writeln!(
                    html,
                    "<figure><img src=\"{}\" alt=\"{role}\" width=\"{}\" height=\"{}\"><figcaption>{role}</figcaption></figure>",
                    escape(&image_name(outcome, role)),
                    png.width * scale,
                    png.height * scale
                );
            }
            html.push_str("</div>\n");
        }
        html.push_str("</section>\n");
    }
    html.push_str("</body>\n</html>\n");
    html
}

fn anchor(outcome: &Outcome) -> String {
    format!("case-{}", outcome.file_stem)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::runner::ReportImages;

    fn png(width: u32, height: u32) -> Png {
        Png { bytes: vec![1, 2, 3], width, height }
    }

    fn outcome(name: &str, status: Status, images: Option<ReportImages>) -> Outcome {
        Outcome {
            name: name.into(),
            file_stem: name.replace(' ', "_"),
            scene: format!("{name}.toml").into(),
            golden: format!("{name}.png").into(),
            status,
            detail: format!("detail of {name} <b>"),
            images,
        }
    }

    #[test]
    fn failing_cases_show_reference_render_and_diff_side_by_side() {
        let images = ReportImages { reference: Some(png(160, 120)), render: png(160, 120), diff: Some(png(200, 154)) };
        let outcomes = [
            outcome("fine", Status::Passed, None),
            outcome("bad one", Status::Mismatch, Some(images)),
            outcome("new", Status::NoGolden, Some(ReportImages { reference: None, render: png(40, 30), diff: None })),
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
    }

    #[test]
    fn the_report_directory_holds_the_page_and_its_images() {
        let dir = tempfile::tempdir().unwrap();
        let report = dir.path().join("report");
        let images = ReportImages { reference: Some(png(4, 4)), render: png(4, 4), diff: None };
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
