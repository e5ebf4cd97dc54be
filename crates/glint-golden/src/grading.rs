//! Grading images Glint did not render: each student's submitted image of a
//! case, held against the case's reference (a scene Glint renders, or a
//! file) by the case's criteria, and scored. Each reference is made once per
//! run, however many students there are; a student's missing, unreadable or
//! wrongly sized image is that case's verdict, and the run goes on.

use std::path::{Path, PathBuf};

use glint_gpu::{Format, Image, Renderer};

use crate::case_render::{render, Rendered};
use crate::comparison::{compare, Roles};
use crate::criteria::Criteria;
use crate::image_io::{self, LinearImage};
use crate::manifest::file_stem_of;
use crate::runner::{Outcome, Points, Status};
use crate::scoring::Scoring;
use crate::settings::RenderSettings;

/// What `image` may hold in its path: the student's folder name.
pub const STUDENT_PLACEHOLDER: &str = "{student}";

const ROLES: Roles = Roles { reference: "reference", tested: "submission" };

/// A `[[case]]` with an `image`: what each student submits for it and what
/// that is compared with.
#[derive(Debug, Clone, PartialEq)]
pub struct GradedCase {
    pub name: String,
    /// The submitted image's path inside each student's folder.
    pub image: String,
    pub reference: Reference,
    pub render: RenderSettings,
    pub criteria: Criteria,
    pub scoring: Scoring,
}

#[derive(Debug, Clone, PartialEq)]
pub enum Reference {
    /// A scene (or `spd:NAME[:SIZE]`) that Glint renders with the case's settings.
    Scene(PathBuf),
    /// An image file.
    File(PathBuf),
}

impl GradedCase {
    pub fn file_stem(&self) -> String {
        file_stem_of(&self.name)
    }
}

/// One student's folder of submitted images.
#[derive(Debug, Clone, PartialEq)]
pub struct Student {
    /// The folder's name.
    pub name: String,
    pub dir: PathBuf,
}

impl Student {
    /// Every folder in `dir`, sorted by name, each a student; hidden ones
    /// (`.git`) are not.
    pub fn all_in(dir: &Path) -> Result<Vec<Student>, String> {
        let cannot = |e: std::io::Error| format!("{}: cannot read the submissions directory: {e}", dir.display());
        let mut students = Vec::new();
        for entry in std::fs::read_dir(dir).map_err(cannot)? {
            let path = entry.map_err(cannot)?.path();
            let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
            if path.is_dir() && !name.starts_with('.') {
                students.push(Student { name, dir: path });
            }
        }
        if students.is_empty() {
            return Err(format!("{}: no student folders in the submissions directory (one folder per student)", dir.display()));
        }
        students.sort_by(|a, b| a.name.cmp(&b.name));
        // Two folders whose names differ only in characters a file name
        // cannot keep would share one report folder.
        let mut stems = std::collections::HashMap::new();
        for student in &students {
            if let Some(earlier) = stems.insert(student.file_stem(), &student.name) {
                return Err(format!(
                    "{}: students `{earlier}` and `{}` would share the report folder `{}`",
                    dir.display(),
                    student.name,
                    student.file_stem()
                ));
            }
        }
        Ok(students)
    }

    /// A single submission folder, as Gradescope gives one: the student is
    /// named after the folder.
    pub fn one(dir: &Path) -> Student {
        let absolute = std::path::absolute(dir).unwrap_or_else(|_| dir.to_path_buf());
        let name = absolute.file_name().map_or_else(|| "submission".into(), |n| n.to_string_lossy().into_owned());
        Student { name, dir: dir.to_path_buf() }
    }

    pub fn file_stem(&self) -> String {
        file_stem_of(&self.name)
    }
}

/// A student's outcomes, one per case in the suite's order.
#[derive(Debug, Clone, PartialEq)]
pub struct Grades {
    pub student: Student,
    pub outcomes: Vec<Outcome>,
}

impl Grades {
    pub fn total(&self) -> Points {
        let points = self.outcomes.iter().filter_map(|o| o.points);
        Points { earned: points.clone().map(|p| p.earned).sum(), possible: points.map(|p| p.possible).sum() }
    }
}

/// A case's reference as made once for the run.
struct Prepared {
    image: Result<ReferenceImage, String>,
    /// The render settings in words, or the reference file's size.
    settings: Option<String>,
    file: (&'static str, PathBuf),
}

enum ReferenceImage {
    /// A render as it reads back from a PNG or PPM, and from a float file, made once
    /// for every student.
    Rendered { png: LinearImage, float: LinearImage },
    Read(LinearImage),
}

impl ReferenceImage {
    fn rendered(image: &Image) -> ReferenceImage {
        ReferenceImage::Rendered { png: LinearImage::from_render(image, Format::Png), float: LinearImage::from_render(image, Format::Exr) }
    }

