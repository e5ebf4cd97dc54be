//! `glint compare A B`: how far image B is from reference A, by FLIP, PSNR,
//! RMSE and the largest difference, judged by one of them.

use std::path::{Path, PathBuf};

use clap::{Args, ValueEnum};
use glint_golden::{number, percent, Criteria, Measurement, Metric, Verdict};

use crate::{exit, Failure};

#[derive(Args)]
pub struct CompareArgs {
    /// The reference image: .png (read as sRGB), .exr or .pfm (linear)
    reference: PathBuf,
    /// The image checked against it, of the same size
    test: PathBuf,
    /// The metric that decides
    #[arg(long, value_enum, default_value_t = MetricArg::Flip)]
    metric: MetricArg,
    /// The metric's limit: a maximum, for psnr a minimum in dB [default: 0.01; psnr: 40]
    #[arg(long, value_parser = finite)]
    threshold: Option<f64>,
    /// A pixel whose own error exceeds this is counted (its FLIP, or else its
    /// largest channel difference) [default: flip 0.2, else 0.01]
    #[arg(long, value_parser = non_negative)]
    pixel_tolerance: Option<f64>,
    /// At most this fraction of pixels may exceed the pixel tolerance
    /// [default: flip 0.005, else no limit]
    #[arg(long, value_parser = fraction)]
    max_bad_fraction: Option<f64>,
    /// Write a false-colour map of each pixel's error, with a legend
    #[arg(long, value_name = "DIFF.png", value_parser = png_path)]
    diff: Option<PathBuf>,
    /// Print one JSON object on stdout
    #[arg(long)]
    json: bool,
}

#[derive(Clone, Copy, ValueEnum)]
enum MetricArg {
    Flip,
    Psnr,
    Rmse,
    Max,
}

fn finite(s: &str) -> Result<f64, String> {
    s.parse::<f64>().ok().filter(|v| v.is_finite()).ok_or_else(|| format!("`{s}` is not a finite number"))
}

fn non_negative(s: &str) -> Result<f64, String> {
    finite(s).ok().filter(|v| *v >= 0.0).ok_or_else(|| format!("`{s}` is not a number >= 0"))
}

fn fraction(s: &str) -> Result<f64, String> {
    finite(s).ok().filter(|v| (0.0..=1.0).contains(v)).ok_or_else(|| format!("`{s}` is not a fraction in [0, 1]"))
}

fn png_path(s: &str) -> Result<PathBuf, String> {
    let path = PathBuf::from(s);
    match glint_golden::format_of(&path) {
        Some(glint_gpu::Format::Png) => Ok(path),
        _ => Err(format!("{s}: the diff map is written as .png")),
    }
}

pub fn run(args: &CompareArgs) -> Result<(), Failure> {
    let metric = match args.metric {
        MetricArg::Flip => Metric::Flip,
        MetricArg::Psnr => Metric::Psnr,
        MetricArg::Rmse => Metric::Rmse,
        MetricArg::Max => Metric::Max,
    };
    let defaults = Criteria::for_metric(metric);
    let criteria = Criteria {
        metric,
        threshold: args.threshold.unwrap_or(defaults.threshold),
        pixel_tolerance: args.pixel_tolerance.unwrap_or(defaults.pixel_tolerance),
        max_bad_fraction: args.max_bad_fraction.or(defaults.max_bad_fraction),
    };
    let read = |path: &Path| glint_golden::read(path).map_err(|e| Failure::new(exit::INPUT, e));
    let (reference, test) = (read(&args.reference)?, read(&args.test)?);
    let measurement = glint_golden::measure(&reference, &test).map_err(|e| {
        Failure::new(
            exit::INPUT,
            format!(
                "{}: the image is {}x{}, but the reference {} is {}x{}",
                args.test.display(),
                e.test.0,
                e.test.1,
                args.reference.display(),
                e.reference.0,
                e.reference.1
            ),
        )
    })?;
    let verdict = glint_golden::judge(&measurement, &criteria);
    if let Some(path) = &args.diff {
        let map = glint_golden::diff_map(&measurement, metric);
        let bytes = glint_golden::encode_png(&map);
        glint_gpu::write_atomically(path, &bytes).map_err(|e| Failure::new(exit::OUTPUT, format!("{}: cannot write: {e}", path.display())))?;
    }
    if args.json {
        println!("{}", json(args, &measurement, &verdict));
    } else {
        print_text(&measurement, &verdict);
    }
    if verdict.passed() { Ok(()) } else { Err(Failure::explained(exit::DIFFERENT)) }
}

fn print_text(m: &Measurement, v: &Verdict) {
    let c = &v.criteria;
    println!("size         {}x{}", m.width, m.height);
    for metric in Metric::ALL {
        let value = number(m.value(metric));
        let unit = if metric == Metric::Psnr { " dB" } else { "" };
        let judged = if metric == c.metric {
            let relation = if metric.higher_is_better() { ">=" } else { "<=" };
            format!(" (threshold {relation} {}: {})", c.threshold, if v.within_threshold() { "pass" } else { "fail" })
        } else {
            String::new()
        };
        println!("{:<12} {value}{unit}{judged}", metric.name());
    }
    let judged = if v.within_bad_fraction() { "pass" } else { "fail" };
    let limit = c.max_bad_fraction.map(|f| format!(", at most {}: {judged}", percent(f))).unwrap_or_default();
    println!(
        "{:<12} {} of {} pixels ({}{limit})",
        format!("above {}", c.pixel_tolerance),
        v.pixels_above,
        v.pixels,
        percent(v.fraction_above())
    );
    let error_kind = if c.metric == Metric::Flip { "FLIP error" } else { "difference" };
    println!("worst pixel  ({}, {}), {error_kind} {}", v.worst.x, v.worst.y, number(f64::from(v.worst.error)));
    println!("{}", if v.passed() { "within threshold" } else { "not within threshold" });
}

fn json(args: &CompareArgs, m: &Measurement, v: &Verdict) -> serde_json::Value {
    let c = &v.criteria;
    // JSON has no infinity: the PSNR of identical images is null.
    serde_json::json!({
        "reference": args.reference.display().to_string(),
        "test": args.test.display().to_string(),
        "width": m.width,
        "height": m.height,
        "flip": m.flip,
        "psnr": m.psnr,
        "rmse": m.rmse,
        "max": m.max,
        "metric": c.metric.name(),
        "threshold": c.threshold,
        "pixel_tolerance": c.pixel_tolerance,
        "max_bad_fraction": c.max_bad_fraction,
        "pixels_above": v.pixels_above,
        "fraction_above": v.fraction_above(),
        "worst": { "x": v.worst.x, "y": v.worst.y, "error": v.worst.error },
        "pass": v.passed(),
        "diff": args.diff.as_ref().map(|p| p.display().to_string()),
    })
}
