//! Running a suite: each case is rendered, compared with its golden and,
//! when asked, blessed. Cases render one after another, since they share one
//! GPU (and lavapipe already spreads each dispatch over every core); reading
//! goldens, comparing, writing goldens and encoding report images run on
//! worker threads while the next case renders. Outcomes come out in the
//! suite's order whatever order the workers finish in, so every output is the
//! same on every run.

use std::collections::BTreeMap;
use std::fmt;
use std::path::PathBuf;
use std::sync::{mpsc, Mutex};

use glint_gpu::{Bits, Image, Renderer};

use crate::case_render::Rendered;
use crate::comparison::{compare, ReportImages, Roles};
use crate::diagnosis::Diagnosis;
use crate::image_io::{self, LinearImage};
use crate::manifest::Case;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Status {
    Passed,
    /// The golden was written.
    Blessed,
    /// Rendered and compared, and not close enough (or of another size).
    Mismatch,
    NoGolden,
    /// A graded case's submitted image is not there.
    NoImage,
    /// The scene, the golden, the submitted image or the GPU failed.
    Error,
}

impl Status {
    pub fn failed(self) -> bool {
        matches!(self, Status::Mismatch | Status::NoGolden | Status::NoImage | Status::Error)
    }
}

/// What a graded case earned out of what it could.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Points {
    pub earned: f64,
    pub possible: f64,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Outcome {
    pub name: String,
    /// The stem of the case's report files.
    pub file_stem: String,
    /// The files compared, each with its role: the scene and its golden, or
    /// a submission and its reference.
    pub files: Vec<(&'static str, PathBuf)>,
    /// The render settings in words (see [`Rendered`]), when known.
    pub settings: Option<String>,
    pub status: Status,
    /// One line: the comparison's summary, or what went wrong.
    pub detail: String,
    /// Set for a graded case.
    pub points: Option<Points>,
    pub images: Option<ReportImages>,
    /// What a failed submission most likely got wrong, set by grading.
    pub diagnosis: Option<Diagnosis>,
}

impl Outcome {
    fn new(case: &Case, status: Status, detail: String) -> Self {
        Outcome {
            name: case.name.clone(),
            file_stem: case.file_stem(),
            files: vec![("scene", case.scene.clone()), ("golden", case.golden.clone())],
            settings: None,
            status,
            detail,
            points: None,
            images: None,
            diagnosis: None,
        }
    }

    /// Sets the diagnosis, and appends its sentence to the detail, which
    /// every text output (stdout, JUnit) shows.
    pub fn diagnose(&mut self, diagnosis: Diagnosis) {
        self.detail += &format!("; {}", diagnosis.sentence());
        self.diagnosis = Some(diagnosis);
    }

    /// The detail without the diagnosis' sentence: for outputs that show the
    /// diagnosis apart.
    pub fn verdict(&self) -> &str {
        self.diagnosis
            .as_ref()
            .and_then(|d| self.detail.strip_suffix(&format!("; {}", d.sentence())))
            .unwrap_or(&self.detail)
    }

    /// The detail, then the settings and the files compared, a line each:
    /// the body of a JUnit failure or of a passed Gradescope test's output.
    pub fn explanation(&self) -> String {
        let mut text = self.detail.clone();
        if let Some(settings) = &self.settings {
            text += &format!("\nsettings: {settings}");
        }
        for (role, path) in &self.files {
            text += &format!("\n{role}: {}", path.display());
        }
        text
    }

    /// The case's line in `glint test`'s output.
    pub fn line(&self) -> String {
        format!("{:<7} {}: {}", self.label(), self.name, self.detail)
    }

    /// `ok`, `blessed` or `FAIL`: how a line starts.
    pub fn label(&self) -> &'static str {
        match self.status {
            Status::Passed => "ok",
            Status::Blessed => "blessed",
            Status::Mismatch | Status::NoGolden | Status::NoImage | Status::Error => "FAIL",
        }
    }
}

