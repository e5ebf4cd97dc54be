//! `glint`: render scenes on the GPU from the command line.

mod bench;
mod bench_cold;
mod check;
mod compare;
mod effects;
mod frames;
mod grade;
mod info;
mod kernels;
mod paint;
mod probe;
mod probe_observer;
mod legend;
mod render;
mod scene_arg;
mod spd;
mod stitch;
mod test;
mod view;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// Exit codes, documented in README.md.
pub mod exit {
    /// `glint compare`: the images are not within the threshold; `glint
    /// test`: a case failed.
    pub const DIFFERENT: u8 = 1;
    /// The command line was wrong (clap's own code).
    pub const USAGE: u8 = 2;
    /// A scene file could not be read or is malformed; `glint stitch`: a part
    /// cannot be read or the parts do not make one image.
    pub const INPUT: u8 = 3;
    /// No usable GPU, or the GPU failed.
    pub const GPU: u8 = 4;
    /// The output file could not be written.
    pub const OUTPUT: u8 = 5;
    /// `glint view`: there is no display to open a window on.
    pub const NO_DISPLAY: u8 = 6;
}

#[derive(Parser)]
#[command(name = "glint", version, about = "A GPU Whitted-style ray tracer")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Render a scene to an image file.
    Render(render::RenderArgs),
    /// Check scene files without a GPU: parse, validate and summarise them.
    Check(check::CheckArgs),
    /// Show the GPU adapter Glint would use, its limits and the choices made for it.
    Info,
    /// Write the WGSL each kernel is given, one file per kernel and tuning.
    Kernels(kernels::KernelsArgs),
    /// Measure BVH build, render times and ray throughput per scene.
    Bench(bench::BenchArgs),
    /// Open a scene in the interactive viewer.
    View(view::ViewArgs),
    /// Write one of the Standard Procedural Databases as an NFF file.
    Spd(spd::SpdArgs),
    /// Follow one pixel's rays: the camera frame and the whole ray tree with every term it adds
    /// (with --observer, also drawn in 3-D as seen from outside, into a PNG).
    Probe(probe::ProbeArgs),
    /// Compare two images (.png, .ppm, .exr, .pfm) by FLIP, PSNR, RMSE or largest difference.
    Compare(compare::CompareArgs),
    /// Render a suite of scenes and compare each with its golden image, or grade students' images.
    Test(test::TestArgs),
    /// Assemble the parts of an image rendered with --region or --shard.
    Stitch(stitch::StitchArgs),
}

/// An error with the exit code it maps to.
pub struct Failure {
    pub code: u8,
    pub message: String,
}

impl Failure {
    pub fn new(code: u8, message: impl std::fmt::Display) -> Self {
        Self { code, message: message.to_string() }
    }

    /// A failure the command has already reported on stdout (a comparison
    /// that did not pass), so only the exit code remains.
    pub fn explained(code: u8) -> Self {
        Self { code, message: String::new() }
    }
}

impl From<glint_gpu::GpuError> for Failure {
    fn from(e: glint_gpu::GpuError) -> Self {
        let code = match e {
            glint_gpu::GpuError::Output(_) => exit::OUTPUT,
            glint_gpu::GpuError::Invalid(_) => exit::INPUT,
            // GLINT_PROFILE names no profile: a usage error.
            glint_gpu::GpuError::Profile(_) => exit::USAGE,
            _ => exit::GPU,
        };
        Failure::new(code, e)
    }
}

/// A renderer on the GPU (a software adapter without one), after any driver warning.
fn renderer() -> Result<glint_gpu::Renderer, Failure> {
    let gpu = glint_gpu::Gpu::new()?;
    if let Some(warning) = gpu.driver_warning() {
        eprintln!("glint: {warning}");
    }
    Ok(glint_gpu::Renderer::new(gpu.device.clone(), gpu.queue.clone(), &glint_gpu::shaders::ShaderSource::Embedded)?)
}

fn main() -> ExitCode {
    // A closed stdout (`glint compare A B | head -1`) ends a command as it
    // ends `cat`: quietly, by SIGPIPE. Rust ignores the signal, which turns
    // the next print into a panic.
    #[cfg(unix)]
    // SAFETY: no thread has been started yet, and SIG_DFL is a valid handler.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        // --help and --version print in full.
        Err(e) if !e.use_stderr() => {
            let _ = e.print();
            return ExitCode::SUCCESS;
        }
        // A usage error in full, as clap explains it (what is missing, the
        // allowed values, a similar name), starting `glint:` like every failure.
        Err(e) => {
            let text = e.to_string();
            eprint!("glint: {}", text.strip_prefix("error: ").unwrap_or(&text));
            return ExitCode::from(exit::USAGE);
        }
    };
    let result = match cli.command {
        Command::Render(args) => render::run(&args),
        Command::Check(args) => check::run(&args),
        Command::Info => info::run(),
        Command::Kernels(args) => kernels::run(&args),
        Command::Bench(args) => bench::run(&args),
        Command::View(args) => view::run(args),
        Command::Spd(args) => spd::run(&args),
        Command::Probe(args) => probe::run(&args),
        Command::Compare(args) => compare::run(&args),
        Command::Test(args) => test::run(&args),
        Command::Stitch(args) => stitch::run(&args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(f) => {
            if !f.message.is_empty() {
                eprintln!("glint: {}", f.message);
            }
            ExitCode::from(f.code)
        }
    }
}