    /// A render is compared as it reads back in the submission's format.
    fn linear(&self, format: Format) -> &LinearImage {
        match self {
            ReferenceImage::Rendered { png, float } => if format.is_display() { png } else { float },
            ReferenceImage::Read(image) => image,
        }
    }
}

/// The cases whose reference is a scene, which need a renderer.
pub fn needs_renderer(cases: &[&GradedCase]) -> bool {
    cases.iter().any(|c| matches!(c.reference, Reference::Scene(_)))
}

/// Grades every student on every case, handing each student's grades to
/// `on_grades` as soon as they are known. `renderer` may be `None` when no
/// case's reference is a scene. Also returns one line for each reference
/// that could not be made (every student's outcome of that case is an error).
pub fn grade(
    cases: &[&GradedCase],
    renderer: Option<&Renderer>,
    students: &[Student],
    report_images: bool,
    on_grades: &mut dyn FnMut(&Grades),
) -> (Vec<Grades>, Vec<String>) {
    let prepared: Vec<Prepared> = cases.iter().map(|case| prepare(case, renderer)).collect();
    let errors = cases
        .iter()
        .zip(&prepared)
        .filter_map(|(case, p)| p.image.as_ref().err().map(|e| format!("case `{}`: reference: {e}", case.name)))
        .collect();
    let grades = students
        .iter()
        .map(|student| {
            let outcomes = cases.iter().zip(&prepared).map(|(case, p)| grade_one(case, p, student, report_images)).collect();
            let grades = Grades { student: student.clone(), outcomes };
            on_grades(&grades);
            grades
        })
        .collect();
    (grades, errors)
}

fn prepare(case: &GradedCase, renderer: Option<&Renderer>) -> Prepared {
    match &case.reference {
        Reference::Scene(scene) => {
            let rendered = renderer
                .ok_or_else(|| "no renderer".to_string())
                .and_then(|renderer| render(renderer, scene, &case.render));
            let (image, settings) = match rendered {
                Ok(Rendered { image, settings }) => (Ok(ReferenceImage::rendered(&image)), Some(settings)),
                Err(e) => (Err(e), None),
            };
            Prepared { image, settings, file: ("reference scene", scene.clone()) }
        }
        Reference::File(file) => {
            let read = image_io::read(file).map_err(|e| e.to_string());
            let settings = read.as_ref().ok().map(|r| format!("reference image, {}x{}", r.width, r.height));
            Prepared { image: read.map(ReferenceImage::Read), settings, file: ("reference", file.clone()) }
        }
    }
}

fn grade_one(case: &GradedCase, prepared: &Prepared, student: &Student, report_images: bool) -> Outcome {
    let image = student.dir.join(case.image.replace(STUDENT_PLACEHOLDER, &student.name));
    let mut outcome = Outcome {
        name: case.name.clone(),
        file_stem: case.file_stem(),
        files: vec![(ROLES.tested, image.clone()), prepared.file.clone()],
        settings: prepared.settings.clone(),
        status: Status::Error,
        detail: String::new(),
        points: Some(Points { earned: 0.0, possible: case.scoring.points }),
        images: None,
    };
    let reference = match &prepared.image {
        Ok(reference) => reference,
        Err(e) => {
            outcome.detail = format!("the reference could not be made: {e}");
            return outcome;
        }
    };
    if !image.exists() {
        outcome.status = Status::NoImage;
        outcome.detail = format!("no image: {} is missing", image.display());
        return outcome;
    }
    let submitted = match image_io::read(&image) {
        Ok(submitted) => submitted,
        Err(e) => {
            outcome.detail = e.to_string();
            return outcome;
        }
    };
    let format = image_io::format_of(&image).expect("a read image has a known format");
    let comparison = compare(reference.linear(format), &submitted, &case.criteria, ROLES, report_images);
    outcome.status = if comparison.passed() { Status::Passed } else { Status::Mismatch };
    outcome.points = Some(Points { earned: case.scoring.earned(comparison.verdict.as_ref()), possible: case.scoring.points });
    outcome.detail = comparison.detail;
    outcome.images = comparison.images;
    outcome
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn students_are_the_folders_in_name_order() {
        let dir = tempfile::tempdir().unwrap();
        for folder in ["zoe", "ann", ".git"] {
            std::fs::create_dir(dir.path().join(folder)).unwrap();
        }
        std::fs::write(dir.path().join("notes.txt"), "").unwrap();
        let names: Vec<String> = Student::all_in(dir.path()).unwrap().into_iter().map(|s| s.name).collect();
        assert_eq!(names, ["ann", "zoe"]);
        assert_eq!(Student::one(&dir.path().join("zoe")).name, "zoe");
        for folder in ["ann lee", "ann-a", "ann_lee"] {
            std::fs::create_dir(dir.path().join(folder)).unwrap();
        }
        let e = Student::all_in(dir.path()).unwrap_err();
        assert!(e.ends_with("students `ann lee` and `ann_lee` would share the report folder `ann_lee`"), "{e}");
        let empty = tempfile::tempdir().unwrap();
        assert!(Student::all_in(empty.path()).unwrap_err().ends_with("no student folders in the submissions directory (one folder per student)"));
    }
}
