//! Golden-image testing, behind `glint compare` and `glint test` and Glint's
//! own golden suite: reading images into linear RGB, the metrics (FLIP, PSNR,
//! RMSE, max), false-colour error maps, manifests of cases, the runner that
//! renders, compares and blesses, and its JUnit XML and HTML reports.

mod case_render;
mod criteria;
mod diff_map;
mod font;
mod html;
mod image_io;
mod junit;
mod manifest;
mod markup;
mod metrics;
mod runner;
mod settings;

pub use criteria::{judge, number, percent, Criteria, Verdict, Worst};
pub use diff_map::diff_map;
pub use html::write_report;
pub use image_io::{encode_png, format_of, read, LinearImage, ReadError};
pub use junit::junit_xml;
pub use manifest::{Case, Suite};
pub use metrics::{measure, Measurement, Metric, SizeMismatch};
pub use runner::{run, Bless, Outcome, RunOptions, Status, Summary};