/// A diagnosis' sentence up to its advice, and the advice: for outputs that
/// set the advice apart.
pub fn sentence_and_advice(diagnosis: &Diagnosis) -> (String, &'static str) {
    let sentence = diagnosis.sentence();
    let lead = sentence.strip_suffix(diagnosis.advice).unwrap_or(&sentence).to_string();
    (lead, diagnosis.advice)
}

/// Counts of a run; displayed as the closing line `N passed, N failed`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Summary {
    pub passed: usize,
    pub failed: usize,
}

impl Summary {
    pub fn of(outcomes: &[Outcome]) -> Self {
        let failed = outcomes.iter().filter(|o| o.status.failed()).count();
        Summary { passed: outcomes.len() - failed, failed }
    }
}

impl fmt::Display for Summary {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} passed, {} failed", self.passed, self.failed)
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Bless {
    No,
    /// Write the goldens that are missing or that fail.
    MissingOrFailing,
    /// Write every case's golden (the cases named on the command line).
    All,
}

#[derive(Debug, Clone, Copy)]
pub struct RunOptions {
    pub bless: Bless,
    /// Keep PNG images of failing cases in the outcomes, for a report.
    pub report_images: bool,
}

struct Job<'a> {
    index: usize,
    case: &'a Case,
    rendered: Result<Rendered, String>,
}

/// Runs `cases` in order on `renderer`, handing each outcome to `on_outcome`
/// in that order as soon as it and all before it are known.
pub fn run(cases: &[&Case], renderer: &Renderer, options: RunOptions, on_outcome: &mut dyn FnMut(&Outcome)) -> Vec<Outcome> {
    let workers = std::thread::available_parallelism().map_or(1, |n| n.get()).min(cases.len()).max(1);
    // A bounded queue keeps at most a few rendered images waiting.
    let (job_sender, job_receiver) = mpsc::sync_channel::<Job>(workers);
    let job_receiver = Mutex::new(job_receiver);
    let (done_sender, done_receiver) = mpsc::channel::<(usize, Outcome)>();
    let mut in_order = InOrder::default();
    std::thread::scope(|scope| {
        for _ in 0..workers {
            let done_sender = done_sender.clone();
            let job_receiver = &job_receiver;
            scope.spawn(move || {
                loop {
                    // The lock is held only while waiting for the next job.
                    let job = job_receiver.lock().unwrap_or_else(|e| e.into_inner()).recv();
                    let Ok(job) = job else { break };
                    let outcome = conclude(job.case, job.rendered, options);
                    if done_sender.send((job.index, outcome)).is_err() {
                        break;
                    }
                }
            });
        }
        drop(done_sender);
        for (index, case) in cases.iter().enumerate() {
            let rendered = crate::case_render::render(renderer, &case.scene, &case.render);
            job_sender.send(Job { index, case, rendered }).expect("the workers outlive the jobs");
            while let Ok((index, outcome)) = done_receiver.try_recv() {
                in_order.add(index, outcome, on_outcome);
            }
        }
        drop(job_sender);
        for (index, outcome) in done_receiver {
            in_order.add(index, outcome, on_outcome);
        }
    });
    in_order.done
}

/// Outcomes released in index order.
#[derive(Default)]
struct InOrder {
    waiting: BTreeMap<usize, Outcome>,
    done: Vec<Outcome>,
}

impl InOrder {
    fn add(&mut self, index: usize, outcome: Outcome, on_outcome: &mut dyn FnMut(&Outcome)) {
        self.waiting.insert(index, outcome);
        while let Some(outcome) = self.waiting.remove(&self.done.len()) {
            on_outcome(&outcome);
            self.done.push(outcome);
        }
    }
}

/// The roles of a golden test's images in its details and report.
const GOLDEN_ROLES: Roles = Roles { reference: "reference", tested: "render" };

