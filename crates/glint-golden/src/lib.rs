//! Golden-image testing, behind `glint compare` and `glint test` and Glint's
//! own golden suite: reading images into linear RGB, the metrics (FLIP, PSNR,
//! RMSE, max), false-colour error maps, manifests of cases, the runner that
//! renders, compares and blesses, and its JUnit XML and HTML reports; and
//! grading students' own images against references, with points, Gradescope
//! results and a class summary.

mod case_render;
mod class_report;
mod comparison;
mod criteria;
mod diagnosis;
mod diff_map;
mod font;
mod gradescope;
mod grading;
mod html;
mod image_io;
mod junit;
mod manifest;
mod markup;
mod metrics;
mod region;
mod runner;
mod scoring;
mod settings;
mod submission_folder;

pub use class_report::{remove_former_students, write_class_report};
pub use comparison::{Png, ReportImages};
pub use criteria::{judge, number, percent, Criteria, Verdict, Worst};
pub use diagnosis::{Diagnosis, Effect};
pub use diff_map::diff_map;
pub use gradescope::results_json;
pub use grading::{grade, needs_renderer, Grades, Student};
pub use html::{points_text, write_report};
pub use image_io::{encode_png, format_of, read, LinearImage, ReadError};
pub use junit::{junit_xml, junit_xml_suites};
pub use manifest::{Case, GradedCase, Reference, Suite};
pub use metrics::{measure, Measurement, Metric, SizeMismatch};
pub use region::Region;
pub use runner::{run, Bless, Outcome, Points, RunOptions, Status, Summary};
pub use settings::Visibility;
