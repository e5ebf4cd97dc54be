//! `glint test MANIFEST --submissions DIR` (or `--submission DIR`): grade
//! students' own images by the manifest's cases that name an `image`. Prints
//! a line per student and case and each student's total, then writes the
//! reports asked for. Grades are the result, so the run exits 0 once they are
//! written, whatever they are; a reference that could not be made is an
//! input error.

use std::path::Path;

use glint_golden::{GradedCase, Grades, Student, Suite};

use crate::{exit, Failure};

/// Whose images are graded.
pub enum Grading<'a> {
    /// A directory holding a folder per student.
    Class(&'a Path),
    /// One student's folder.
    One(&'a Path),
}

impl<'a> Grading<'a> {
    pub fn of(submissions: Option<&'a Path>, submission: Option<&'a Path>) -> Option<Self> {
        submissions.map(Grading::Class).or(submission.map(Grading::One))
    }
}

pub struct Outputs<'a> {
    pub report: Option<&'a Path>,
    pub junit: Option<&'a Path>,
    pub gradescope: Option<&'a Path>,
}

pub fn run(suite: &Suite, names: &[String], grading: Grading, outputs: Outputs) -> Result<(), Failure> {
    if suite.graded.is_empty() {
        return Err(Failure::new(
            exit::USAGE,
            format!("{}: no case names an `image` to grade (see docs/golden-ci.md, \"Grading students' images\")", suite.source.display()),
        ));
    }
    let cases: Vec<&GradedCase> = suite.select_graded(names).map_err(|e| Failure::new(exit::USAGE, e))?;
    let whole_class = matches!(grading, Grading::Class(_));
    let students = match grading {
        Grading::Class(dir) => Student::all_in(dir).map_err(|e| Failure::new(exit::INPUT, e))?,
        Grading::One(dir) if dir.is_dir() => vec![Student::one(dir)],
        Grading::One(dir) => return Err(Failure::new(exit::INPUT, format!("{}: the submission is not a directory", dir.display()))),
    };
    let renderer = if glint_golden::needs_renderer(&cases) { Some(crate::renderer()?) } else { None };
    // Gradescope's results show a failure's images too.
    let report_images = outputs.report.is_some() || outputs.gradescope.is_some();
    let (grades, reference_errors) = glint_golden::grade(&cases, renderer.as_ref(), &students, report_images, &mut print_grades);
    write_outputs(&suite.name, &cases, &grades, &outputs, whole_class)?;
    if reference_errors.is_empty() {
        return Ok(());
    }
    for error in &reference_errors {
        eprintln!("glint: {error}");
    }
    Err(Failure::explained(exit::INPUT))
}

fn print_grades(grades: &Grades) {
    let student = &grades.student.name;
    for outcome in &grades.outcomes {
        let points = outcome.points.map(glint_golden::points_text).unwrap_or_default();
        println!("{:<7} {student}/{}: {} ({points} points)", outcome.label(), outcome.name, outcome.detail);
    }
    println!("{student}: {}; {} points", glint_golden::Summary::of(&grades.outcomes), glint_golden::points_text(grades.total()));
}

/// Writes the reports asked for; a class's report drops the folders of
/// students no longer in it.
fn write_outputs(suite_name: &str, cases: &[&GradedCase], grades: &[Grades], outputs: &Outputs, whole_class: bool) -> Result<(), Failure> {
    let output_error = |e: String| Failure::new(exit::OUTPUT, e);
    let write = |path: &Path, text: String| {
        glint_gpu::write_atomically(path, text.as_bytes()).map_err(|e| output_error(format!("{}: cannot write: {e}", path.display())))
    };
    // --gradescope comes only with --submission: one student.
    if let (Some(path), [student]) = (outputs.gradescope, grades) {
        write(path, glint_golden::results_json(suite_name, cases, student))?;
    }
    if let Some(path) = outputs.junit {
        let suites: Vec<(&str, &[glint_golden::Outcome])> = grades.iter().map(|g| (g.student.name.as_str(), &g.outcomes[..])).collect();
        write(path, glint_golden::junit_xml_suites(suite_name, &suites))?;
    }
    if let Some(dir) = outputs.report {
        let index = glint_golden::write_class_report(dir, suite_name, cases, grades).map_err(output_error)?;
        if whole_class {
            for folder in glint_golden::remove_former_students(dir, grades).map_err(output_error)? {
                println!("removed {}: no longer in the class", folder.display());
            }
        }
        println!("wrote {}", index.display());
    }
    Ok(())
}