/// Compares a rendered case with its golden, blessing it if asked.
fn conclude(case: &Case, rendered: Result<Rendered, String>, options: RunOptions) -> Outcome {
    let Rendered { image, settings } = match rendered {
        Ok(rendered) => rendered,
        Err(e) => return Outcome::new(case, Status::Error, e),
    };
    let mut outcome = judge_render(case, &image, options);
    outcome.settings = Some(settings);
    outcome
}

fn judge_render(case: &Case, image: &Image, options: RunOptions) -> Outcome {
    if options.bless == Bless::All {
        return bless(case, image);
    }
    let Some(format) = image_io::format_of(&case.golden) else {
        return Outcome::new(case, Status::Error, format!("golden {}: use a {} file", case.golden.display(), glint_gpu::Format::EXTENSIONS));
    };
    let render = LinearImage::from_render(image, format);
    if !case.golden.exists() {
        if options.bless == Bless::MissingOrFailing {
            return bless(case, image);
        }
        let mut outcome = Outcome::new(case, Status::NoGolden, format!("no golden: {}", case.golden.display()));
        outcome.images = options.report_images.then(|| ReportImages::alone(GOLDEN_ROLES.tested, &render));
        return outcome;
    }
    let (status, detail, images) = match image_io::read(&case.golden) {
        Err(e) => (Status::Error, format!("golden {e}"), options.report_images.then(|| ReportImages::alone(GOLDEN_ROLES.tested, &render))),
        Ok(reference) => {
            let comparison = compare(&reference, &render, &case.criteria, GOLDEN_ROLES, options.report_images);
            let status = if comparison.passed() { Status::Passed } else { Status::Mismatch };
            (status, comparison.detail, comparison.images)
        }
    };
    if status.failed() && options.bless == Bless::MissingOrFailing {
        return bless(case, image);
    }
    let mut outcome = Outcome::new(case, status, detail);
    outcome.images = images;
    outcome
}

fn bless(case: &Case, image: &Image) -> Outcome {
    let written = case
        .golden
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .map_or(Ok(()), std::fs::create_dir_all)
        .map_err(|e| format!("{}: cannot create the directory: {e}", case.golden.display()))
        .and_then(|()| glint_gpu::write_image(image, &case.golden, Bits::Eight).map_err(|e| e.to_string()));
    match written {
        Ok(()) => Outcome::new(case, Status::Blessed, format!("wrote {}", case.golden.display())),
        Err(e) => Outcome::new(case, Status::Error, format!("cannot bless: {e}")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn case() -> Case {
        Case {
            name: "c".into(),
            scene: "c.toml".into(),
            golden: "c.png".into(),
            render: Default::default(),
            criteria: crate::criteria::Criteria::for_metric(crate::metrics::Metric::Flip),
        }
    }

    #[test]
    fn outcomes_are_released_in_order() {
        let case = case();
        let outcome = |detail: &str| Outcome::new(&case, Status::Passed, detail.into());
        let mut seen = Vec::new();
        let mut in_order = InOrder::default();
        let mut record = |o: &Outcome| seen.push(o.detail.clone());
        in_order.add(2, outcome("third"), &mut record);
        in_order.add(1, outcome("second"), &mut record);
        in_order.add(0, outcome("first"), &mut record);
        in_order.add(3, outcome("fourth"), &mut record);
        assert_eq!(seen, ["first", "second", "third", "fourth"]);
        assert_eq!(in_order.done.len(), 4);
    }

    #[test]
    fn the_summary_is_the_closing_line() {
        let case = case();
        let outcomes: Vec<Outcome> = [Status::Passed, Status::Blessed, Status::Mismatch, Status::NoGolden, Status::NoImage, Status::Error]
            .into_iter()
            .map(|s| Outcome::new(&case, s, "d".into()))
            .collect();
        assert_eq!(Summary::of(&outcomes).to_string(), "2 passed, 4 failed");
        assert_eq!(outcomes[2].line(), "FAIL    c: d");
        assert_eq!(outcomes[1].line(), "blessed c: d");
    }
}
