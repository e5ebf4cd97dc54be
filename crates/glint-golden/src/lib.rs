//! Golden-image testing, behind `glint compare` and `glint test` and Glint's
//! own golden suite: reading images into linear RGB, the metrics (FLIP, PSNR,
//! RMSE, max), false-colour error maps, manifests of cases, the runner that
//! renders, compares and blesses, and its JUnit XML and HTML reports.

pub mod case_render;
pub mod criteria;
pub mod diff_map;
mod font;
pub mod html;
pub mod image_io;
pub mod junit;
pub mod manifest;
mod markup;
pub mod metrics;
pub mod runner;
pub mod settings;

pub use criteria::{judge, Criteria, Verdict, Worst};
pub use diff_map::diff_map;
pub use html::write_report;
pub use image_io::{read, LinearImage, ReadError};
pub use junit::junit_xml;
pub use manifest::{Case, Suite};
pub use metrics::{measure, Measurement, Metric, SizeMismatch};
pub use runner::{run, Bless, Outcome, RunOptions, Status, Summary};
