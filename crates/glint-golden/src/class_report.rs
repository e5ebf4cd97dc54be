//! A graded class's reports, in one directory: `index.html`, the class
//! summary (students × cases, sortable by any column), and a folder per
//! student with the student's own HTML report and Gradescope `results.json`.

use std::fmt::Write;
use std::path::{Path, PathBuf};

use crate::gradescope::results_json;
use crate::grading::Grades;
use crate::manifest::GradedCase;
use crate::html::{points_text, write_file, write_report, STYLE};
use crate::markup::escape;

/// Clicking a header sorts the rows by that column, again to reverse. Each
/// cell's `data-sort` is its key; inline, so the page works from file://.
const SORT_SCRIPT: &str = "for (const [column, th] of document.querySelectorAll('#class th').entries()) {
  th.addEventListener('click', () => {
    const body = document.querySelector('#class tbody');
    const key = row => row.cells[column].dataset.sort;
    const numeric = th.dataset.type === 'number';
    const rows = Array.from(body.rows).sort((a, b) => numeric ? key(b) - key(a) : key(a).localeCompare(key(b)));
    const reversed = th.dataset.sorted === 'yes';
    if (reversed) rows.reverse();
    document.querySelectorAll('#class th').forEach(other => delete other.dataset.sorted);
    if (!reversed) th.dataset.sorted = 'yes';
    body.append(...rows);
  });
}";

/// Writes every student's report and results.json, then the class summary;
/// returns the summary's path. The error names the file that failed.
pub fn write_class_report(dir: &Path, suite_name: &str, cases: &[&GradedCase], grades: &[Grades]) -> Result<PathBuf, String> {
    for student in grades {
        let student_dir = dir.join(&student.student.report_folder);
        write_report(&student_dir, &format!("{suite_name}: {}", student.student.name), &student.outcomes)?;
        write_file(&student_dir.join("results.json"), results_json(suite_name, cases, student).as_bytes())?;
    }
    let index = dir.join("index.html");
    write_file(&index, class_page(suite_name, grades).as_bytes())?;
    Ok(index)
}

/// Removes the report folders in `dir` of students not in `grades` (a
/// student's folder has a results.json), so that the report is the class as
/// graded now; returns the folders removed. Other folders are left alone.
pub fn remove_former_students(dir: &Path, grades: &[Grades]) -> Result<Vec<PathBuf>, String> {
    let Ok(entries) = std::fs::read_dir(dir) else { return Ok(Vec::new()) };
    let current: Vec<&str> = grades.iter().map(|g| g.student.report_folder.as_str()).collect();
    let mut removed = Vec::new();
    for path in entries.flatten().map(|e| e.path()) {
        let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
        if path.join("results.json").is_file() && !current.contains(&name.as_str()) {
            std::fs::remove_dir_all(&path).map_err(|e| format!("{}: cannot remove a former student's report: {e}", path.display()))?;
            removed.push(path);
        }
    }
    removed.sort();
    Ok(removed)
}

/// The summary: a row per student with the total and each case's points,
/// each linking to the student's report.
pub fn class_page(suite_name: &str, grades: &[Grades]) -> String {
    let title = escape(suite_name);
    let mut html = String::new();
    let _ = write!(
        html,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>glint grades: {title}</title>\n<style>\n{STYLE}\nth {{ cursor: pointer }}\n</style>\n</head>\n<body>\n<h1>glint grades: {title}</h1>\n<p>{} students; click a column's header to sort by it.</p>\n",
        grades.len()
    );
    html.push_str("<table id=\"class\">\n<thead><tr><th data-type=\"text\">student</th><th data-type=\"number\">score</th>");
    for outcome in grades.first().map_or(&[][..], |g| &g.outcomes[..]) {
        let _ = write!(html, "<th data-type=\"number\">{}</th>", escape(&outcome.name));
    }
    html.push_str("</tr></thead>\n<tbody>\n");
    for student in grades {
        let name = escape(&student.student.name);
        let total = student.total();
        let _ = write!(
            html,
            "<tr><td data-sort=\"{name}\"><a href=\"{}/index.html\">{name}</a></td><td data-sort=\"{}\">{}</td>",
            escape(&student.student.report_folder),
            total.earned,
            points_text(total)
        );
        for outcome in &student.outcomes {
            let points = outcome.points.expect("a graded outcome has points");
            let class = if outcome.status.failed() { " class=\"failed\"" } else { "" };
            let _ = write!(html, "<td{class} data-sort=\"{}\" title=\"{}\">{}</td>", points.earned, escape(&outcome.detail), points_text(points));
        }
        html.push_str("</tr>\n");
    }
    let _ = write!(html, "</tbody>\n</table>\n<script>\n{SORT_SCRIPT}\n</script>\n</body>\n</html>\n");
    html
}
