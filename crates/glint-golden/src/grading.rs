//! Grading images Glint did not render: each student's submitted image of a
//! case, held against the case's reference (a scene Glint renders, or a
//! file) by the case's criteria, and scored. Each reference is made once per
//! run, however many students there are; a student's missing, unreadable or
//! wrongly sized image is that case's verdict, and the run goes on.

use std::cell::OnceCell;
use std::path::{Path, PathBuf};

use glint_gpu::{Format, Image, Renderer};

use crate::case_render::{render, Rendered};
use crate::comparison::{compare, Roles, DIFF_ROLE};
use crate::diagnosis::{diagnose, variants, Variant};
use crate::image_io::{self, LinearImage};
use crate::manifest::{file_stem_of, GradedCase, Reference};
use crate::runner::{Outcome, Points, Status};
use crate::settings::ViewName;
use crate::submission_folder::{is_not_work, look_alike};

/// What `image` may hold in its path: the student's folder name.
pub const STUDENT_PLACEHOLDER: &str = "{student}";

const ROLES: Roles = Roles { reference: "reference", tested: "submission" };

/// One student's folder of submitted images.
#[derive(Debug, Clone, PartialEq)]
pub struct Student {
    /// The folder's name.
    pub name: String,
    pub dir: PathBuf,
    /// The student's folder in a report: the name made safe for a file name,
    /// and unique in the class.
    pub report_folder: String,
}

impl Student {
    /// Every folder in `dir`, sorted by name, each a student; hidden ones
    /// (`.git`) and archivers' (`__MACOSX`) are not.
    pub fn all_in(dir: &Path) -> Result<Vec<Student>, String> {
        let cannot = |e: std::io::Error| format!("{}: cannot read the submissions directory: {e}", dir.display());
        let mut folders = Vec::new();
        for entry in std::fs::read_dir(dir).map_err(cannot)? {
            let path = entry.map_err(cannot)?.path();
            let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
            if path.is_dir() && !is_not_work(&name) {
                folders.push((name, path));
            }
        }
        if folders.is_empty() {
            return Err(format!("{}: no student folders in the submissions directory (one folder per student)", dir.display()));
        }
        folders.sort();
        let report_folders = unique_report_folders(folders.iter().map(|(name, _)| name.as_str()));
        Ok(folders.into_iter().zip(report_folders).map(|((name, dir), report_folder)| Student { name, dir, report_folder }).collect())
    }

    /// A single submission folder, as Gradescope gives one: the student is
    /// named after the folder.
    pub fn one(dir: &Path) -> Student {
        let absolute = std::path::absolute(dir).unwrap_or_else(|_| dir.to_path_buf());
        let name: String = absolute.file_name().map_or_else(|| "submission".into(), |n| n.to_string_lossy().into_owned());
        Student { report_folder: file_stem_of(&name), name, dir: dir.to_path_buf() }
    }
}

