//! `glint spd`: write one of the Standard Procedural Databases as NFF or
//! Rayshade text.

use std::io::Write;
use std::path::PathBuf;

use clap::{Args, ValueEnum};
use glint_scene::spd::Format;

use crate::{exit, Failure};

#[derive(Args)]
pub struct SpdArgs {
    /// Database: balls, gears, mount, rings, teapot, tetra, tree, jacks, shells, lattice, sombrero, nurbtst
    #[arg(value_parser = database)]
    name: &'static glint_scene::spd::Database,
    /// Size (default: the database's classic benchmark size)
    #[arg(short, long)]
    size: Option<u32>,
    /// Output .nff or .ray file (default: standard output)
    #[arg(short, long)]
    output: Option<PathBuf>,
    /// Output format, as SPD's `-r 1` or `-r 8` (default: rayshade for a .ray output, else nff)
    #[arg(long, value_enum)]
    format: Option<FormatArg>,
}

#[derive(Clone, Copy, ValueEnum)]
enum FormatArg {
    Nff,
    Rayshade,
}

impl SpdArgs {
    fn format(&self) -> Format {
        let by_extension = || {
            let ext = self.output.as_deref()?.extension()?.to_str()?;
            ext.eq_ignore_ascii_case("ray").then_some(Format::Rayshade)
        };
        match self.format {
            Some(FormatArg::Nff) => Format::Nff,
            Some(FormatArg::Rayshade) => Format::Rayshade,
            None => by_extension().unwrap_or(Format::Nff),
        }
    }
}

fn database(name: &str) -> Result<&'static glint_scene::spd::Database, String> {
    glint_scene::spd::database(name).map_err(|e| e.to_string())
}

pub fn run(args: &SpdArgs) -> Result<(), Failure> {
    let text = args.name.generate_as(args.size, args.format()).map_err(|e| Failure::new(exit::USAGE, e))?;
    match &args.output {
        Some(path) => glint_gpu::write_atomically(path, text.as_bytes())
            .map_err(|e| Failure::new(exit::OUTPUT, format!("{}: {e}", path.display()))),
        None => std::io::stdout()
            .lock()
            .write_all(text.as_bytes())
            .map_err(|e| Failure::new(exit::OUTPUT, format!("standard output: {e}"))),
    }
}
