//! `glint test [MANIFEST.toml | DIR]`: render every case of a suite, compare
//! each with its golden image, print one line per case and close with
//! `N passed, N failed`. With `--submissions DIR` (or one `--submission`), it
//! grades students' own images instead: see grade.rs.

use std::path::PathBuf;

use clap::Args;
use glint_golden::{Bless, RunOptions, Suite, Summary};
use crate::{exit, renderer, Failure};

#[derive(Args)]
pub struct TestArgs {
    /// A manifest (.toml), or a directory whose scene files each have their
    /// golden NAME.png beside them
    #[arg(default_value = ".")]
    suite: PathBuf,
    /// Run only this case (repeatable); with --bless, its golden is rewritten
    /// even when it passes
    #[arg(long = "case", value_name = "NAME")]
    cases: Vec<String>,
    /// Write the goldens that are missing or failing
    #[arg(long)]
    bless: bool,
    /// Also write the results as JUnit XML
    #[arg(long, value_name = "FILE.xml")]
    junit: Option<PathBuf>,
    /// Also write an HTML report, with reference, render and diff of each
    /// failing case, as DIR/index.html; when grading, the class summary, and
    /// each student's report and results.json in DIR/STUDENT/
    #[arg(long, value_name = "DIR")]
    report: Option<PathBuf>,
    /// Grade the images in this directory, one folder per student, by the
    /// manifest's cases that name an `image`
    #[arg(long, value_name = "DIR", conflicts_with_all = ["submission", "bless"])]
    submissions: Option<PathBuf>,
    /// Grade one student's folder of images (Gradescope's /autograder/submission)
    #[arg(long, value_name = "DIR", conflicts_with = "bless")]
    submission: Option<PathBuf>,
    /// Write the --submission's Gradescope results, e.g. /autograder/results/results.json
    #[arg(long, value_name = "FILE.json", requires = "submission")]
    gradescope: Option<PathBuf>,
}

pub fn run(args: &TestArgs) -> Result<(), Failure> {
    let suite = Suite::load(&args.suite).map_err(|e| Failure::new(exit::INPUT, e))?;
    if let Some(grading) = crate::grade::Grading::of(args.submissions.as_deref(), args.submission.as_deref()) {
        let outputs = crate::grade::Outputs { report: args.report.as_deref(), junit: args.junit.as_deref(), gradescope: args.gradescope.as_deref() };
        return crate::grade::run(&suite, &args.cases, grading, outputs);
    }
    if suite.cases.is_empty() {
        return Err(Failure::new(
            exit::USAGE,
            format!("{}: its cases grade submitted images: give --submissions DIR (a folder per student) or --submission DIR", suite.source.display()),
        ));
    }
    let cases = suite.select(&args.cases).map_err(|e| Failure::new(exit::USAGE, e))?;
    let renderer = renderer()?;
    let bless = match (args.bless, args.cases.is_empty()) {
        (false, _) => Bless::No,
        (true, true) => Bless::MissingOrFailing,
        (true, false) => Bless::All,
    };
    let options = RunOptions { bless, report_images: args.report.is_some() };
    let outcomes = glint_golden::run(&cases, &renderer, options, &mut |outcome| println!("{}", outcome.line()));

    if let Some(path) = &args.junit {
        let xml = glint_golden::junit_xml(&suite.name, &outcomes);
        glint_gpu::write_atomically(path, xml.as_bytes())
            .map_err(|e| Failure::new(exit::OUTPUT, format!("{}: cannot write: {e}", path.display())))?;
    }
    if let Some(dir) = &args.report {
        glint_golden::write_report(dir, &suite.name, &outcomes).map_err(|e| Failure::new(exit::OUTPUT, e))?;
    }
    let summary = Summary::of(&outcomes);
    println!("{summary}");
    if summary.failed == 0 { Ok(()) } else { Err(Failure::explained(exit::DIFFERENT)) }
}