/// A report folder for each name, in order: the name made safe for a file
/// name; where two names would share one (`a b`, `a_b`), a name already safe
/// keeps it and the others get `-2`, `-3`…
fn unique_report_folders<'a>(names: impl Iterator<Item = &'a str> + Clone) -> Vec<String> {
    let mut taken: std::collections::HashSet<String> = names.clone().filter(|n| file_stem_of(n) == *n).map(String::from).collect();
    names
        .map(|name| {
            let stem = file_stem_of(name);
            if stem == name {
                return stem;
            }
            let folder = std::iter::once(stem.clone()).chain((2..).map(|k| format!("{stem}-{k}"))).find(|f| !taken.contains(f)).expect("an unbounded list");
            taken.insert(folder.clone());
            folder
        })
        .collect()
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
    /// The scene's variants with one effect changed, rendered at the first
    /// submission that fails (`diagnosis.rs`); none for a reference file.
    variants: OnceCell<Vec<Variant>>,
    /// The render settings in words, or the reference file's size.
    settings: Option<String>,
    file: (&'static str, PathBuf),
}

enum ReferenceImage {
    /// A render as it reads back from a PNG or PPM, and from a float file, made once
    /// for every student.
    Rendered { image: Image, png: LinearImage, float: LinearImage },
    Read(LinearImage),
}

impl ReferenceImage {
    fn rendered(image: &Image) -> ReferenceImage {
        ReferenceImage::Rendered { image: image.clone(), png: LinearImage::from_render(image, Format::Png), float: LinearImage::from_render(image, Format::Exr) }
    }

    /// A render is compared as it reads back in the submission's format.
    fn linear(&self, format: Format) -> &LinearImage {
        match self {
            ReferenceImage::Rendered { png, float, .. } => if format.is_display() { png } else { float },
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
            let outcomes = cases.iter().zip(&prepared).map(|(case, p)| grade_one(case, p, renderer, student, report_images)).collect();
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
            Prepared { image, variants: OnceCell::new(), settings, file: ("reference scene", scene.clone()) }
        }
        Reference::File(file) => {
            let read = image_io::read(file).map_err(|e| e.to_string());
            let settings = read.as_ref().ok().map(|r| format!("reference image, {}x{}", r.width, r.height));
            Prepared { image: read.map(ReferenceImage::Read), variants: OnceCell::new(), settings, file: ("reference", file.clone()) }
        }
    }
}

fn grade_one(case: &GradedCase, prepared: &Prepared, renderer: Option<&Renderer>, student: &Student, report_images: bool) -> Outcome {
    let relative = case.image.replace(STUDENT_PLACEHOLDER, &student.name);
    let image = student.dir.join(&relative);
    let mut outcome = Outcome {
        name: case.name.clone(),
        file_stem: case.file_stem(),
        files: vec![(ROLES.tested, image.clone()), prepared.file.clone()],
        settings: prepared.settings.clone(),
        status: Status::Error,
        detail: String::new(),
        points: Some(Points { earned: 0.0, possible: case.scoring.points }),
        images: None,
        diagnosis: None,
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
        if let Some(found) = look_alike(&student.dir, Path::new(&relative)) {
            outcome.detail += &format!("; did you mean {found}?");
        }
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
    let passed = comparison.passed();
    outcome.status = if passed { Status::Passed } else { Status::Mismatch };
    let award = case.scoring.award(comparison.verdict.as_ref());
    outcome.points = Some(Points { earned: award.points, possible: case.scoring.points });
    outcome.detail = comparison.detail;
    outcome.images = comparison.images;
    // A failing image says which band, if any, its points came from, then
    // what it most likely got wrong, and its diff map shows where.
    if !passed && comparison.verdict.is_some() {
        if !case.scoring.partial.is_empty() {
            outcome.detail += &match award.band {
                Some(band) => format!("; partial credit: {}", band.conditions(&case.criteria)),
                None => "; no partial-credit band holds".to_string(),
            };
        }
        let variants = prepared.variants.get_or_init(|| diagnosis_variants(case, reference, renderer));
        if let Some(diagnosis) = diagnose(&submitted, format, reference.linear(format), variants) {
            if let Some(images) = &mut outcome.images {
                images.outline(DIFF_ROLE, diagnosis.region);
            }
            outcome.diagnose(diagnosis);
        }
    }
    outcome
}

/// The case's variants for diagnosis: a rendered scene's, or none. A variant
/// that cannot be rendered only loses the diagnosis, not the grade.
fn diagnosis_variants(case: &GradedCase, reference: &ReferenceImage, renderer: Option<&Renderer>) -> Vec<Variant> {
    match (&case.reference, reference, renderer) {
        (Reference::Scene(scene), ReferenceImage::Rendered { image, .. }, Some(renderer)) if case.render.view.is_none_or(|v| v == ViewName::Shaded) => {
            variants(renderer, scene, &case.render, image).unwrap_or_default()
        }
        _ => Vec::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn students_are_the_folders_in_name_order() {
        let dir = tempfile::tempdir().unwrap();
        for folder in ["zoe", "ann", ".git", "__MACOSX"] {
            std::fs::create_dir(dir.path().join(folder)).unwrap();
        }
        std::fs::write(dir.path().join("notes.txt"), "").unwrap();
        let names: Vec<String> = Student::all_in(dir.path()).unwrap().into_iter().map(|s| s.name).collect();
        assert_eq!(names, ["ann", "zoe"]);
        assert_eq!(Student::one(&dir.path().join("zoe")).name, "zoe");
        let empty = tempfile::tempdir().unwrap();
        assert!(Student::all_in(empty.path()).unwrap_err().ends_with("no student folders in the submissions directory (one folder per student)"));
    }

    #[test]
    fn students_whose_names_collide_get_their_own_report_folders() {
        let dir = tempfile::tempdir().unwrap();
        for folder in ["ann lee", "ann-a", "ann_lee", "ann:lee", "bo b", "bo_b-2"] {
            std::fs::create_dir(dir.path().join(folder)).unwrap();
        }
        let folders: Vec<(String, String)> = Student::all_in(dir.path()).unwrap().into_iter().map(|s| (s.name, s.report_folder)).collect();
        let expected = [("ann lee", "ann_lee-2"), ("ann-a", "ann-a"), ("ann:lee", "ann_lee-3"), ("ann_lee", "ann_lee"), ("bo b", "bo_b"), ("bo_b-2", "bo_b-2")];
        assert_eq!(folders, expected.map(|(a, b)| (a.to_string(), b.to_string())));
    }
}
