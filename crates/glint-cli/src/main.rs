//! `glint`: render scenes on the GPU from the command line.

mod bench;
mod info;
mod render;
mod scene_arg;
mod spd;
mod view;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// Exit codes, documented in README.md.
pub mod exit {
    /// The command line was wrong (clap's own code).
    pub const USAGE: u8 = 2;
    /// A scene file could not be read or is malformed.
    pub const INPUT: u8 = 3;
    /// No usable GPU, or the GPU failed.
    pub const GPU: u8 = 4;
    /// The output file could not be written.
    pub const OUTPUT: u8 = 5;
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
    /// Show the GPU adapter Glint would use and its limits.
    Info,
    /// Measure BVH build, render times and ray throughput per scene.
    Bench(bench::BenchArgs),
    /// Open a scene in the interactive viewer.
    View(view::ViewArgs),
    /// Write one of the Standard Procedural Databases as an NFF file.
    Spd(spd::SpdArgs),
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
}

impl From<glint_gpu::GpuError> for Failure {
    fn from(e: glint_gpu::GpuError) -> Self {
        let code = match e {
            glint_gpu::GpuError::Output(_) => exit::OUTPUT,
            glint_gpu::GpuError::Invalid(_) => exit::INPUT,
            _ => exit::GPU,
        };
        Failure::new(code, e)
    }
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        // --help and --version print in full; a usage error is one line, like
        // every other failure.
        Err(e) if !e.use_stderr() => {
            let _ = e.print();
            return ExitCode::SUCCESS;
        }
        Err(e) => {
            let text = e.to_string();
            let first = text.lines().next().unwrap_or_default();
            eprintln!("glint: {}", first.strip_prefix("error: ").unwrap_or(first));
            return ExitCode::from(exit::USAGE);
        }
    };
    let result = match cli.command {
        Command::Render(args) => render::run(&args),
        Command::Info => info::run(),
        Command::Bench(args) => bench::run(&args),
        Command::View(args) => view::run(args),
        Command::Spd(args) => spd::run(&args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(f) => {
            eprintln!("glint: {}", f.message);
            ExitCode::from(f.code)
        }
    }
}
